#pragma once
/// @file
/// The exact gain evaluation (docs/model.md "One view"): every unobserved cell inside the frustum
/// on its own ray from the sensor origin to the cell's centre, summed. The paper's definition and
/// the reference for every faster search.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/model.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"

namespace vantage {

/// Exact evaluation of every view on a snapshot, whatever `config.evaluation` says, with the ray
/// model `Model` (model.hpp; instantiated for PaperModel and BlindModel). With `config.epsilon` =
/// 0 it is the literal model.
template <typename Model = PaperModel>
std::vector<ViewGain> exact_view_gains(const GainMap& map, std::span<const Frustum> views,
                                       const GainConfig& config);

/// Whether the cell of linear index `i` is in the sample of `bits`: the top `bits` bits of a
/// SplitMix64 hash of `i` are zero (rate 2^-bits). Each sample holds those of more bits. A hash,
/// not a lattice: a regular lattice lines up with a table's plane and a ring's symmetry.
bool in_cell_sample(std::uint64_t i, int bits);

/// The linear indices of the unobserved cells in the sample of `bits`, ascending: the targets
/// a sequence planned on a sample evaluates (SequenceConfig::sample_bits).
std::vector<std::uint32_t> unobserved_sample(const ClassMap& map, int bits);
/// The unobserved cells by the nested samples they first enter, from the smallest sample
/// expected to hold at most `max_size` of them (one in 2^b for the least such b) to all of them:
/// b + 1 lists, list k < b holding the cells in the sample of k bits but not of k + 1, list b the
/// sample of b bits; lists k ... b together are the sample of k bits. Each list ascending.
std::vector<std::vector<std::uint32_t>> unobserved_by_sample(const ClassMap& map,
                                                             std::size_t max_size);
/// The most a cell's sample may be boosted (cells_by_sample).
inline constexpr int kMostBoost = 7;

/// The same nested samples of `cells` (linear indices, ascending). With `boost` (per cell of the
/// map, at most kMostBoost), a cell of boost o enters them o bits early: it is in the sample of b
/// bits when the top max(0, b - o) bits of its hash are zero, and the smallest sample is the first
/// expected to hold at most `max_size` cells.
std::vector<std::vector<std::uint32_t>> cells_by_sample(std::span<const std::uint32_t> cells,
                                                        std::size_t max_size,
                                                        std::span<const std::uint8_t> boost = {});

/// The same on the grid, which is only read.
std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config);

/// Exact gain of one view.
ViewGain exact_view_gain(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config);

/// The survival reading's expected cells seen (ViewGain::cells) of `views` together under each
/// of `alphas`, in one pass: each unobserved target in view with no occupied cell before it adds
/// a^n, n the unobserved cells before it, so a histogram of n serves every a [cells]. Equal to
/// the sum of exact_view_gains' cells at each a up to the order of the additions.
std::vector<double> survival_cells_by_alpha(const OccupancyGrid& grid,
                                            std::span<const Frustum> views,
                                            std::span<const double> alphas, int num_threads = 0);

/// The indices of `views` grouped by origin (exactly equal): each group in view order, the groups
/// in the order of their first view. Views from one origin share each target's ray.
std::vector<std::vector<std::size_t>> views_by_origin(std::span<const Frustum> views);

/// Predicted gain of one target cell seen from `origin`, whatever its state (known cells are
/// evaluated too; the view sums skip them). Follows the literal model whatever `config.epsilon`
/// says.
double exact_cell_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                       const Index3& target, const GainConfig& config);

}  // namespace vantage
