#pragma once
/// @file
/// A decision's settings as a user gives them, in words and numbers: what the CLI's options
/// (apps/vantage/commands/options.hpp) and Python's keyword arguments fill, and the one builder
/// of a PlannerConfig from them that both call.

#include <stdexcept>
#include <string>

#include "vantage/gain/ray_model.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/types.hpp"

namespace vantage {

/// A setting the builder refused; setting() is its name as the settings spell it (`search`,
/// `alpha`, ...), what() says what was wrong.
class SettingError : public std::invalid_argument {
 public:
  SettingError(std::string setting, const std::string& message)
      : std::invalid_argument(message), setting_(std::move(setting)) {}
  const std::string& setting() const { return setting_; }

 private:
  std::string setting_;
};

/// The settings; each empty text means "the method's own" (or the search's default).
struct PlanningSettings {
  /// A method's name (parse_planner_method); empty: the default one for `task`, and for
  /// whether the robot's pose is known (default_planner_method).
  std::string method;
  ViewTask task = ViewTask::kObjects;
  bool knows_pose = true;
  std::string alpha;      ///< a number, "auto", or empty: the caller's literal default
  std::string objective;  ///< bits, cells, or empty: the method's own (natural_objective)
  std::string evaluation = "auto";
  /// swept, pruned, exhaustive, or empty: the fastest that serves the method (resolve_decider)
  std::string search;
  double epsilon = GainConfig{}.epsilon;
  double lambda = PlannerConfig{}.lambda;                 ///< [1/m]
  int threads = 0;                                        ///< 0 = all cores
  int horizon = SequenceConfig{}.horizon;                 ///< the sequence's K
  double travel_weight = SequenceConfig{}.travel_weight;  ///< [1/m]
  int shortlist = SequenceConfig{}.shortlist;             ///< [views]
  int sample = 1;                               ///< the sequence's values on one cell in N
  int swept_rays = PlannerConfig{}.swept_rays;  ///< the swept search's rays across a view

  /// The method named, or the default one (`method` empty); throws SettingError.
  PlannerMethod planner_method() const;
  /// `alpha` as a setting; without it `literal` (the scene kind's a), also auto's prior. Throws
  /// SettingError.
  AlphaSetting alpha_setting(double literal = kTableTopAlpha) const;
  /// The decision's settings, validated, the search resolved against the method: a search that
  /// does not serve it is refused naming those that do. Under alpha auto, gain.alpha is the fit's
  /// prior. Throws SettingError naming the setting.
  PlannerConfig planner_config(double literal_alpha = kTableTopAlpha) const;
};

/// What `vantage plan` and Python's plan ask for beside the decision: greedy's count on every
/// candidate (the reference of the paper's Fig. 11), except after a swept search or a sequence,
/// where it would cost more than the decision itself.
void request_plan_reference(PlannerConfig& config);

}  // namespace vantage
