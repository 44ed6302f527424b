#pragma once
/// @file
/// Options that several subcommands share (explore, bench, plan): how to choose a view and how
/// to build the map.

#include <CLI/CLI.hpp>
#include <string>

#include "vantage/gain/ray_model.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::cli {

/// Help of --no-stop-projection (explore and bench office).
inline constexpr const char* kNoStopProjectionHelp =
    "keep the paper's fallback for a frontier centroid the robot cannot reach (drive as close "
    "as possible, section 5.3.1) instead of moving it to its region's nearest reachable cell";

/// --method, --alpha, --objective, --evaluation, --epsilon, --lambda, --threads.
struct PlanningOptions {
  std::string method = "probabilistic";
  std::string alpha;  ///< a number, "auto", or empty: the caller's literal default
  std::string objective = "bits";
  std::string evaluation = "auto";
  double epsilon = GainConfig{}.epsilon;
  double lambda = PlannerConfig{}.lambda;
  int threads = 0;

  void add_to(CLI::App& cmd);
  /// --alpha as a setting; without it `literal` (the scene kind's a), which is also auto's prior.
  /// Throws std::invalid_argument naming the bad option.
  AlphaSetting alpha_setting(double literal = kTableTopAlpha) const;
  /// Throws std::invalid_argument naming the bad option. Under --alpha auto, gain.alpha is the
  /// fit's prior.
  PlannerConfig planner_config(double literal_alpha = kTableTopAlpha) const;
};

/// --integration, --no-icp, --no-segmentation, --no-hole-filling.
struct MappingOptions {
  std::string integration = "paper";
  bool icp = true;
  bool segmentation = true;
  bool hole_filling = true;

  void add_to(CLI::App& cmd);
  /// The scene's defaults with the options applied (segmentation only where the scene has a
  /// table).
  MapperConfig mapper_config(const sim::Scene& scene) const;
};

}  // namespace vantage::cli
