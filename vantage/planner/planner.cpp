#include "vantage/planner/planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/hierarchy.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/swept.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/prune.hpp"
#include "vantage/planner/race.hpp"
#include "vantage/planner/screen.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Every candidate's views in one list; candidate c's are [first[c], first[c + 1]).
struct Views {
  std::vector<Frustum> frusta;
  std::vector<std::size_t> first;

  Views() = default;
  explicit Views(std::span<const Candidate> candidates) {
    for (const Candidate& c : candidates) {
      first.push_back(frusta.size());
      frusta.push_back(c.view);
      frusta.insert(frusta.end(), c.more_views.begin(), c.more_views.end());
    }
    first.push_back(frusta.size());
  }

  /// The views of candidates `among`, in that order.
  Views subset(const std::vector<std::size_t>& among) const {
    Views out;
    for (const std::size_t c : among) {
      out.first.push_back(out.frusta.size());
      out.frusta.insert(out.frusta.end(), frusta.begin() + static_cast<std::ptrdiff_t>(first[c]),
                        frusta.begin() + static_cast<std::ptrdiff_t>(first[c + 1]));
    }
    out.first.push_back(out.frusta.size());
    return out;
  }

  /// The candidate whose views hold view `v`.
  std::size_t candidate_of(std::size_t v) const {
    return static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), v) -
                                    first.begin()) -
           1;
  }

  /// Per-view values summed per candidate.
  std::vector<double> sums(const std::vector<double>& per_view) const {
    std::vector<double> out(first.size() - 1, 0.0);
    for (std::size_t c = 0; c + 1 < first.size(); ++c) {
      for (std::size_t v = first[c]; v < first[c + 1]; ++v) out[c] += per_view[v];
    }
    return out;
  }
};

/// Each view's value under `method` (in bits or in cells, as `objective` says), and with
/// `per_candidate` each candidate's summed gains.
std::vector<double> gains_of(const OccupancyGrid& grid, const Views& views, GainConfig config,
                             GainMethod method, GainObjective objective,
                             std::vector<ViewGain>* per_candidate = nullptr) {
  config.method = method;
  const std::vector<ViewGain> gains = evaluate_views(grid, views.frusta, config);
  std::vector<double> values;
  values.reserve(gains.size());
  // NOTE: greedy's gain is its count of cells; only the probabilistic method's differ.
  const bool cells = objective == GainObjective::kCells && method_traits(method).has_objective;
  for (const ViewGain& g : gains) values.push_back(cells ? g.cells : g.gain);
  if (per_candidate != nullptr) {
    per_candidate->assign(views.first.size() - 1, ViewGain{});
    for (std::size_t v = 0; v < gains.size(); ++v) {
      ViewGain& sum = (*per_candidate)[views.candidate_of(v)];
      sum.gain += gains[v].gain;
      sum.cells += gains[v].cells;
      sum.targets += gains[v].targets;
    }
  }
  return values;
}

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Greedy's count on the candidates' poses, the reference of the other methods' predictions
/// (Fig. 11), and its time.
void add_greedy_reference(const OccupancyGrid& grid, const Views& views, const GainConfig& gain,
                          Plan& plan) {
  const auto start = std::chrono::steady_clock::now();
  plan.greedy_gains =
      views.sums(gains_of(grid, views, gain, GainMethod::kGreedy, GainObjective::kCells));
  plan.reference_seconds = since(start);
}

/// What Latombe multiplies a candidate's gain by, exp(-lambda * travel); 1 for the others.
double travel_factor(const PlannerConfig& config, const Candidate& candidate) {
  return config.method == PlannerMethod::kLatombe ? std::exp(-config.lambda * candidate.travel)
                                                  : 1.0;
}

/// A counting method's gains are greedy's: the plan's greedy reference costs nothing.
void gains_as_greedy_reference(Plan& plan) {
  plan.greedy_gains.clear();
  for (const ViewGain& g : plan.gains) plan.greedy_gains.push_back(g.gain);
}

/// Candidate `c`'s exact prediction: its views' gains under `gain.method`, summed.
ViewGain full_prediction(const OccupancyGrid& grid, const Views& views, std::size_t c,
                         const GainConfig& gain) {
  const std::span<const Frustum> chosen(views.frusta.data() + views.first[c],
                                        views.first[c + 1] - views.first[c]);
  ViewGain full;
  for (const ViewGain& g : exact_view_gains(grid, chosen, gain)) {
    full.gain += g.gain;
    full.cells += g.cells;
    full.targets += g.targets;
  }
  return full;
}

/// What a search that decided on estimates reports: the chosen candidate's exact prediction,
/// after the decision and not part of its time (it is also what an online fit of a compares with
/// the scan's outcome), and greedy's reference.
void report_choice(const OccupancyGrid& grid, const Views& views, const PlannerConfig& config,
                   const GainConfig& gain, Plan& plan) {
  const auto predict_start = std::chrono::steady_clock::now();
  plan.gains[plan.best] = full_prediction(grid, views, plan.best, gain);
  plan.estimated[plan.best] = false;
  plan.prediction_seconds = since(predict_start);
  if (config.greedy_reference && !method_traits(gain.method).counts) {
    add_greedy_reference(grid, views, config.gain, plan);
    plan.seconds += plan.reference_seconds;  // as the other searches count it
  } else if (method_traits(gain.method).counts) {
    gains_as_greedy_reference(plan);
  }
}

/// Whether the sampled search serves the method: a target model with sampled estimates, or
/// Latombe's weighting of greedy's.
bool samplable(PlannerMethod method) {
  return method != PlannerMethod::kRandom && method != PlannerMethod::kYamauchi &&
         method_traits(gain_method_of(method)).sampled;
}

/// The sampled search (screen.hpp, sample_candidates): every candidate ranked by its estimate on
/// one hashed sample of the unobserved cells; the chosen one's exact prediction after.
Plan plan_sampled(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                  const Views& views, const PlannerConfig& config,
                  std::chrono::steady_clock::time_point start) {
  GainConfig gain = config.gain;
  gain.method = gain_method_of(config.method);
  const bool cells =
      config.objective == GainObjective::kCells || !method_traits(gain.method).has_objective;
  detail::Screening sampled =
      detail::sample_candidates(grid, views.frusta, views.first, gain, config.sample_bits);
  Plan plan;
  plan.gains = std::move(sampled.gains);
  plan.estimated = std::move(sampled.estimated);
  for (std::size_t c = 0; c < plan.gains.size(); ++c) {
    const double value = cells ? plan.gains[c].cells : plan.gains[c].gain;
    plan.scores.push_back(value * travel_factor(config, candidates[c]));
  }
  plan.best = choose_best(plan.scores);
  plan.seconds = since(start);
  plan.evaluated = 1;
  report_choice(grid, views, config, gain, plan);
  return plan;
}

/// What the swept search estimates for the method, if it serves it: the survival reading's
/// expected cells seen (when it ranks by cells) or greedy's count (greedy, Latombe).
std::optional<CountRule> swept_rule(const PlannerConfig& config) {
  if (config.method == PlannerMethod::kRandom || config.method == PlannerMethod::kYamauchi) {
    return std::nullopt;
  }
  switch (method_traits(gain_method_of(config.method)).ray) {
    case TargetRay::kUnblocked:
      return CountRule::kGreedy;
    case TargetRay::kSurvival:
      if (config.objective == GainObjective::kCells) return CountRule::kSurvivalCells;
      break;
    case TargetRay::kPaper:
    case TargetRay::kNone:
      break;
  }
  return std::nullopt;
}

/// Whether the swept search serves the method by the paper's model: it races every candidate on
/// the model's exact v_M (plan_swept_paper). Only when it ranks by cells: a target's gain in bits
/// can sit in a few cells a sample misses (docs/decision.md, "The paper's model").
bool swept_paper(const PlannerConfig& config) {
  return config.method != PlannerMethod::kRandom && config.method != PlannerMethod::kYamauchi &&
         method_traits(gain_method_of(config.method)).ray == TargetRay::kPaper &&
         config.objective == GainObjective::kCells;
}

bool sweepable(const PlannerConfig& config) {
  return swept_rule(config).has_value() || swept_paper(config);
}

/// The swept search's rounds (docs/decision.md, "The swept search"): how many candidates the
/// second round casts again at twice the rays a side, and how many of those, within what part of
/// the leader's estimate, the third races on samples of their cells.
constexpr std::size_t kSweptSecond = 12;
constexpr std::size_t kSweptFinal = 3;
constexpr double kSweptMargin = 0.15;
/// The most unobserved cells the race's first sample is expected to hold, whatever the map holds,
/// so that its cost does not grow with the cells.
constexpr std::size_t kSweptSample = std::size_t{1} << 13;

/// The candidates among `among` whose scores lie within `margin` of the best of them, the best
/// `keep` of those (ties to the lower index), in descending order of score.
std::vector<std::size_t> leaders(const std::vector<double>& scores,
                                 const std::vector<std::size_t>& among, std::size_t keep,
                                 double margin) {
  std::vector<std::size_t> order = among;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  if (order.size() > keep) order.resize(keep);
  const double lead = order.empty() ? 0.0 : scores[order.front()];
  std::erase_if(order, [&](std::size_t c) { return scores[c] < (1.0 - margin) * lead; });
  return order;
}

/// Ends a swept search on its race between the candidates `raced` (ascending), by cells: their
/// last scores and the winner into the plan, the decision's time, and the winner's exact
/// prediction after.
void finish_race(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                 const Views& views, const PlannerConfig& config, const GainConfig& gain,
                 std::chrono::steady_clock::time_point start, const std::vector<std::size_t>& raced,
                 const std::vector<double>& factor, const detail::Race& race, Plan& plan) {
  for (std::size_t k = 0; k < raced.size(); ++k) {
    const std::size_t c = raced[k];
    plan.scores[c] = race.scores[k];
    // NOTE: every race is by cells; a counting method's gain is its count.
    plan.gains[c].cells = race.scores[k] / factor[k];
    plan.gains[c].gain = method_traits(gain.method).counts ? plan.gains[c].cells : 0.0;
  }
  plan.best = raced[race.winner];
  plan.evaluated = raced.size();
  plan.bits_of_chosen_only = !method_traits(gain.method).counts;
  plan.seconds = since(start);
  report_choice(grid, views, config, gain, plan);
  plan.scores[plan.best] =
      plan.gains[plan.best].cells * travel_factor(config, candidates[plan.best]);
}

/// The paper's race starts every candidate on a sample of about kSweptSample * kSweptFinal / n
/// unobserved cells (at least kPaperLeastSample), so that its first round costs about what the
/// three finalists' first round does in the other race.
constexpr std::size_t kPaperLeastSample = 512;
std::size_t paper_first_sample(std::size_t candidates) {
  return std::max(kPaperLeastSample,
                  kSweptSample * kSweptFinal / std::max<std::size_t>(candidates, 1));
}

/// The swept search under the paper's model: no ray sweeps a volume (the model's state in a cell
/// depends on the cell's own ray, and a ray carried past it predicts it several-fold off near
/// frontiers, docs/fast-gain.md "The replay"), so every candidate enters the race, on the model's
/// exact per-target v_M [cells].
Plan plan_swept_paper(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                      const Views& views, const PlannerConfig& config,
                      std::chrono::steady_clock::time_point start) {
  GainConfig gain = config.gain;
  gain.method = gain_method_of(config.method);
  const GainMap map(grid, gain.num_threads);
  Plan plan;
  plan.gains.assign(candidates.size(), ViewGain{});
  plan.estimated.assign(candidates.size(), true);
  plan.scores.assign(candidates.size(), 0.0);
  std::vector<std::size_t> all(candidates.size());
  std::vector<double> factor;
  for (std::size_t c = 0; c < all.size(); ++c) {
    all[c] = c;
    factor.push_back(travel_factor(config, candidates[c]));
  }
  const detail::Race race = detail::race_candidates(
      unobserved_by_sample(ClassMap(grid), paper_first_sample(candidates.size())), views.frusta,
      views.first, factor,
      [&](std::span<const Frustum> raced, std::span<const std::uint32_t> cells) {
        return paper_view_cells(map, raced, gain, cells);
      });
  finish_race(grid, candidates, views, config, gain, start, all, factor, race, plan);
  return plan;
}

/// The swept search: every candidate's swept estimate; the leaders cast again at twice the rays;
/// the leaders of that raced (race.hpp); the chosen one's exact prediction after.
Plan plan_swept(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                const Views& views, const PlannerConfig& config,
                std::chrono::steady_clock::time_point start) {
  if (swept_paper(config)) return plan_swept_paper(grid, candidates, views, config, start);
  GainConfig gain = config.gain;
  gain.method = gain_method_of(config.method);
  // NOTE: the grid's own classes and census, no snapshot: the swept rays and the race read
  // classes only.
  const ClassMap map(grid);
  SweptConfig swept;
  swept.alpha = gain.alpha;
  swept.epsilon = gain.epsilon;
  swept.num_threads = gain.num_threads;
  Plan plan;
  plan.gains.assign(candidates.size(), ViewGain{});
  plan.estimated.assign(candidates.size(), true);
  plan.scores.assign(candidates.size(), 0.0);
  // Candidates `among` estimated at `rays` across, into the plan's gains and scores.
  const auto estimate = [&](const std::vector<std::size_t>& among, int rays) {
    const Views subset = views.subset(among);
    swept.rays_across = rays;
    const std::vector<double> per_view =
        swept_view_counts(map, subset.frusta, *swept_rule(config), swept);
    const std::vector<double> sums = subset.sums(per_view);
    for (std::size_t k = 0; k < among.size(); ++k) {
      const std::size_t c = among[k];
      plan.gains[c].cells = sums[k];
      plan.gains[c].gain = method_traits(gain.method).counts ? sums[k] : 0.0;
      plan.scores[c] = sums[k] * travel_factor(config, candidates[c]);
    }
  };
  std::vector<std::size_t> all(candidates.size());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = c;
  estimate(all, config.swept_rays);
  const std::vector<std::size_t> second = leaders(plan.scores, all, kSweptSecond, 1.0);
  estimate(second, std::min(2 * config.swept_rays, 4096));
  // NOTE: the last round races the leaders on samples of the targets, whose values are exact:
  // the swept estimate is not, it weighs a cell by the part of its volume the rays reach where
  // the exact sum asks whether its centre is reached.
  std::vector<std::size_t> final_round = leaders(plan.scores, second, kSweptFinal, kSweptMargin);
  // NOTE: in candidate order, so that an exact tie on the full lists goes to the lower index, as
  // in the exhaustive search.
  std::sort(final_round.begin(), final_round.end());
  const Views finalists = views.subset(final_round);
  std::vector<double> factor;
  for (const std::size_t c : final_round) factor.push_back(travel_factor(config, candidates[c]));
  const detail::Race race =
      detail::race_candidates(map, finalists.frusta, finalists.first, factor, gain, kSweptSample);
  finish_race(grid, candidates, views, config, gain, start, final_round, factor, race, plan);
  return plan;
}

/// Whether the pruned search serves the method (PlannerConfig::search): a target model (its
/// per-target values are what prune.hpp bounds), or Latombe's weighting of greedy's.
bool prunable(PlannerMethod method) {
  return method != PlannerMethod::kRandom && method != PlannerMethod::kYamauchi &&
         method_traits(gain_method_of(method)).ray != TargetRay::kNone;
}

/// The pruned search (prune.hpp) and, for the candidate it chooses, the full prediction.
Plan plan_pruned(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                 const Views& views, const PlannerConfig& config,
                 std::chrono::steady_clock::time_point start) {
  GainConfig gain = config.gain;
  gain.method = gain_method_of(config.method);
  const bool counts = method_traits(gain.method).counts;
  // NOTE: what the method ranks by decides the score; the paper's model's cells have no
  // reachability to prune by (its visibility never reaches 0).
  detail::PrunedScore score = detail::PrunedScore::kBits;
  if (counts) {
    score = detail::PrunedScore::kGreedy;
  } else if (config.objective == GainObjective::kCells) {
    score = config.method == PlannerMethod::kSurvival ? detail::PrunedScore::kSurvivalCells
                                                      : detail::PrunedScore::kModelCells;
  }
  std::vector<double> factor;
  if (config.method == PlannerMethod::kLatombe) {
    for (const Candidate& c : candidates) factor.push_back(travel_factor(config, c));
  }
  detail::Pruning pruning =
      detail::prune_candidates(grid, views.frusta, views.first, factor, gain, score);
  Plan plan;
  plan.best = pruning.best;
  plan.gains = std::move(pruning.gains);
  plan.estimated = std::move(pruning.estimated);
  plan.scores = std::move(pruning.scores);
  plan.evaluated = pruning.evaluated;
  plan.bits_of_chosen_only = score == detail::PrunedScore::kSurvivalCells;
  if (counts) gains_as_greedy_reference(plan);
  plan.seconds = since(start);
  if (score == detail::PrunedScore::kSurvivalCells) {
    // NOTE: the cells decided; the bits of eq. (4) are the chosen view's report, not the choice.
    const auto predict_start = std::chrono::steady_clock::now();
    plan.gains[plan.best] = full_prediction(grid, views, plan.best, gain);
    plan.prediction_seconds = since(predict_start);
  }
  if (config.greedy_reference && !counts) {
    add_greedy_reference(grid, views, config.gain, plan);
    plan.seconds += plan.reference_seconds;  // as the other searches count it
  }
  return plan;
}

/// The sequence decision (sequence.hpp): the tour's first view, and for it the full prediction.
Plan plan_by_sequence(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                      const PlannerConfig& config, std::chrono::steady_clock::time_point start) {
  std::vector<Frustum> views;
  std::vector<double> travel;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!candidates[c].more_views.empty()) {
      throw std::invalid_argument(cat("planner.sequence plans single views; candidate ", c,
                                      " is a sweep of ", candidates[c].more_views.size() + 1,
                                      " views"));
    }
    views.push_back(candidates[c].view);
    travel.push_back(candidates[c].travel);
  }
  GainConfig gain = config.gain;
  gain.method = gain_method_of(config.method);
  SequencePlan sequence = plan_sequence(grid, views, travel, gain, sequence_of(config));
  Plan plan;
  plan.best = sequence.first;
  plan.gains = std::move(sequence.gains);
  plan.scores = std::move(sequence.scores);
  plan.evaluated = candidates.size();
  plan.sequence = std::move(sequence.tour);
  plan.tour_length = sequence.tour_length;
  plan.sequence_value = sequence.value;
  const bool counts = method_traits(gain.method).counts;
  const bool sampled = sequence_of(config).sample_bits > 0;
  if (sampled) plan.estimated.assign(plan.gains.size(), true);
  if (counts) gains_as_greedy_reference(plan);
  plan.seconds = since(start);
  if (!counts || sampled) {
    // NOTE: the cells decided; the bits of eq. (4) are the chosen view's report (as pruned).
    const auto predict_start = std::chrono::steady_clock::now();
    plan.gains[plan.best] = exact_view_gain(grid, views[plan.best], gain);
    plan.prediction_seconds = since(predict_start);
    if (sampled) plan.estimated[plan.best] = false;
    if (counts) plan.greedy_gains[plan.best] = plan.gains[plan.best].gain;
  }
  return plan;
}

}  // namespace

// NOTE: the planner's own strategies, then one per gain method it scores by, named as the gain
// method is (methods.hpp); the rows' order is the order names are listed in messages.
constexpr EnumNames<PlannerMethod, 14> kPlannerMethodNames = {{
    {PlannerMethod::kProbabilistic, "probabilistic"},
    {PlannerMethod::kSurvival, "survival"},
    {PlannerMethod::kGreedy, "greedy"},
    {PlannerMethod::kRandom, "random"},
    {PlannerMethod::kLatombe, "latombe"},
    {PlannerMethod::kYamauchi, "yamauchi"},
    {PlannerMethod::kOcclusionAware, "occlusion-aware"},
    {PlannerMethod::kUnobservedVoxel, "unobserved-voxel"},
    {PlannerMethod::kRearSideVoxel, "rear-side-voxel"},
    {PlannerMethod::kRearSideEntropy, "rear-side-entropy"},
    {PlannerMethod::kProximityCount, "proximity-count"},
    {PlannerMethod::kAverageEntropy, "average-entropy"},
    {PlannerMethod::kAreaFactor, "area-factor"},
    {PlannerMethod::kSequence, "sequence"},
}};

std::string_view to_string(PlannerMethod method) { return name_of(method, kPlannerMethodNames); }

GainMethod gain_method_of(PlannerMethod method) {
  if (method == PlannerMethod::kSequence) return GainMethod::kSurvival;
  // NOTE: random, latombe and yamauchi report (latombe: and weigh) greedy's count.
  return find_gain_method(to_string(method)).value_or(GainMethod::kGreedy);
}

bool uses_survival_reading(PlannerMethod method) {
  return method_traits(gain_method_of(method)).ray == TargetRay::kSurvival;
}

SequenceConfig sequence_of(const PlannerConfig& config) {
  SequenceConfig sequence = config.sequence;
  if (config.search == DecisionSearch::kSampled) sequence.sample_bits = config.sample_bits;
  if (config.method == PlannerMethod::kSequence && !sequence.active()) {
    sequence.horizon = kSequenceDefaults.horizon;
    sequence.travel_weight = kSequenceDefaults.travel_weight;
  }
  return sequence;
}

PlannerMethod parse_planner_method(std::string_view name) {
  return value_named(name, kPlannerMethodNames, "method");
}

std::string_view to_string(DecisionSearch search) {
  switch (search) {
    case DecisionSearch::kScreened:
      return "screened";
    case DecisionSearch::kPruned:
      return "pruned";
    case DecisionSearch::kSampled:
      return "sampled";
    case DecisionSearch::kSwept:
      return "swept";
    case DecisionSearch::kExhaustive:
      break;
  }
  return "exhaustive";
}

DecisionSearch parse_decision_search(std::string_view name) {
  for (const DecisionSearch s :
       {DecisionSearch::kExhaustive, DecisionSearch::kScreened, DecisionSearch::kPruned,
        DecisionSearch::kSampled, DecisionSearch::kSwept}) {
    if (name == to_string(s)) return s;
  }
  throw std::invalid_argument(cat("unknown decision search '", name,
                                  "' (expected exhaustive, screened, pruned, sampled or swept)"));
}

std::string_view to_string(GainObjective objective) {
  return objective == GainObjective::kCells ? "cells" : "bits";
}

GainObjective parse_gain_objective(std::string_view name) {
  if (name == "bits") return GainObjective::kBits;
  if (name == "cells") return GainObjective::kCells;
  throw std::invalid_argument(cat("unknown objective '", name, "' (expected bits or cells)"));
}

GainObjective natural_objective(PlannerMethod method) {
  return uses_survival_reading(method) ? GainObjective::kCells : GainObjective::kBits;
}

bool has_observability(PlannerMethod method) {
  return method_traits(gain_method_of(method)).has_objective;
}

void PlannerConfig::validate() const {
  gain.validate();
  if (!(lambda >= 0.0 && std::isfinite(lambda))) {
    throw std::invalid_argument(cat("planner.lambda must be >= 0, got ", lambda));
  }
  if (swept_rays < 1 || swept_rays > 4096) {
    throw std::invalid_argument(cat("planner.swept_rays must lie in [1, 4096], got ", swept_rays));
  }
  if (sample_bits < 0 || sample_bits > 16) {
    throw std::invalid_argument(cat("planner.sample_bits must lie in [0, 16], got ", sample_bits));
  }
  sequence.validate();
  if (sequence.active() || method == PlannerMethod::kSequence) {
    if (!uses_survival_reading(method) && method != PlannerMethod::kGreedy) {
      throw std::invalid_argument(
          cat("planner.sequence plans with survival, sequence or greedy, not ", to_string(method)));
    }
    if (uses_survival_reading(method) && objective != GainObjective::kCells) {
      throw std::invalid_argument("planner.sequence ranks survival's views by cells, not bits");
    }
  }
}

Plan plan_next_view(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                    const PlannerConfig& config, std::uint64_t seed) {
  config.validate();
  if (candidates.empty()) throw std::invalid_argument("no candidate views to choose from");
  const auto start = std::chrono::steady_clock::now();
  Plan plan;
  const Views views(candidates);
  const bool probabilistic = has_observability(config.method);
  // NOTE: the paper's model and the metrics score by something other than greedy's count, so
  // greedy's prediction on the same poses is the reference of their predictions (Fig. 11).
  const GainMethod scored_by = gain_method_of(config.method);
  if (sequence_of(config).active()) return plan_by_sequence(grid, candidates, config, start);
  if (config.search == DecisionSearch::kPruned && prunable(config.method)) {
    return plan_pruned(grid, candidates, views, config, start);
  }
  if (config.search == DecisionSearch::kSampled && samplable(config.method)) {
    return plan_sampled(grid, candidates, views, config, start);
  }
  if (config.search == DecisionSearch::kSwept && sweepable(config)) {
    return plan_swept(grid, candidates, views, config, start);
  }
  if (probabilistic && config.search == DecisionSearch::kScreened) {
    // NOTE: only the argmax and its prediction are needed; a dropped candidate keeps its
    // estimate, flagged, and the greedy reference (if asked for) stays every candidate's.
    GainConfig gain = config.gain;
    gain.method = scored_by;
    detail::Screening screening = detail::screen_candidates(
        grid, views.frusta, views.first, gain, config.objective == GainObjective::kCells);
    plan.gains = std::move(screening.gains);
    plan.estimated = std::move(screening.estimated);
    for (std::size_t c = 0; c < plan.gains.size(); ++c) {
      const ViewGain& g = plan.gains[c];
      plan.scores.push_back(config.objective == GainObjective::kCells ? g.cells : g.gain);
    }
    // The best of the candidates evaluated in full (a dropped one's estimate never competes).
    std::vector<double> full = plan.scores;
    for (std::size_t c = 0; c < full.size(); ++c) {
      if (plan.estimated[c]) full[c] = -std::numeric_limits<double>::infinity();
    }
    plan.best = choose_best(full);
    plan.evaluated =
        static_cast<std::size_t>(std::count(plan.estimated.begin(), plan.estimated.end(), false));
    if (config.greedy_reference) add_greedy_reference(grid, views, config.gain, plan);
    plan.seconds = since(start);
    return plan;
  }
  std::vector<double> view_scores =
      gains_of(grid, views, config.gain, scored_by,
               probabilistic ? config.objective : GainObjective::kCells, &plan.gains);
  if (method_traits(scored_by).counts) {
    plan.greedy_gains = views.sums(view_scores);
  } else if (config.greedy_reference) {
    add_greedy_reference(grid, views, config.gain, plan);
  }

  // NOTE: a score is summed over the candidate's views (Latombe: each view's gain times the
  // candidate's travel factor), in the order of its views.
  switch (config.method) {
    case PlannerMethod::kRandom:
      plan.scores = views.sums(view_scores);
      plan.best = views.candidate_of(choose_random(views.frusta.size(), seed));
      break;
    case PlannerMethod::kLatombe:
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        for (std::size_t v = views.first[c]; v < views.first[c + 1]; ++v) {
          view_scores[v] *= travel_factor(config, candidates[c]);
        }
      }
      plan.scores = views.sums(view_scores);
      plan.best = choose_best(plan.scores);
      break;
    case PlannerMethod::kYamauchi:
      plan.scores.clear();
      for (const Candidate& c : candidates) plan.scores.push_back(-c.travel);
      // NOTE: of the views at the nearest place, the one that sees the most (issue 27).
      plan.best = choose_best(plan.scores, plan.greedy_gains);
      break;
    default:  // probabilistic, greedy and the metrics: the highest score
      plan.scores = views.sums(view_scores);
      plan.best = choose_best(plan.scores);
      break;
  }
  plan.evaluated = candidates.size();
  plan.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace vantage
