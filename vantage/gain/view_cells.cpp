#include "vantage/gain/view_cells.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

#include "vantage/gain/detail/target_sums.hpp"
#include "vantage/gain/exact.hpp"
#include "vantage/gain/target_ray.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// v_M of one target: greedy's 1 or 0, or the survival reading's a^n (n the unobserved cells
/// before it, 0 behind an occupied one or once the ray's visibility fell below `epsilon` before
/// the target), on the cells TargetWalk takes; `powers[n]` = a^n by repeated multiplication, as
/// the exact evaluation multiplies.
double target_seen(const GainMap& map, const Eigen::Vector3d& origin, const Index3& target,
                   bool greedy, std::span<const double> powers, double epsilon) {
  TargetWalk walk(map.spec(), origin, target);
  if (!walk.entered()) return greedy ? 1.0 : 0.0;  // as greedy_gain and survival_ray_gain
  int unobserved = 0;
  bool last_unobserved = false, stepped = false;
  for (; !walk.at_target(); walk.advance()) {
    stepped = true;
    const CellState state = map.value(walk.linear()).state;
    if (occludes(state)) return 0.0;
    last_unobserved = state == CellState::kUnobserved;
    unobserved += last_unobserved ? 1 : 0;
  }
  if (greedy) return 1.0;
  // NOTE: the exact walk tests its visibility before each step, so the last test sees the
  // unobserved cells before the one next to the target.
  if (stepped) {
    const double before = powers[static_cast<std::size_t>(unobserved - (last_unobserved ? 1 : 0))];
    if (!(before >= epsilon && before > 0.0)) return 0.0;
  }
  return powers[static_cast<std::size_t>(unobserved)];
}

}  // namespace

double ViewCells::sum() const {
  double total = 0.0;
  for (const double v : seen) total += v;
  return total;
}

std::vector<ViewCells> exact_view_cells(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config) {
  config.validate();
  const bool greedy = config.method == GainMethod::kGreedy;
  if (!greedy && config.method != GainMethod::kSurvival) {
    throw std::invalid_argument(
        cat("exact_view_cells: gain.method must be survival or greedy, got ",
            to_string(config.method)));
  }
  const GridSpec& spec = map.spec();
  std::vector<double> powers(static_cast<std::size_t>(detail::longest_ray(spec, views)) + 1);
  powers[0] = 1.0;
  for (std::size_t k = 1; k < powers.size(); ++k) powers[k] = powers[k - 1] * config.alpha;
  std::vector<ViewCells> out(views.size());
  const std::vector<std::vector<std::size_t>> groups = views_by_origin(views);
  run_with_threads(config.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
      const std::vector<std::size_t>& members = groups[g];
      const Eigen::Vector3d origin = views[members.front()].origin();
      std::vector<CellBox> boxes;
      CellBox box{spec.dims, Index3(-1, -1, -1)};
      for (const std::size_t v : members) {
        boxes.push_back(cells_under(spec, views[v]));
        if (boxes.back().empty()) continue;
        box.lo = box.lo.cwiseMin(boxes.back().lo);
        box.hi = box.hi.cwiseMax(boxes.back().hi);
      }
      if (box.empty()) return;
      // NOTE: z, then y, then x: ascending linear index, so every list comes out sorted.
      Index3 cell;
      for (cell.z() = box.lo.z(); cell.z() <= box.hi.z(); ++cell.z()) {
        for (cell.y() = box.lo.y(); cell.y() <= box.hi.y(); ++cell.y()) {
          for (cell.x() = box.lo.x(); cell.x() <= box.hi.x(); ++cell.x()) {
            const std::size_t linear = spec.linear(cell);
            if (map.value(linear).state != CellState::kUnobserved) continue;
            const Eigen::Vector3d center = spec.center(cell);
            bool evaluated = false;
            double seen = 0.0;
            for (std::size_t m = 0; m < members.size(); ++m) {
              const CellBox& b = boxes[m];
              if ((cell.array() < b.lo.array()).any() || (cell.array() > b.hi.array()).any() ||
                  !views[members[m]].contains(center)) {
                continue;
              }
              if (!evaluated) {
                seen = target_seen(map, origin, cell, greedy, powers, config.epsilon);
                evaluated = true;
              }
              ViewCells& list = out[members[m]];
              ++list.targets;
              if (seen > 0.0) {
                list.cells.push_back(static_cast<std::uint32_t>(linear));
                list.seen.push_back(seen);
              }
            }
          }
        }
      }
    });
  });
  return out;
}

}  // namespace vantage
