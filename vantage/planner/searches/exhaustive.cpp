// The exhaustive search (DecisionSearch::kExhaustive): every candidate evaluated in full by the
// gain façade (evaluate_views, GainConfig::evaluation), then ranked. The reference every other
// search is held to, and the one search that serves every method.

#include <algorithm>

#include "vantage/gain/view_gain.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/search.hpp"

namespace vantage {
namespace {

bool serves(const PlannerConfig&) { return true; }

// Random and Yamauchi's nearest do not rank by a gain: only the candidates they can choose are
// evaluated (random's one; the nearest ones, whose counts break their tie), and the others are
// left as estimates of 0, so that the decision costs one evaluation instead of every candidate's.
Plan run_without_gain(const SearchInput& in) {
  const std::size_t n = in.candidates.size();
  Plan plan;
  plan.search = DecisionSearch::kExhaustive;
  plan.gains.assign(n, ViewGain{});
  plan.scores.assign(n, 0.0);
  plan.estimated.assign(n, true);
  std::vector<std::size_t> among;
  if (in.config.method.ranking == Ranking::kRandom) {
    // NOTE: a uniformly random view, so a candidate of several views is as likely as its views.
    among.push_back(in.views.candidate_of(choose_random(in.views.frusta.size(), in.seed)));
  } else {
    double nearest = in.candidates[0].travel;
    for (const Candidate& c : in.candidates) nearest = std::min(nearest, c.travel);
    for (std::size_t c = 0; c < n; ++c) {
      plan.scores[c] = -in.candidates[c].travel;
      if (in.candidates[c].travel == nearest) among.push_back(c);
    }
  }
  const CandidateViews chosen = in.views.subset(among);
  const std::vector<ViewGain> gains = chosen.sums(evaluate_views(in.grid, chosen.frusta, in.gain));
  std::vector<double> counts;
  for (std::size_t i = 0; i < among.size(); ++i) {
    plan.gains[among[i]] = gains[i];
    plan.estimated[among[i]] = false;
    counts.push_back(gains[i].gain);
  }
  // NOTE: of the views at the nearest place, the one that sees the most (issue 27); ties go to
  // the lower index, as `among` is in index order.
  plan.best = among[choose_best(counts)];
  if (in.config.method.ranking == Ranking::kRandom) plan.scores[plan.best] = gains[0].gain;
  plan.evaluated = among.size();
  plan.seconds = in.seconds();
  report_choice(in, plan);
  return plan;
}

Plan run(const SearchInput& in) {
  if (!ranks_by_gain(in.config.method)) return run_without_gain(in);
  Plan plan;
  plan.search = DecisionSearch::kExhaustive;
  const std::vector<ViewGain> per_view = evaluate_views(in.grid, in.views.frusta, in.gain);
  const GainQuantity quantity = in.quantity();
  std::vector<double> values;
  values.reserve(per_view.size());
  for (std::size_t v = 0; v < per_view.size(); ++v) {
    // NOTE: a score is summed over the candidate's views, each times the candidate's travel
    // factor (Latombe), in the order of its views.
    values.push_back(per_view[v].value(quantity) * in.travel_factor(in.views.candidate_of(v)));
  }
  plan.gains = in.views.sums(per_view);
  plan.scores = in.views.sums(values);
  plan.evaluated = in.candidates.size();
  plan.best = choose_best(plan.scores);
  plan.seconds = in.seconds();
  report_choice(in, plan);
  return plan;
}

}  // namespace

extern const SearchTraits kExhaustiveSearch;
const SearchTraits kExhaustiveSearch = {
    DecisionSearch::kExhaustive,
    "every candidate evaluated in full: the reference; serves every method", &serves, &run};

}  // namespace vantage
