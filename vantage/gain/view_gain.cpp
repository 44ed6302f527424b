#include "vantage/gain/view_gain.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

#include "vantage/gain/fast_gain.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Cell values read straight from the grid, for one-off rays where a snapshot would cost more
/// than it saves.
struct GridCells {
  const OccupancyGrid& grid;
  const GridSpec& spec() const { return grid.spec(); }
  const OccupancyParams& params() const { return grid.params(); }
  GainMap::Value value(std::size_t i) const {
    GainMap::Value v;
    v.p = grid.probability(i);
    v.entropy = entropy_bits(v.p);
    v.state = grid.state(i);
    return v;
  }
};

/// The probabilistic model on one target ray, with the table of states after the free cells
/// outside the grid. `Cells` is GainMap or GridCells.
template <typename Cells>
class ProbabilisticRay {
 public:
  ProbabilisticRay(const Cells& map, const Eigen::Vector3d& origin, double alpha, double epsilon)
      : map_(map), origin_(origin), epsilon_(epsilon) {
    const int cells = max_ray_cells(map.spec(), origin);
    const RayModel model(alpha);
    const UniformPrefix outside(model, map.params().p_min, cells + 1);
    outside_.resize(static_cast<std::size_t>(cells) + 1);
    t_.resize(static_cast<std::size_t>(cells) + 1);
    t_[0] = 1.0;
    for (int k = 1; k <= cells; ++k) {
      outside_[static_cast<std::size_t>(k)] = detail::Odds(outside.at(k));
      t_[static_cast<std::size_t>(k)] = t_[static_cast<std::size_t>(k) - 1] * alpha;
    }
  }

  /// Gain of the target cell; 0 when the ray stops early (GainConfig::epsilon) before it.
  double gain(const Index3& target) const {
    const GridSpec& spec = map_.spec();
    const std::size_t target_linear = spec.linear(target);
    // NOTE: the model in odds form (detail::Odds): the same numbers as RayModel to rounding,
    // without the two divisions per cell that would dominate a long ray.
    detail::Odds state;
    double p_prev = 0.0;
    double gain = 0.0;
    bool first = true;
    traverse(spec, origin_, spec.center(target), [&](const Index3&, std::size_t linear, int m) {
      const auto cell = map_.value(linear);
      if (!first) {
        state.step(t_[static_cast<std::size_t>(m)], p_prev, cell.p);
        if ((m & 7) == 0) state.renormalize();
      } else if (m == 0) {
        state = detail::Odds(1.0, cell.p);  // the origin's cell: v_0 = 1, q_0 = p_0
      } else {
        state = outside_[static_cast<std::size_t>(m)];  // the free cells before the grid
        state.step(t_[static_cast<std::size_t>(m)], map_.params().p_min, cell.p);
      }
      first = false;
      p_prev = cell.p;
      if (linear == target_linear) {
        gain = cell.entropy - entropy_bits(state.posterior());  // eq. (4)
        return false;
      }
      // The fast mode's early stop: a ray stops once it is hidden.
      return !state.hidden(epsilon_);
    });
    return gain;
  }

 private:
  const Cells& map_;
  Eigen::Vector3d origin_;
  double epsilon_;
  std::vector<detail::Odds> outside_;  // outside_[k]: the state after k free cells
  std::vector<double> t_;              // a^m
};

/// Whether nothing occupied lies on the ray before the target (the simple greedy gain).
template <typename Cells>
double greedy_gain(const Cells& map, const Eigen::Vector3d& origin, const Index3& target) {
  const GridSpec& spec = map.spec();
  const std::size_t target_linear = spec.linear(target);
  bool clear = true;
  traverse(spec, origin, spec.center(target), [&](const Index3&, std::size_t linear, int) {
    if (linear == target_linear) return false;
    if (map.value(linear).state == CellState::kOccupied) {
      clear = false;
      return false;
    }
    return true;
  });
  return clear ? 1.0 : 0.0;
}

/// Sums a per-target gain over the unobserved cells inside the frustum. The frustum and the
/// cell's class are tested before any traversal. Rows (fixed y, z) run in parallel; the row sums
/// are added in row order, so the result does not depend on threads.
template <typename CellGain>
ViewGain sum_over_targets(const GainMap& map, const Frustum& view, CellGain&& cell_gain) {
  const GridSpec& spec = map.spec();
  const detail::CellBox box = detail::cells_under(spec, view);
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
        if (map.value(linear).state != CellState::kUnobserved ||
            !view.contains(spec.center(cell))) {
          continue;
        }
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

ViewGain evaluate_one(const GainMap& map, const Frustum& view, const GainConfig& config) {
  const Eigen::Vector3d origin = view.origin();
  switch (config.method) {
    case GainMethod::kProbabilistic: {
      const ProbabilisticRay<GainMap> ray(map, origin, config.alpha, config.epsilon);
      return sum_over_targets(map, view, [&](const Index3& target) { return ray.gain(target); });
    }
    case GainMethod::kGreedy:
      return sum_over_targets(
          map, view, [&](const Index3& target) { return greedy_gain(map, origin, target); });
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

std::string_view to_string(GainEvaluation evaluation) {
  switch (evaluation) {
    case GainEvaluation::kExact:
      return "exact";
    case GainEvaluation::kFast:
      return "fast";
    case GainEvaluation::kAuto:
      return "auto";
  }
  return "unknown";
}

GainEvaluation parse_gain_evaluation(std::string_view name) {
  if (name == "exact") return GainEvaluation::kExact;
  if (name == "fast") return GainEvaluation::kFast;
  if (name == "auto") return GainEvaluation::kAuto;
  throw std::invalid_argument(
      cat("unknown gain evaluation '", name, "' (expected exact, fast or auto)"));
}

void GainConfig::validate() const {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("gain.alpha must lie in (0, 1], got ", alpha));
  }
  if (!(epsilon >= 0.0 && epsilon < 0.5)) {
    throw std::invalid_argument(cat("gain.epsilon must lie in [0, 0.5), got ", epsilon));
  }
  if (!(ray_spacing > 0.0 && ray_spacing <= 1.0)) {
    throw std::invalid_argument(
        cat("gain.ray_spacing must lie in (0, 1] cells, got ", ray_spacing));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("gain.num_threads must be >= 0, got ", num_threads));
  }
}

std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config) {
  switch (config.evaluation) {
    case GainEvaluation::kExact:
      return exact_view_gains(grid, views, config);
    case GainEvaluation::kFast:
      return fast_view_gains(grid, views, config);
    case GainEvaluation::kAuto:
      return cheapest_view_gains(grid, views, config);
  }
  throw std::invalid_argument("gain.evaluation is not a known evaluation");
}

std::vector<ViewGain> exact_view_gains(const GainMap& map, std::span<const Frustum> views,
                                       const GainConfig& config) {
  config.validate();
  std::vector<ViewGain> gains(views.size());
  run_with_threads(config.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(),
                      [&](std::size_t i) { gains[i] = evaluate_one(map, views[i], config); });
  });
  return gains;
}

std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config) {
  config.validate();
  return exact_view_gains(GainMap(grid, config.num_threads), views, config);
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
  const GridCells cells{grid};
  if (config.method == GainMethod::kGreedy) return greedy_gain(cells, origin, target);
  return ProbabilisticRay<GridCells>(cells, origin, config.alpha, 0.0).gain(target);
}

}  // namespace vantage
