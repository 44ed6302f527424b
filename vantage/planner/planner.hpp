#pragma once
/// @file
/// The next-best-view decision: score every candidate by a method, choose the best (eq. 1).
/// Every method of the paper — its own and the baselines — goes through this one entry point;
/// which search decides is the registry's (search.hpp), the sequence is sequence.hpp's, and the
/// types are types.hpp's (docs/architecture.md).

#include <cstdint>
#include <span>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/types.hpp"

namespace vantage {

/// Scores the candidates and chooses one by what resolve_decider names (search.hpp): a sequence
/// when config.sequence plans one, else config.search, or the fastest that serves the method. Ties
/// go to the lower index; kRandom uses `seed` and takes the candidate of a uniformly random view
/// (uniform over candidates of as many views). Throws std::invalid_argument when there are no
/// candidates, or when config.search does not serve the method.
Plan plan_next_view(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                    const PlannerConfig& config, std::uint64_t seed = 0);

}  // namespace vantage
