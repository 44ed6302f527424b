#pragma once
/// @file
/// Which unobserved cells each view is predicted to see, one by one (issue 26): the per-target
/// visibilities v_M that the exact evaluation sums into ViewGain::cells, kept per cell so that a
/// planner can tell what two views would see twice (vantage/planner/sequence.hpp).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Every view's per-target visibilities under `config.method`, survival or greedy (v_M = 1 when
/// nothing occupied lies before the target, else 0): each unobserved cell whose centre lies in
/// the frustum, on its own ray from the view's origin, walked as the exact evaluation walks it
/// (GridWalk, map/traversal.hpp), with its early stop at `config.epsilon`. Views from one origin
/// share each target's ray. Origins run in parallel and each list is built in cell order, so the
/// result is the same for any thread count. With `sample_bits` k > 0, only the targets in the
/// sampled search's hashed sample of one cell in 2^k (in_cell_sample, exact.hpp), the same for
/// every view. It reads the cells' classes only, from the grid itself (ClassMap), and its rays
/// cross free cubes in one step. Throws std::invalid_argument for another method.
std::vector<ViewCells> exact_view_cells(const ClassMap& map, std::span<const Frustum> views,
                                        const GainConfig& config, int sample_bits = 0);

/// The same for the targets among `cells`: linear indices of unobserved cells, ascending.
std::vector<ViewCells> exact_view_cells(const ClassMap& map, std::span<const Frustum> views,
                                        const GainConfig& config,
                                        std::span<const std::uint32_t> cells);

/// The same lists under the paper's model (`config.method`'s cells must be
/// GainQuantity::kPaperCells), for the targets among `cells` (unobserved, ascending): each target's
/// v_M on its own ray, as the exact evaluation predicts it (PaperPredictor, bit for bit), from a
/// snapshot, since the model reads every cell's occupancy. Throws std::invalid_argument for another
/// method.
std::vector<ViewCells> paper_view_cells(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config,
                                        std::span<const std::uint32_t> cells);

}  // namespace vantage
