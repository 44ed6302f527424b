#pragma once
/// @file
/// The next-best-view decision: score every candidate by a method, choose the best (eq. 1).
/// Every method of the paper — its own and the baselines — goes through this one interface.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "vantage/gain/view_gain.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/sequence.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How the next view is chosen.
enum class PlannerMethod {
  kProbabilistic,  ///< highest expected gain under the paper's visibility model
  kSurvival,       ///< the same under the survival reading of it (gain/survival.hpp)
  kGreedy,         ///< highest simple-greedy gain (infinite visibility)
  kRandom,         ///< a uniformly random candidate, seeded
  kLatombe,        ///< González-Baños & Latombe: greedy gain * exp(-lambda * travel)
  kYamauchi,       ///< the candidate nearest by travel distance
  // The highest value of one of the field's volumetric metrics (vantage/gain/metrics.hpp).
  kOcclusionAware,
  kUnobservedVoxel,
  kRearSideVoxel,
  kRearSideEntropy,
  kProximityCount,
  kAverageEntropy,
  kAreaFactor,
  /// Plans past the next scan (sequence.hpp, docs/decision.md "Planning a sequence"): the
  /// survival reading's expected cells, the views that jointly see the most toured from the
  /// current pose, PlannerConfig::sequence, or kSequenceDefaults when that plans one view.
  kSequence,
};

std::string_view to_string(PlannerMethod method);
/// Whether the method predicts with the survival reading of the visibility (survival, sequence):
/// its a is a chance per unobserved cell, fitted online by default, and it ranks by cells.
bool uses_survival_reading(PlannerMethod method);
/// Parses probabilistic, greedy, random, latombe, yamauchi or a metric's name (as GainMethod's);
/// throws std::invalid_argument.
PlannerMethod parse_planner_method(std::string_view name);
/// The gain method a planner method scores by: probabilistic, survival, a metric, or greedy for
/// the rest.
GainMethod gain_method_of(PlannerMethod method);
/// Whether the method predicts with a visibility model of parameter a (probabilistic, survival):
/// it takes --alpha (auto too) and --objective, and reports its expected cells seen.
bool has_observability(PlannerMethod method);

/// What the probabilistic method maximises over the candidates.
enum class GainObjective {
  kBits,   ///< the expected information gain of eq. (1), ViewGain::gain [bits]
  kCells,  ///< the expected number of unobserved cells seen, ViewGain::cells [cells]
};

std::string_view to_string(GainObjective objective);
/// Parses "bits" or "cells"; throws std::invalid_argument naming the value.
GainObjective parse_gain_objective(std::string_view name);
/// What a method ranks by when not told: the survival reading its expected cells seen (what its
/// a is fitted to), the paper's method the information gain of eq. (1).
GainObjective natural_objective(PlannerMethod method);

/// How the probabilistic method searches the candidates for the best (docs/decision.md).
enum class DecisionSearch {
  kExhaustive,  ///< every candidate evaluated in full (gain.evaluation)
  /// Sampled estimates drop the candidates that cannot win; the rest are evaluated in full and
  /// the best of them is chosen. Plan::gains of a dropped candidate is its estimate.
  /// Statistical: it may miss the best candidate (docs/decision.md).
  kScreened,
  /// Upper bounds from the map's block summary order the candidates; they are evaluated exactly
  /// best bound first until no bound left can beat the best score. The exhaustive exact search's
  /// choice, proven; Plan::gains of a candidate never evaluated is its bound. Survival,
  /// probabilistic, greedy and Latombe; the others search exhaustively.
  kPruned,
  /// Every candidate ranked by its unbiased estimate on one hashed sample of the unobserved
  /// cells (1 in 2^PlannerConfig::sample_bits, the same cells for every view); the chosen one is
  /// then evaluated in full for its report. Statistical and without a guarantee: near-ties go
  /// either way (docs/decision.md). For candidate sets of hundreds of views. Survival,
  /// probabilistic, greedy and Latombe; the others search exhaustively.
  kSampled,
  /// Every candidate ranked by the swept estimate (vantage/gain/swept.hpp: a thousand rays cast
  /// outward a view, each crediting the volume it sweeps through unobserved cells); the leaders
  /// cast again at twice the rays a side, and the leaders of that raced on samples of their cells
  /// up to all of them (race.hpp); the winner is then evaluated in full for its report.
  /// Statistical and without a guarantee (docs/decision.md), for decisions in milliseconds.
  /// Survival (by cells), greedy and Latombe; the paper's model by cells, every candidate raced
  /// on its exact per-target v_M (no sweep: docs/decision.md "The paper's model"); the others
  /// search exhaustively.
  kSwept,
};

std::string_view to_string(DecisionSearch search);
/// Parses "exhaustive", "screened", "pruned", "sampled" or "swept"; throws std::invalid_argument
/// naming the value.
DecisionSearch parse_decision_search(std::string_view name);

/// Settings of the decision.
struct PlannerConfig {
  PlannerMethod method = PlannerMethod::kProbabilistic;
  /// What the probabilistic and survival methods rank by; the others count cells whatever it
  /// says.
  GainObjective objective = GainObjective::kBits;
  /// Gain evaluation settings; `gain.method` is set from `method` (gain_method_of).
  GainConfig gain;
  double lambda = 0.5;  ///< kLatombe's travel penalty [1/m]
  /// How the probabilistic and survival methods search the candidates; the others evaluate all.
  DecisionSearch search = DecisionSearch::kExhaustive;
  /// The sampled search's rate: one unobserved cell in 2^sample_bits, in [0, 16].
  int sample_bits = 4;
  /// The swept search's rays across a view's image (SweptConfig::rays_across), in [1, 4096].
  int swept_rays = 32;
  /// Also predict every candidate's greedy gain when the method uses another, so predictions can
  /// be compared on the same poses (the paper's Fig. 11).
  bool greedy_reference = false;
  /// Plan a sequence of views and take its tour's first (sequence.hpp) when active (horizon > 1
  /// or a travel weight); survival (ranking by cells) and greedy only. It evaluates exactly and
  /// ignores `search`.
  SequenceConfig sequence;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// A candidate view and what it costs to get there.
struct Candidate {
  Frustum view;
  double travel = 0.0;    ///< travel distance from the robot [m]; 0 where motion is free
  bool reachable = true;  ///< false: the robot can only get close (the paper's fallback)
  /// Further views from the same place (the other steps of an office stop's 360° sweep): the
  /// candidate's gains and score are sums over `view` and these.
  std::vector<Frustum> more_views = {};
};

/// The decision and everything behind it.
struct Plan {
  std::size_t best = 0;         ///< index of the chosen candidate
  std::vector<ViewGain> gains;  ///< each candidate's predicted gain under the method's model
  /// Per candidate: true where `gains` is the screen's sampling estimate, not a full evaluation
  /// (DecisionSearch::kScreened); empty for an exhaustive search.
  std::vector<bool> estimated;
  std::vector<double> greedy_gains;  ///< each candidate's greedy gain (when requested or used)
  std::vector<double> scores;        ///< what was maximised
  double seconds = 0.0;              ///< wall time of the decision [s]
  /// ... of which evaluating the greedy reference (PlannerConfig::greedy_reference), which the
  /// decision itself does not need [s]
  double reference_seconds = 0.0;
  /// The pruned search: the chosen candidate's full prediction (gain in bits beside the cells
  /// the survival reading ranks by), evaluated after the decision and not part of `seconds` [s]
  double prediction_seconds = 0.0;
  std::size_t evaluated = 0;  ///< candidates evaluated in full (all but the estimated ones)
  /// True when only the chosen candidate's ViewGain::gain is a prediction: a decision by the
  /// expected cells seen (the survival reading's pruned search, the swept search but for
  /// greedy's counts) computes no gain in bits for the others and leaves it 0.
  bool bits_of_chosen_only = false;
  /// PlannerConfig::sequence: the planned views in the tour's order (`best` first), its length
  /// from the current pose [m] and the views' joint expected cells seen [cells]; else empty, 0.
  std::vector<std::size_t> sequence;
  double tour_length = 0.0;
  double sequence_value = 0.0;
};

/// The sequence the decision plans: `config.sequence`, with kSequenceDefaults' horizon and
/// travel weight for PlannerMethod::kSequence when it plans one view.
SequenceConfig sequence_of(const PlannerConfig& config);

/// Scores the candidates and chooses one. Ties go to the lower index; kRandom uses `seed` and
/// takes the candidate of a uniformly random view (uniform over candidates of as many views).
/// Throws std::invalid_argument when there are no candidates.
Plan plan_next_view(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                    const PlannerConfig& config, std::uint64_t seed = 0);

}  // namespace vantage
