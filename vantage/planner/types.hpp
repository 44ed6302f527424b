#pragma once
/// @file
/// The planner's shared types, at the bottom of its layer: what a decision is asked (the method,
/// what it ranks by, the search, PlannerConfig), what it chooses among (Candidate) and what it
/// returns (Plan). Nothing above them is needed to include this file; docs/architecture.md.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/planner/sequence_config.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How a gain is turned into a choice: the ways to rank any gain model's views.
enum class Ranking {
  kBest,     ///< the highest score
  kTravel,   ///< González-Baños & Latombe: the score times exp(-lambda * travel)
  kNearest,  ///< Yamauchi: the candidate nearest by travel; of those, the one that sees most
  kRandom,   ///< a uniformly random candidate, seeded
  /// Plans past the next scan (sequence.hpp, docs/decision.md "Planning a sequence"): the views
  /// that jointly see the most toured from the current pose, PlannerConfig::sequence, or
  /// kSequenceDefaults when that plans one view.
  kSequence,
};

/// How the next view is chosen: a gain model (GainMethod, whose registry names it) ranked one
/// way. Named as the CLI names it: a gain method's own name ranks it best; `latombe`,
/// `yamauchi` and `random` rank greedy's count, `sequence` the survival reading's cells; any
/// other pair is RANKING+GAIN, such as `latombe+survival`.
struct PlannerMethod {
  GainMethod gain = GainMethod::kProbabilistic;
  Ranking ranking = Ranking::kBest;

  static const PlannerMethod kProbabilistic, kSurvival, kGreedy, kRandom, kLatombe, kYamauchi,
      kSequence;
  friend bool operator==(const PlannerMethod&, const PlannerMethod&) = default;
};
inline constexpr PlannerMethod PlannerMethod::kProbabilistic{GainMethod::kProbabilistic};
inline constexpr PlannerMethod PlannerMethod::kSurvival{GainMethod::kSurvival};
inline constexpr PlannerMethod PlannerMethod::kGreedy{GainMethod::kGreedy};
inline constexpr PlannerMethod PlannerMethod::kRandom{GainMethod::kGreedy, Ranking::kRandom};
inline constexpr PlannerMethod PlannerMethod::kLatombe{GainMethod::kGreedy, Ranking::kTravel};
inline constexpr PlannerMethod PlannerMethod::kYamauchi{GainMethod::kGreedy, Ranking::kNearest};
inline constexpr PlannerMethod PlannerMethod::kSequence{GainMethod::kSurvival, Ranking::kSequence};

std::string to_string(PlannerMethod method);

/// What the views are for, which picks the planner a user gets when naming none.
enum class ViewTask {
  kObjects,      ///< see the objects on a table: views around them (ring, sphere, hemisphere)
  kExploration,  ///< explore a building: stops at its frontiers (the office)
};

/// The planner a user gets when naming none (explore, bench tabletop, plan, Python). Around
/// objects, `latombe+surface`: the surface model ranked by Latombe's travel discount, the best by
/// scan-point coverage and travel on the ring and the hemisphere over 54 table tops (RESULTS.md,
/// "The surface model"); without the robot's pose there is no travel to weigh, and it is
/// `surface`. Exploring a building, `survival`: the surface model credits only cells near the
/// surface already known, and ranked by travel it keeps the robot near it, leaving more of the
/// building unknown (three offices, 3 stops: docs/decision.md, "The default planner").
PlannerMethod default_planner_method(ViewTask task, bool knows_pose);
/// Whether the method predicts with the survival reading of the visibility (survival, sequence):
/// its a is a chance per unobserved cell, fitted online by default, and it ranks by cells.
bool uses_survival_reading(PlannerMethod method);
/// Parses a gain method's name, latombe, yamauchi, random, sequence or RANKING+GAIN; throws
/// std::invalid_argument naming the value and the names there are.
PlannerMethod parse_planner_method(std::string_view name);
/// Whether the method predicts with a visibility model of parameter a (probabilistic, survival):
/// it takes --alpha (auto too) and --objective, and reports its expected cells seen.
bool has_observability(PlannerMethod method);
/// Whether a sequence (sequence.hpp) plans with the gain model `gain`: one whose value in cells
/// is read off the cells' classes (survival, greedy), or a metric credited cell by cell with the
/// chance of the surface it adds (the surface model), so that what two views would see twice is
/// counted once.
bool plans_sequences(GainMethod gain);
/// Whether the method ranks candidates by a gain (not random or Yamauchi's nearest).
bool ranks_by_gain(PlannerMethod method);
/// Whether the method weighs travel, so a decision needs the robot's pose (Latombe, Yamauchi).
bool uses_travel(PlannerMethod method);

/// What a method ranks by when not told: the survival reading its expected cells seen (what its
/// a is fitted to), the paper's method the information gain of eq. (1).
GainObjective natural_objective(PlannerMethod method);

/// The swept search's tolerance: its choice is within this share of the best candidate's exact
/// score (at three standard errors of its race's samples; docs/decision.md, "The swept search"),
/// so that two views that nearly tie do not drive its race to the full lists. On the Kinect table
/// top at 1.85 M cells two ring views lie 0.069 % apart, and telling them apart took the race to
/// one cell in two (BENCHMARK.md, issue 38); 0.5 % is far below the survival reading's own error
/// in predicting a scan's cells (a median of 14 %, RESULTS.md, "The sweep with every method").
/// The exact argmax, proven, is the pruned search's.
inline constexpr double kSweptTolerance = 0.005;

/// How the candidates are searched for the best (vantage/planner/searches/, docs/decision.md): a
/// search by the name its file registers (search.hpp), so that adding one takes its file and one
/// registry row. The three built in are named here.
struct DecisionSearch {
  std::string_view name;

  /// Every candidate ranked by rays cast outward; the leaders raced on nested samples of their
  /// cells up to all of them (searches/swept.cpp). Milliseconds; the exhaustive exact choice in
  /// every oracle state, not proven.
  static const DecisionSearch kSwept;
  /// Exact evaluations in the order of upper bounds from the map's blocks, until no bound left
  /// can beat the best (searches/pruned.cpp): the exhaustive exact choice, proven.
  static const DecisionSearch kPruned;
  /// Every candidate evaluated in full (searches/exhaustive.cpp): the reference.
  static const DecisionSearch kExhaustive;

  friend bool operator==(const DecisionSearch&, const DecisionSearch&) = default;
};
inline constexpr DecisionSearch DecisionSearch::kSwept{"swept"};
inline constexpr DecisionSearch DecisionSearch::kPruned{"pruned"};
inline constexpr DecisionSearch DecisionSearch::kExhaustive{"exhaustive"};

/// The search's name.
inline std::string_view to_string(DecisionSearch search) { return search.name; }
/// The registered search named `name` ("swept", "pruned", "exhaustive", ...); throws
/// std::invalid_argument naming the value and the searches there are.
DecisionSearch parse_decision_search(std::string_view name);

/// Settings of the decision.
struct PlannerConfig {
  PlannerMethod method = PlannerMethod::kProbabilistic;
  /// What the probabilistic and survival methods rank by; the others count cells whatever it
  /// says.
  GainObjective objective = GainObjective::kBits;
  /// Gain evaluation settings; `gain.method` is set from `method.gain`.
  GainConfig gain;
  double lambda = 0.5;  ///< kLatombe's travel penalty [1/m]
  /// The search; none: the fastest that serves the method (resolve_decider, search.hpp). A
  /// search named here that does not serve the method is refused by resolve_decider, which
  /// plan_next_view calls, naming the searches that do.
  std::optional<DecisionSearch> search;
  /// The swept search's rays across a view's image (SweptConfig::rays_across), in [1, 4096].
  int swept_rays = 32;
  /// Also predict greedy's gain when the method uses another, so predictions can be compared on
  /// the same poses (the paper's Fig. 11): every candidate's in plan_next_view; in an exploration
  /// (ExplorationConfig::planner), the view taken's only, after the decision, since on the early
  /// scans even that costs more than the decision (docs/decision.md, "Greedy's reference
  /// prediction").
  bool greedy_reference = false;
  /// After a decision on estimates, bounds or cells, evaluate the chosen candidate in full: its
  /// gain in bits beside its exact cells (Plan::prediction_seconds). That walks every target of
  /// the view with the occupancy filter, and on a large grid takes longer than the decision (at
  /// 1.85 M cells 1.5-2.5 s against ~1 s: BENCHMARK.md, issue 38). False leaves it out of the
  /// decision's path: the chosen candidate keeps the search's own figures (its exact cells when
  /// the search reached them, Plan::is_estimate otherwise) and no gain in bits
  /// (Plan::bits_predicted); full_prediction (search.hpp) gives them after, off the robot's loop.
  bool predict_chosen = true;
  /// Predict every candidate's gain, an estimate at least: none is left at an upper bound because
  /// its travel puts it out of the choice (the swept search's first round ranked by travel,
  /// docs/decision.md "The swept search"). A stop on the best predicted gain of any candidate
  /// (ExplorationConfig::min_gain) reads them all; the choice is the same either way.
  bool gain_of_every_candidate = false;
  /// Plan a sequence of views and take its tour's first (sequence.hpp) when active (horizon > 1
  /// or a travel weight); survival (ranking by cells) and greedy only. It evaluates every
  /// candidate exactly (or on its own sample, SequenceConfig::sample_bits): no search serves it.
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
  std::size_t best = 0;  ///< index of the chosen candidate
  /// The search that decided (for a sequence: kExhaustive, its exact evaluation).
  DecisionSearch search = DecisionSearch::kExhaustive;
  std::vector<ViewGain> gains;  ///< each candidate's predicted gain under the method's model
  /// Per candidate: true where `gains` and `scores` are the search's estimate (swept), upper
  /// bound (pruned, or swept for a candidate its travel proved out) or, for the rankings that do
  /// not rank by a gain (random, Yamauchi's nearest), 0 for a candidate they could not choose; not
  /// a full evaluation. Empty when every candidate was evaluated in full.
  std::vector<bool> estimated;
  std::vector<double> greedy_gains;  ///< each candidate's greedy gain (when requested or used)
  std::vector<double> scores;        ///< what was maximised
  double seconds = 0.0;              ///< wall time of the decision [s]
  /// ... of which evaluating the greedy reference (PlannerConfig::greedy_reference), which the
  /// decision itself does not need [s]
  double reference_seconds = 0.0;
  /// A search that decided on estimates or bounds: the chosen candidate's full prediction (gain
  /// in bits beside the cells), evaluated after the decision and not part of `seconds` [s]
  double prediction_seconds = 0.0;
  std::size_t evaluated = 0;  ///< candidates evaluated in full (all but the estimated ones)
  /// True when only the chosen candidate's ViewGain::gain is a prediction: a decision by the
  /// expected cells seen (the survival reading's pruned search, the swept search but for
  /// greedy's counts) computes no gain in bits for the others and leaves it 0.
  bool bits_of_chosen_only = false;
  /// False when not even the chosen candidate's gain in bits was predicted
  /// (PlannerConfig::predict_chosen false after a decision by cells): every ViewGain::gain is 0.
  bool bits_predicted = true;
  /// PlannerConfig::sequence: the planned views in the tour's order (`best` first), its length
  /// from the current pose [m] and the views' joint expected cells seen [cells]; else empty, 0.
  std::vector<std::size_t> sequence;
  double tour_length = 0.0;
  double sequence_value = 0.0;

  /// Whether candidate c's gains and score are an estimate or a bound, not a full evaluation.
  bool is_estimate(std::size_t c) const { return c < estimated.size() && estimated[c]; }
  /// The candidates, the chosen one first, then those evaluated in full by score, then the
  /// estimated ones by score (ties: the lower index), so that no estimate is listed above the
  /// choice it lost to.
  std::vector<std::size_t> ranking() const;
};

/// The sequence the decision plans: `config.sequence`, with kSequenceDefaults' horizon and
/// travel weight for PlannerMethod::kSequence when it plans one view.
SequenceConfig sequence_of(const PlannerConfig& config);
/// Which quantity the decision computes and ranks by: the registry's row of the method's gain
/// model read with the objective (MethodTraits::quantity). Every search asks it.
GainQuantity decision_quantity(const PlannerConfig& config);

}  // namespace vantage
