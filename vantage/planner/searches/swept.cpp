// The swept search (DecisionSearch::kSwept; docs/decision.md, "The swept search"): every
// candidate ranked by its swept estimate (gain/evaluators/swept.hpp: a thousand rays cast outward a
// view, each crediting the volume it sweeps through unobserved cells); the leaders cast again at
// twice the rays a side; the leaders of that raced on nested samples of their cells up to all of
// them (race.hpp); the winner's full prediction after. Under the paper's model no ray sweeps a
// volume, so every candidate enters the race on the model's exact per-target v_M. A metric's rounds
// cast the metric's own rays, coarser but in the last (run_metric); a metric whose value is a sum
// of cell credits races every candidate on samples of those cells (run_cell_sum; docs/decision.md,
// "A metric raced cell by cell"). Statistical, with the exhaustive exact search's choice, or one
// within 0.5 % of it, in every oracle state but one raced cell by cell (0.9915)
// (tests/planner/swept_scenes_test.cpp, tests/gain/metrics_race_scenes_test.cpp).

#include "vantage/gain/evaluators/swept.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <numeric>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/planner/searches/race.hpp"
#include "vantage/util/clock.hpp"

namespace vantage {
namespace {

/// Whether the search serves the decision, by the quantity it computes: the survival reading's
/// expected cells seen and greedy's count, which the swept rays estimate; the paper's expected
/// cells, raced on every candidate's exact v_M (only by cells: a target's gain in bits can sit
/// in a few cells a sample misses, docs/decision.md "The paper's model"); a metric's value, its
/// rounds on the metric's own rays (evaluators/metric_evaluator.hpp).
bool serves(const PlannerConfig& config) {
  if (!ranks_by_gain(config.method)) return false;
  const GainQuantity quantity = decision_quantity(config);
  if (quantity == GainQuantity::kMetric) return config.method.ranking != Ranking::kSequence;
  return counts_classes(quantity) || quantity == GainQuantity::kPaperCells;
}

/// The rounds: how many candidates the second round casts again at twice the rays a side, and
/// which of those the third races on samples of their cells: the best kFinal within kMargin of
/// the leader's estimate, and every one within kNearTie of it, up to kMostFinal. The second
/// round's estimates err by about 2 % of a view's count: on tabletop-4's hemisphere after 3 scans
/// (64 rays across) the best view's 55 299 exact cells were estimated at 54 148 and a view of
/// 54 580 at 55 674, so the best ranked fourth among five views within 2 % of each other; the
/// near-tie rule keeps such a view in the race, which decides on exact cells
/// (tests/planner/swept_scenes_test.cpp).
constexpr std::size_t kSecond = 12;
/// The first round estimates candidates this many at a time, in the order of their bounds
/// (first_round): enough views for both threads, few past the last one needed.
constexpr std::size_t kBoundBatch = 32;
constexpr std::size_t kFinal = 3;
constexpr double kMargin = 0.15;
constexpr std::size_t kMostFinal = 8;
constexpr double kNearTie = 0.05;
/// The most unobserved cells the race's first sample is expected to hold, whatever the map holds,
/// so that its cost does not grow with the cells.
constexpr std::size_t kSample = std::size_t{1} << 13;
/// A race of cell credits stops before a sample expected to add more than kCellSumMostTargets
/// targets to each finalist's lists (detail::RaceRules::most_new_targets) and evaluates the
/// finalists left by the metric's own rays: past it, listing a finalist's credits costs about as
/// much as its rays do. In the default run's ring decisions on tabletop-4 (issue 52) a target
/// listed cost 0.16-0.26 us of wall time on 2 threads and a finalist's rays 1.5-2.1 ms, when every
/// ray was walked (6 000 then); since only the rays that may credit a cell are walked
/// (rays_that_may_credit) a finalist costs less, and 3 000 stops the ring's slowest race a sample
/// earlier. Counted by a view's targets, not the sample's cells, since a narrow view meets a small
/// share of them (docs/decision.md, "A metric raced cell by cell").
constexpr double kCellSumMostTargets = 3000.0;
/// A race of cell credits counts in the error of each difference a cell its sample may have
/// missed (RaceRules::unseen): the credits sit on few cells (a cell face to face with a surface is
/// credited up to its class's rate, 0.6, one 4 cells off 0.03), and a sample that misses the large
/// ones gives a view an estimate and an error both too small. Over the race oracle's 48 states
/// (tests/gain/metrics_race_scenes_test.cpp), without it the surface model chose views of 0.948
/// and 0.929 of the best's value in 2 of its 144 decisions, the best dropped at half its value;
/// with it, one of 0.9915 (dropped at 3.4 standard errors on 3 151 cells).
/// The paper's race starts every candidate on a sample of about kSample * kFinal / n unobserved
/// cells (at least kPaperLeastSample), so that its first round costs about what the three
/// finalists' first round does in the other race.
constexpr std::size_t kPaperLeastSample = 512;
/// A race of cell credits starts as the paper's does, but on at least kCellSumLeastSample cells:
/// among many views (187 on the hemisphere, 1 000 on a sphere) a first sample of 128 cells
/// already drops most views after one scan, when their values lie far apart, and the first round,
/// which lists every view, costs a quarter.
constexpr std::size_t kCellSumLeastSample = 128;

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

/// A plan whose every candidate is still an estimate.
Plan estimates(const SearchInput& in) {
  Plan plan;
  plan.search = DecisionSearch::kSwept;
  plan.gains.assign(in.candidates.size(), ViewGain{});
  plan.estimated.assign(in.candidates.size(), true);
  plan.scores.assign(in.candidates.size(), 0.0);
  return plan;
}

/// Ends the search on its race between the candidates `raced` (ascending), by cells: their last
/// scores and the winner into the plan, the decision's time, and the winner's full prediction.
Plan finish(const SearchInput& in, const std::vector<std::size_t>& raced,
            const std::vector<double>& factor, const detail::Race& race, Plan plan) {
  const GainQuantity quantity = in.quantity();
  for (std::size_t k = 0; k < raced.size(); ++k) {
    const std::size_t c = raced[k];
    plan.scores[c] = race.scores[k];
    // NOTE: every race is by cells; a counting method's gain is its count.
    plan.gains[c] = ViewGain::of(quantity, race.scores[k] / factor[k]);
  }
  plan.best = raced[race.winner];
  // NOTE: a race that reached the full lists has the winner's exact cells (a counting method's
  // exact gain, up to the rounding of the travel factor), which stand when the chosen candidate
  // is not predicted in full after.
  if (race.exact && !in.config.predict_chosen) plan.estimated[plan.best] = false;
  plan.evaluated = raced.size();
  plan.bits_of_chosen_only = quantity != GainQuantity::kCount;
  plan.seconds = in.seconds();
  report_choice(in, plan);
  plan.scores[plan.best] = plan.gains[plan.best].cells * in.travel_factor(plan.best);
  return plan;
}

/// The paper's model: every candidate raced on its exact per-target v_M [cells].
Plan run_paper(const SearchInput& in) {
  const GainMap map(in.grid, in.gain.num_threads);
  std::vector<std::size_t> all(in.candidates.size());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = c;
  const std::vector<double> factor = in.travel_factors();
  const std::size_t first_sample =
      std::max(kPaperLeastSample, kSample * kFinal / std::max<std::size_t>(all.size(), 1));
  const detail::Race race = detail::race_candidates(
      unobserved_by_sample(ClassMap(in.grid), first_sample), in.views.frusta, in.views.first,
      factor,
      [&](std::span<const Frustum> raced, std::span<const std::size_t>,
          std::span<const std::uint32_t> cells) {
        return paper_view_cells(map, raced, in.gain, cells);
      },
      detail::RaceRules{.tolerance = kSweptTolerance});
  return finish(in, all, factor, race, estimates(in));
}

/// The winner of a metric's race: its value at the metric's own pitch, with its cells counted, and
/// the decision's time into the plan.
Plan with_metric_winner(const SearchInput& in, const MetricEvaluator& metric, Plan plan) {
  plan.seconds = in.seconds();
  // NOTE: the chosen view's report, after the decision (report_choice): its value when the race
  // chose it on a sample, and the unobserved cells its rays reach.
  if (in.config.predict_chosen || plan.estimated[plan.best]) {
    const auto report_start = std::chrono::steady_clock::now();
    const CandidateViews chosen = in.views.subset({plan.best});
    plan.gains[plan.best] = chosen.sums(metric.gains(chosen.frusta)).front();
    plan.estimated[plan.best] = false;
    plan.prediction_seconds = seconds_since(report_start);
  }
  report_choice(in, plan);
  return plan;
}

/// A metric whose value is a sum of cell credits (MetricEvaluator::lists_cells): every candidate
/// raced, as under the paper's model, on nested samples of the cells it may credit, each credit
/// by the view's own rays through the cell; the race ends within kSweptTolerance of the best.
Plan run_cell_sum(const SearchInput& in, const MetricEvaluator& metric) {
  std::vector<std::size_t> all(in.candidates.size());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = c;
  const std::vector<double> factor = in.travel_factors();
  const std::size_t first_sample =
      std::max(kCellSumLeastSample, kSample * kFinal / std::max<std::size_t>(all.size(), 1));
  const std::vector<std::uint8_t> boost = metric.sample_boost();
  // NOTE: the cells hidden from every candidate's origin are credited 0 by every candidate: left
  // out of the samples, the race's samples hold more of the cells that tell the views apart.
  std::vector<Eigen::Vector3d> origins;
  for (const Frustum& view : in.views.frusta) origins.push_back(view.origin());
  const std::vector<std::uint32_t> reachable =
      metric.shadows().empty()
          ? metric.creditable()
          : metric.shadows().reachable(origins, metric.creditable(), in.gain.num_threads);
  // NOTE: each view's rays stopped by a surface, kept across the rounds: a ray is walked to its
  // stop once, not once for each cell of the surface it passes (the same lists).
  std::vector<StoppedRays> stopped(in.views.frusta.size());
  const detail::Race race = detail::race_candidates(
      cells_by_sample(reachable, first_sample, boost), in.views.frusta, in.views.first, factor,
      [&](std::span<const Frustum> raced, std::span<const std::size_t> which,
          std::span<const std::uint32_t> cells) {
        std::vector<StoppedRays*> mine;
        for (const std::size_t v : which) mine.push_back(&stopped[v]);
        return metric.cells(raced, cells, mine);
      },
      detail::RaceRules{.tolerance = kSweptTolerance,
                        .unseen = true,
                        .most_new_targets = kCellSumMostTargets,
                        .boost = boost});
  Plan plan = estimates(in);
  for (std::size_t c = 0; c < all.size(); ++c) {
    plan.scores[c] = race.scores[c];
    plan.gains[c].gain = race.scores[c] / factor[c];
  }
  plan.best = race.winner;
  plan.evaluated = 1;  // the winner, in full, after the race
  if (!race.alive.empty()) {
    // NOTE: the finalists left, evaluated in full by the metric's rays; the best exact value
    // decides, the lower index on a tie.
    const CandidateViews left = in.views.subset(race.alive);
    const std::vector<ViewGain> sums =
        left.sums(metric.gains(left.frusta, 1, /*count_cells=*/false));
    std::vector<double> exact;
    for (std::size_t k = 0; k < race.alive.size(); ++k) {
      const std::size_t c = race.alive[k];
      plan.gains[c] = sums[k];
      plan.scores[c] = sums[k].gain * factor[c];
      plan.estimated[c] = false;
      exact.push_back(plan.scores[c]);
    }
    plan.best = race.alive[choose_best(exact)];
    plan.evaluated = race.alive.size();
  }
  plan = with_metric_winner(in, metric, std::move(plan));
  plan.scores[plan.best] = plan.gains[plan.best].gain * factor[plan.best];
  return plan;
}

/// A metric's race (MethodTraits::race_rounds): every candidate estimated by the metric's coarser
/// rays, the best of each round passed on to the next, the last round's evaluated at the metric's
/// own pitch, exactly; the best exact value decides, the lower index on a tie.
Plan run_metric(const SearchInput& in) {
  const MetricEvaluator metric(in.grid, in.gain);
  if (metric.lists_cells()) return run_cell_sum(in, metric);
  Plan plan = estimates(in);
  std::vector<std::size_t> among(in.candidates.size());
  for (std::size_t c = 0; c < among.size(); ++c) among[c] = c;
  const auto evaluate = [&](int coarseness) {
    const CandidateViews subset = in.views.subset(among);
    // NOTE: no cell counts in the rounds, so that the rays may cross the cells the metric
    // leaves unchanged; the chosen view's are counted after.
    const std::vector<ViewGain> sums =
        subset.sums(metric.gains(subset.frusta, coarseness, /*count_cells=*/false));
    for (std::size_t k = 0; k < among.size(); ++k) {
      const std::size_t c = among[k];
      plan.gains[c] = sums[k];
      plan.scores[c] = sums[k].gain * in.travel_factor(c);
    }
  };
  for (const MetricRound& round : method_traits(in.gain.method).race_rounds) {
    evaluate(round.coarseness);
    among = leaders(plan.scores, among, round.keep, 1.0);
    // NOTE: in candidate order, so that an exact tie goes to the lower index, as in the
    // exhaustive search.
    std::sort(among.begin(), among.end());
  }
  evaluate(1);
  std::vector<double> exact;
  for (const std::size_t c : among) {
    plan.estimated[c] = false;
    exact.push_back(plan.scores[c]);
  }
  plan.best = among[choose_best(exact)];
  plan.evaluated = among.size();
  return with_metric_winner(in, metric, std::move(plan));
}

/// Candidates `among` estimated by swept rays (swept.rays_across across), into the plan's gains
/// and scores.
void swept_estimates(const SearchInput& in, const ClassMap& map, const SweptConfig& swept,
                     const std::vector<std::size_t>& among, Plan& plan) {
  const GainQuantity quantity = in.quantity();
  const CandidateViews subset = in.views.subset(among);
  const std::vector<double> sums =
      subset.sums(swept_view_counts(map, subset.frusta, quantity, swept));
  for (std::size_t k = 0; k < among.size(); ++k) {
    const std::size_t c = among[k];
    plan.gains[c] = ViewGain::of(quantity, sums[k]);
    plan.scores[c] = sums[k] * in.travel_factor(c);
  }
}

/// The first round: every candidate estimated, but those that cannot be among its kSecond
/// leaders whatever their estimates. Candidate c's estimate is at most its views' bounds
/// (swept_view_bounds) and its score at most that times its travel factor; candidates are
/// estimated kBoundBatch at a time in descending order of those bounds (ties: the lower index),
/// and once a bound falls below the kSecond-th best score estimated, neither it nor any after can
/// be a leader: each keeps its bound as its estimate and score, as the pruned search's candidates
/// do. The leaders are those of every candidate estimated; the estimates do not depend on the
/// batches. Ranked by travel (Latombe), the views beyond a few metres are proved out: of FR-079's
/// 1 348 frontier views 192 are cast (a frustum holds 19 570 cells; the 12th best score is about
/// 2 100 cells, which e^(-0.5/m * d) brings a frustum below past d = 4.5 m); without travel every
/// bound is alike and every candidate is cast. PlannerConfig::gain_of_every_candidate casts every
/// one all the same (a stop on the best predicted gain reads them all).
std::vector<std::size_t> first_round(const SearchInput& in, const ClassMap& map,
                                     const SweptConfig& swept, Plan& plan) {
  const GainQuantity quantity = in.quantity();
  const std::vector<double> bounds =
      in.views.sums(swept_view_bounds(in.views.frusta, map.spec().resolution, swept));
  std::vector<std::size_t> order(in.candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for (const std::size_t c : order) {
    plan.gains[c] = ViewGain::of(quantity, bounds[c]);
    plan.scores[c] = bounds[c] * in.travel_factor(c);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return plan.scores[a] > plan.scores[b]; });
  std::vector<std::size_t> estimated;
  std::vector<double> best;  // the kSecond best scores estimated, descending
  for (std::size_t next = 0; next < order.size();) {
    const std::size_t last = std::min(order.size(), next + kBoundBatch);
    // NOTE: strictly below: a candidate whose bound ties the kSecond-th score may tie it.
    if (!in.config.gain_of_every_candidate && best.size() == kSecond &&
        plan.scores[order[next]] < best.back()) {
      break;
    }
    const std::vector<std::size_t> batch(order.begin() + static_cast<std::ptrdiff_t>(next),
                                         order.begin() + static_cast<std::ptrdiff_t>(last));
    swept_estimates(in, map, swept, batch, plan);
    for (const std::size_t c : batch) best.push_back(plan.scores[c]);
    std::sort(best.begin(), best.end(), std::greater<>());
    if (best.size() > kSecond) best.resize(kSecond);
    estimated.insert(estimated.end(), batch.begin(), batch.end());
    next = last;
  }
  std::sort(estimated.begin(), estimated.end());
  return estimated;
}

Plan run(const SearchInput& in) {
  const GainQuantity quantity = in.quantity();
  if (quantity == GainQuantity::kPaperCells) return run_paper(in);
  if (quantity == GainQuantity::kMetric) return run_metric(in);
  // NOTE: the grid's own classes and census, no snapshot: the swept rays and the race read
  // classes only.
  const ClassMap map(in.grid);
  SweptConfig swept;
  swept.alpha = in.gain.alpha;
  swept.epsilon = in.gain.epsilon;
  swept.num_threads = in.gain.num_threads;
  swept.rays_across = in.config.swept_rays;
  Plan plan = estimates(in);
  const std::vector<std::size_t> cast = first_round(in, map, swept, plan);
  const std::vector<std::size_t> second = leaders(plan.scores, cast, kSecond, 1.0);
  swept.rays_across = std::min(2 * in.config.swept_rays, 4096);
  swept_estimates(in, map, swept, second, plan);
  // NOTE: the last round races the leaders on samples of the targets, whose values are exact:
  // the swept estimate is not, it weighs a cell by the part of its volume the rays reach where
  // the exact sum asks whether its centre is reached.
  // NOTE: both rules keep a prefix of the same order, so their union is the longer.
  std::vector<std::size_t> final_round = leaders(plan.scores, second, kFinal, kMargin);
  const std::vector<std::size_t> near = leaders(plan.scores, second, kMostFinal, kNearTie);
  if (near.size() > final_round.size()) final_round = near;
  // NOTE: in candidate order, so that an exact tie on the full lists goes to the lower index, as
  // in the exhaustive search.
  std::sort(final_round.begin(), final_round.end());
  const CandidateViews finalists = in.views.subset(final_round);
  std::vector<double> factor;
  for (const std::size_t c : final_round) factor.push_back(in.travel_factor(c));
  // NOTE: a race of one is won before it starts: its lists would only refine the winner's
  // estimate, which the full prediction replaces (report_choice). On FR-079's 1 348 frontier
  // views under Latombe the one finalist's first sample cost 20 of the decision's 400 ms of CPU.
  const detail::Race race =
      final_round.size() == 1
          ? detail::Race{.winner = 0, .scores = {plan.scores[final_round.front()]}, .alive = {}}
          : detail::race_candidates(map, finalists.frusta, finalists.first, factor, in.gain,
                                    kSample, kSweptTolerance);
  return finish(in, final_round, factor, race, std::move(plan));
}

}  // namespace

extern const SearchTraits kSweptSearch;
const SearchTraits kSweptSearch = {
    DecisionSearch::kSwept,
    "every view ranked by rays cast outward, the leaders raced on samples of their cells until "
    "one is within 0.5 % of the best: milliseconds; survival and probabilistic by cells, greedy "
    "and latombe; the metrics on their coarser rays, the leaders on their own; the surface model "
    "and the proximity count raced cell by cell: a tenth of a second among 187 views",
    &serves, &run};

}  // namespace vantage
