// The exhaustive search (DecisionSearch::kExhaustive): every candidate evaluated in full by the
// gain façade (evaluate_views, GainConfig::evaluation), then ranked. The reference every other
// search is held to, and the one search that serves every method.

#include "vantage/gain/methods.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/search.hpp"

namespace vantage {
namespace {

bool serves(const PlannerConfig&) { return true; }

Plan run(const SearchInput& in) {
  const PlannerConfig& config = in.config;
  Plan plan;
  plan.search = DecisionSearch::kExhaustive;
  const std::vector<ViewGain> per_view = evaluate_views(in.grid, in.views.frusta, in.gain);
  // NOTE: greedy's gain is its count of cells; only the models with an objective differ.
  const bool cells =
      config.objective == GainObjective::kCells && method_traits(in.gain.method).has_objective;
  std::vector<double> values;
  values.reserve(per_view.size());
  for (std::size_t v = 0; v < per_view.size(); ++v) {
    // NOTE: a score is summed over the candidate's views, each times the candidate's travel
    // factor (Latombe), in the order of its views.
    values.push_back((cells ? per_view[v].cells : per_view[v].gain) *
                     in.travel_factor(in.views.candidate_of(v)));
  }
  plan.gains = in.views.sums(per_view);
  plan.scores = in.views.sums(values);
  plan.evaluated = in.candidates.size();
  switch (config.method.ranking) {
    case Ranking::kRandom:
      // NOTE: a uniformly random view, so a candidate of several views is as likely as its views.
      plan.best = in.views.candidate_of(choose_random(in.views.frusta.size(), in.seed));
      break;
    case Ranking::kNearest: {
      std::vector<double> counts;
      for (const ViewGain& g : plan.gains) counts.push_back(g.gain);
      plan.scores.clear();
      for (const Candidate& c : in.candidates) plan.scores.push_back(-c.travel);
      // NOTE: of the views at the nearest place, the one that sees the most (issue 27).
      plan.best = choose_best(plan.scores, counts);
      break;
    }
    default:
      plan.best = choose_best(plan.scores);
      break;
  }
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
