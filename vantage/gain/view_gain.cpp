#include "vantage/gain/view_gain.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <optional>
#include <stdexcept>

#include "vantage/gain/ray_model.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Per-view evaluation context for the probabilistic model: the model and the table of states
/// after the free cells outside the grid.
struct ProbabilisticRay {
  RayModel model;
  UniformPrefix outside;

  ProbabilisticRay(const OccupancyGrid& grid, const Eigen::Vector3d& origin, double alpha)
      : model(alpha), outside(model, grid.params().p_min, max_ray_cells(grid.spec(), origin)) {}

  double gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
              const Index3& target) const {
    RayState state;
    bool first = true;
    const TraversalResult walk =
        traverse(grid.spec(), origin, grid.spec().center(target),
                 [&](const Index3&, std::size_t linear, int m) {
                   const double p = grid.probability(linear);
                   if (!first) {
                     state = model.step(state, p);
                   } else {
                     state = m == 0 ? RayModel::start(p) : model.step(outside.at(m), p);
                     first = false;
                   }
                 });
    return walk.reached_end ? state.gain() : 0.0;
  }
};

double greedy_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin, const Index3& target) {
  return line_of_sight(grid, origin, target) ? 1.0 : 0.0;
}

/// Index box of the grid cells that may lie inside the frustum.
struct CellBox {
  Index3 lo, hi;  // inclusive
  bool empty() const { return (hi.array() < lo.array()).any(); }
};

CellBox cells_under(const GridSpec& spec, const Frustum& view) {
  const Eigen::AlignedBox3d box = view.bounds();
  CellBox cells;
  cells.lo = spec.lattice_index(box.min()).cwiseMax(Index3::Zero());
  cells.hi = spec.lattice_index(box.max()).cwiseMin(spec.dims - Index3::Ones());
  return cells;
}

/// Sums a per-target gain over the unobserved cells inside the frustum. Rows (fixed y, z) run in
/// parallel; the row sums are added in row order, so the result does not depend on threads.
template <typename CellGain>
ViewGain sum_over_targets(const OccupancyGrid& grid, const Frustum& view, CellGain&& cell_gain) {
  const GridSpec& spec = grid.spec();
  const CellBox box = cells_under(spec, view);
  if (box.empty()) return {};
  const int ny = box.hi.y() - box.lo.y() + 1;
  const int nz = box.hi.z() - box.lo.z() + 1;
  const auto rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  std::vector<ViewGain> row_sums(rows);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const auto& range) {
    for (std::size_t row = range.begin(); row != range.end(); ++row) {
      ViewGain sum;
      Index3 cell(0, box.lo.y() + static_cast<int>(row % static_cast<std::size_t>(ny)),
                  box.lo.z() + static_cast<int>(row / static_cast<std::size_t>(ny)));
      for (cell.x() = box.lo.x(); cell.x() <= box.hi.x(); ++cell.x()) {
        const std::size_t linear = spec.linear(cell);
        if (!grid.is_unobserved(linear) || !view.contains(spec.center(cell))) continue;
        sum.gain += cell_gain(cell);
        ++sum.targets;
      }
      row_sums[row] = sum;
    }
  });
  ViewGain total;
  for (const ViewGain& row : row_sums) {
    total.gain += row.gain;
    total.targets += row.targets;
  }
  return total;
}

ViewGain evaluate_one(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config) {
  const Eigen::Vector3d origin = view.origin();
  switch (config.method) {
    case GainMethod::kProbabilistic: {
      const ProbabilisticRay ray(grid, origin, config.alpha);
      return sum_over_targets(grid, view,
                              [&](const Index3& target) { return ray.gain(grid, origin, target); });
    }
    case GainMethod::kGreedy:
      return sum_over_targets(
          grid, view, [&](const Index3& target) { return greedy_gain(grid, origin, target); });
  }
  return {};
}

}  // namespace

std::string_view to_string(GainMethod method) {
  switch (method) {
    case GainMethod::kProbabilistic:
      return "probabilistic";
    case GainMethod::kGreedy:
      return "greedy";
  }
  return "unknown";
}

GainMethod parse_gain_method(std::string_view name) {
  if (name == "probabilistic") return GainMethod::kProbabilistic;
  if (name == "greedy") return GainMethod::kGreedy;
  throw std::invalid_argument(
      cat("unknown gain method '", name, "' (expected probabilistic or greedy)"));
}

void GainConfig::validate() const {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("gain.alpha must lie in (0, 1], got ", alpha));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("gain.num_threads must be >= 0, got ", num_threads));
  }
}

std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config) {
  config.validate();
  std::vector<ViewGain> gains(views.size());
  run_with_threads(config.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(),
                      [&](std::size_t i) { gains[i] = evaluate_one(grid, views[i], config); });
  });
  return gains;
}

ViewGain exact_view_gain(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config) {
  return exact_view_gains(grid, std::span<const Frustum>(&view, 1), config).front();
}

double exact_cell_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                       const Index3& target, const GainConfig& config) {
  config.validate();
  if (!grid.spec().contains(target)) {
    throw std::out_of_range(cat("target cell (", target.x(), ", ", target.y(), ", ", target.z(),
                                ") is outside the grid"));
  }
  if (config.method == GainMethod::kGreedy) return greedy_gain(grid, origin, target);
  return ProbabilisticRay(grid, origin, config.alpha).gain(grid, origin, target);
}

}  // namespace vantage
