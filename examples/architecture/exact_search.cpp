// docs/architecture.md, "Add a search": a search in its own file, as vantage/planner/searches/
// holds them. To register it, this file goes to vantage/planner/searches/exact.cpp (and to the
// core's SOURCES) and one row goes to the registry, vantage/planner/search.cpp:
//
//   extern const SearchTraits kExactSearch;        // beside the other searches' declarations
//   ... = {&kSweptSearch, &kPrunedSearch, &kExactSearch, &kExhaustiveSearch};
//
// Its place in the row is its place in the order of preference. `--search exact` then names it,
// and tests/architecture/worked_examples_test.cpp compiles this file and runs it behind the
// interface.

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/search.hpp"

namespace vantage {
namespace {

/// Every candidate evaluated by the exact evaluation, whatever GainConfig::evaluation says: the
/// paper's definition of every view's gain, for greedy's count ranked by a gain. What a decision
/// computes is the registry's answer (decision_quantity), not the method's name.
bool serves(const PlannerConfig& config) {
  return ranks_by_gain(config.method) && decision_quantity(config) == GainQuantity::kCount;
}

Plan run(const SearchInput& in) {
  Plan plan;
  plan.search = DecisionSearch{"exact"};
  plan.gains = in.views.sums(exact_view_gains(in.grid, in.views.frusta, in.gain));
  for (std::size_t c = 0; c < plan.gains.size(); ++c) {
    plan.scores.push_back(plan.gains[c].value(in.quantity()) * in.travel_factor(c));
  }
  plan.best = choose_best(plan.scores);
  plan.evaluated = plan.gains.size();
  plan.seconds = in.seconds();
  report_choice(in, plan);
  return plan;
}

}  // namespace

extern const SearchTraits kExactSearch;
const SearchTraits kExactSearch = {DecisionSearch{"exact"},
                                   "every candidate by the exact evaluation: greedy and latombe",
                                   &serves, &run};

}  // namespace vantage
