#include "vantage/planner/planner.hpp"

#include <chrono>
#include <stdexcept>

#include "vantage/planner/search.hpp"
#include "vantage/planner/sequence.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage {

Plan plan_next_view(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                    const PlannerConfig& config, std::uint64_t seed) {
  config.validate();
  if (candidates.empty()) throw std::invalid_argument("no candidate views to choose from");
  const Decider decider = resolve_decider(config);
  if (!decider.search) return decide_by_sequence(grid, candidates, config);
  const SearchTraits& search = search_traits(*decider.search);
  const auto start = std::chrono::steady_clock::now();
  const CandidateViews views(candidates);
  GainConfig gain = config.gain;
  gain.method = config.method.gain;
  // NOTE: the decision's steps in one arena of its threads (run_with_threads).
  Plan plan;
  run_with_threads(gain.num_threads, [&] {
    plan = search.run(SearchInput{grid, candidates, views, config, gain, start, seed});
  });
  return plan;
}

}  // namespace vantage
