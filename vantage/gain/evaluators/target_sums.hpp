#pragma once
/// @file
/// How the exact evaluations sum a per-target prediction over each view's unobserved cells, written
/// once for every ray model (exact.cpp, hierarchy.cpp): views from one origin share each target's
/// ray, rows run in parallel and are added in a fixed order, so every view's sum is bit for bit
/// its own, for any thread count.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage::detail {

/// The cell box of each member view (`boxes`, in member order) and the box that holds them all;
/// empty when every member's is.
inline CellBox boxes_under(const GridSpec& spec, std::span<const Frustum> views,
                           std::span<const std::size_t> members, std::vector<CellBox>& boxes) {
  CellBox box{spec.dims, Index3(-1, -1, -1)};
  for (const std::size_t v : members) {
    boxes.push_back(cells_under(spec, views[v]));
    if (boxes.back().empty()) continue;
    box.lo = box.lo.cwiseMin(boxes.back().lo);
    box.hi = box.hi.cwiseMax(boxes.back().hi);
  }
  return box;
}

/// Calls `take(m)` for each member m (in order) whose frustum holds `cell`, whose centre is
/// `center`: its cell box first, then the frustum.
template <typename Take>
void for_members_holding(std::span<const Frustum> views, std::span<const std::size_t> members,
                         std::span<const CellBox> boxes, const Index3& cell,
                         const Eigen::Vector3d& center, Take&& take) {
  for (std::size_t m = 0; m < members.size(); ++m) {
    const CellBox& b = boxes[m];
    if ((cell.array() >= b.lo.array()).all() && (cell.array() <= b.hi.array()).all() &&
        views[members[m]].contains(center)) {
      take(m);
    }
  }
}

/// Sums a per-target gain over the unobserved cells inside each frustum, for views that share
/// one origin (`members`, indices into `views`): each unobserved cell in any member's frustum is
/// evaluated once and added to every member whose frustum holds it. The frustum and the cell's
/// class are tested before any traversal. Rows (fixed y, z) run in parallel; a member's row sums
/// are added in row order, so the result does not depend on threads, and it is bit for bit the
/// member's sum evaluated alone: its cells are added in the same order within a row and its rows
/// in the same (z, y) order, and the rows and cells it does not hold add nothing.
template <typename CellGain>
void sum_over_shared_targets(const GainMap& map, std::span<const Frustum> views,
                             std::span<const std::size_t> members, CellGain&& cell_gain,
                             std::vector<ViewGain>& gains) {
  const GridSpec& spec = map.spec();
  const std::size_t k = members.size();
  std::vector<CellBox> boxes;
  const CellBox box = boxes_under(spec, views, members, boxes);
  if (box.empty()) return;
  const int ny = box.hi.y() - box.lo.y() + 1;
  const int nz = box.hi.z() - box.lo.z() + 1;
  const auto rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  std::vector<ViewGain> row_sums(rows * k);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const auto& range) {
    for (std::size_t row = range.begin(); row != range.end(); ++row) {
      ViewGain* sums = row_sums.data() + row * k;
      Index3 cell(0, box.lo.y() + static_cast<int>(row % static_cast<std::size_t>(ny)),
                  box.lo.z() + static_cast<int>(row / static_cast<std::size_t>(ny)));
      for (cell.x() = box.lo.x(); cell.x() <= box.hi.x(); ++cell.x()) {
        const std::size_t linear = spec.linear(cell);
        if (map.value(linear).state != CellState::kUnobserved) continue;
        bool evaluated = false;
        TargetPrediction prediction;
        for_members_holding(views, members, boxes, cell, spec.center(cell), [&](std::size_t m) {
          if (!evaluated) {
            prediction = cell_gain(cell);
            evaluated = true;
          }
          sums[m].gain += prediction.gain;
          sums[m].cells += prediction.seen;
          ++sums[m].targets;
        });
      }
    }
  });
  for (std::size_t m = 0; m < k; ++m) {
    ViewGain total;
    for (std::size_t row = 0; row < rows; ++row) total += row_sums[row * k + m];
    gains[members[m]] = total;
  }
}

/// The most cells a ray from any view's origin crosses.
inline int longest_ray(const GridSpec& spec, std::span<const Frustum> views) {
  int cells = 1;
  for (const Frustum& view : views) cells = std::max(cells, max_ray_cells(spec, view.origin()));
  return cells;
}

/// Every view's sum of `cell_gain(origin, target)` over its targets; the views of one origin
/// (a ring position's yaw offsets) share each target's ray, so each cell is evaluated once per
/// origin and every view's sum is bit for bit its own. Origins run in parallel.
template <typename CellGain>
std::vector<ViewGain> sum_by_origin(const GainMap& map, std::span<const Frustum> views,
                                    int num_threads, CellGain&& cell_gain) {
  std::vector<ViewGain> gains(views.size());
  const std::vector<std::vector<std::size_t>> groups = views_by_origin(views);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
      const Eigen::Vector3d origin = views[groups[g].front()].origin();
      sum_over_shared_targets(
          map, views, groups[g], [&](const Index3& target) { return cell_gain(origin, target); },
          gains);
    });
  });
  return gains;
}

}  // namespace vantage::detail
