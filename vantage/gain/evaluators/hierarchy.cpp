#include "vantage/gain/evaluators/hierarchy.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vantage/gain/evaluators/target_sums.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

constexpr int kShift = ClassBlocks::kShift;
constexpr int kBlock = ClassBlocks::kBlock;

/// The octant distance transform of ClassBlocks::depth, one pass per octant: a block with a known
/// cell is 0, one without is 1 + the least of its seven neighbours on the octant's side (0 past
/// the grid's edge). Exact for the Chebyshev distance restricted to the octant. A block cut by the
/// grid's edge counts as known: the cells it lacks lie outside, free (docs/model.md).
void octant_depths(ClassBlocks& blocks, const GridSpec& spec) {
  const Index3 d = blocks.dims;
  const std::size_t n = blocks.classes.size();
  for (int o = 0; o < 8; ++o) {
    std::vector<std::uint8_t>& depth = blocks.depth[o];
    depth.assign(n, 0);
    const Index3 step((o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1);
    // Visit blocks so that the seven neighbours on the octant's side come first.
    const auto range = [&](int a, auto&& body) {
      if (step[a] > 0) {
        for (int i = d[a] - 1; i >= 0; --i) body(i);
      } else {
        for (int i = 0; i < d[a]; ++i) body(i);
      }
    };
    range(2, [&](int z) {
      range(1, [&](int y) {
        range(0, [&](int x) {
          const Index3 b(x, y, z);
          const std::size_t i = blocks.at(b);
          const bool whole = ((b.array() + 1) * kBlock <= spec.dims.array()).all();
          if (blocks.classes[i] != ClassBlocks::kHasUnobserved || !whole) return;  // known cells
          int least = 255;
          for (int e = 1; e < 8; ++e) {
            const Index3 nb(x + ((e & 1) ? step.x() : 0), y + ((e & 2) ? step.y() : 0),
                            z + ((e & 4) ? step.z() : 0));
            const bool inside = (nb.array() >= 0).all() && (nb.array() < d.array()).all();
            least = std::min(least, inside ? static_cast<int>(depth[blocks.at(nb)]) : 0);
          }
          depth[i] = static_cast<std::uint8_t>(std::min(255, least + 1));
        });
      });
    });
  }
}

/// What one ray to a target counts: the unobserved cells before it, whether the last cell before
/// it was one, whether an occupied cell lies before it, and whether the walk reached it.
struct RayCount {
  int unobserved = 0;
  bool last_unobserved = false;
  bool occluded = false;
  bool reached = false;
  bool first = false;  ///< the target is the first grid cell the ray enters
};

/// Whether a ray may cross a block whose cells hold the classes `cls` in one step for `quantity`:
/// for greedy any block without an occupied cell, for the survival reading a block of one class.
bool crossable(std::uint8_t cls, GainQuantity quantity) {
  return quantity == GainQuantity::kCount ? (cls & ClassBlocks::kHasOccupied) == 0
                                          : (cls & (cls - 1)) == 0;
}

/// Walks from `origin` to `target`, across whole coarse blocks, then whole blocks, where `blocks`
/// says they are crossable (above) and the target is not in them.
template <typename Classes>
RayCount count_ray(const GridSpec& spec, const Classes& class_of, const ClassBlocks* blocks,
                   const Eigen::Vector3d& origin, const Index3& target, GainQuantity quantity) {
  constexpr int kCoarseShift = ClassBlocks::kCoarseShift;
  RayCount r;
  if (blocks != nullptr) {
    const Eigen::Vector3d dir = spec.center(target) - origin;
    const int octant = (dir.x() > 0.0 ? 1 : 0) | (dir.y() > 0.0 ? 2 : 0) | (dir.z() > 0.0 ? 4 : 0);
    if (((blocks->reach[spec.linear(target)] >> octant) & 1u) == 0) {
      r.occluded = true;  // every walk of cells the ray could take to it holds an occupied one
      return r;
    }
  }
  GridWalk walk(spec, origin, target);
  if (!walk.entered()) return r;
  r.first = walk.at_end();
  const Index3 target_block(target.x() >> kShift, target.y() >> kShift, target.z() >> kShift);
  const Index3 target_coarse(target.x() >> kCoarseShift, target.y() >> kCoarseShift,
                             target.z() >> kCoarseShift);
  // Crosses box `box` (of `size` cells a side, its cells' classes `cls`) in one step when it may
  // be crossed and does not hold the target, counting its cells; an occupied one ends the ray.
  const auto cross = [&](std::uint8_t cls, const Index3& box, const Index3& target_box, int size) {
    if (box == target_box || !crossable(cls, quantity)) return false;
    if (cls == ClassBlocks::kHasOccupied) return r.occluded = true;
    const Index3 lo = box * size;
    const int cells = walk.leave_box(lo, (lo.array() + size - 1).min(spec.dims.array() - 1));
    r.last_unobserved = cls == ClassBlocks::kHasUnobserved;
    r.unobserved += r.last_unobserved ? cells : 0;
    return true;
  };
  Index3 last_block(-1, -1, -1);  // the block whose cells are being walked one by one
  while (!walk.at_end()) {
    if (blocks != nullptr) {
      const Index3& c = walk.cell();
      const Index3 b(c.x() >> kShift, c.y() >> kShift, c.z() >> kShift);
      if (b != last_block) {
        const Index3 cb(c.x() >> kCoarseShift, c.y() >> kCoarseShift, c.z() >> kCoarseShift);
        if (cross(blocks->coarse_classes[blocks->coarse_at(cb)], cb, target_coarse,
                  ClassBlocks::kCoarse) ||
            cross(blocks->classes[blocks->at(b)], b, target_block, kBlock)) {
          if (r.occluded) return r;
          continue;
        }
        last_block = b;
      }
    }
    const std::uint8_t bit = class_of(walk.linear());
    if (bit == ClassBlocks::kHasOccupied) {
      r.occluded = true;
      return r;
    }
    r.last_unobserved = bit == ClassBlocks::kHasUnobserved;
    r.unobserved += r.last_unobserved ? 1 : 0;
    walk.advance();
  }
  r.reached = true;
  return r;
}

/// The survival reading's v_M from a count (SurvivalPredictor's, step for step): a^n
/// by repeated products, 0 when occluded, never reached, or stopped at c_{M-1} by `epsilon`.
double survival_seen(const RayCount& r, std::span<const double> powers, double epsilon) {
  if (!r.reached || r.occluded) return 0.0;
  if (!r.first) {
    const double before =
        powers[static_cast<std::size_t>(r.unobserved - (r.last_unobserved ? 1 : 0))];
    if (!(before >= epsilon && before > 0.0)) return 0.0;
  }
  return powers[static_cast<std::size_t>(r.unobserved)];
}

}  // namespace

std::size_t ClassBlocks::bytes() const {
  std::size_t total = classes.size() + coarse_classes.size() +
                      unobserved.size() * 10 * sizeof(std::uint32_t) +
                      (entropy.size() + open_entropy.size()) * sizeof(double) + reach.size();
  for (const auto& d : depth) total += d.size();
  return total;
}

namespace {

/// Plain reachability: a breadth-first fill through cells that are not occupied, from those on
/// the grid's faces and the views' origins inside it; 0xff where reached.
template <typename Classes>
void fill_reachable(const GridSpec& spec, const Classes& class_of, std::span<const Frustum> views,
                    std::vector<std::uint8_t>& reach) {
  std::vector<std::uint32_t> queue;
  const auto push = [&](std::size_t i) {
    if (reach[i] != 0 || class_of(i) == ClassBlocks::kHasOccupied) return;
    reach[i] = 0xff;
    queue.push_back(static_cast<std::uint32_t>(i));
  };
  const Index3 d = spec.dims;
  Index3 c;
  for (c.z() = 0; c.z() < d.z(); ++c.z()) {
    for (c.y() = 0; c.y() < d.y(); ++c.y()) {
      for (c.x() = 0; c.x() < d.x(); ++c.x()) {
        const bool face = (c.array() == 0).any() || (c.array() == d.array() - 1).any();
        if (face) push(spec.linear(c));
        if (!face && c.x() == 0) c.x() = d.x() - 2;  // only faces seed: jump to the row's end
      }
    }
  }
  for (const Frustum& view : views) {
    const Index3 o = spec.lattice_index(view.origin());
    if (spec.contains(o)) push(spec.linear(o));
  }
  const std::ptrdiff_t stride[3] = {1, d.x(), static_cast<std::ptrdiff_t>(d.x()) * d.y()};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t i = queue[head];
    const Index3 cell = spec.unravel(i);
    for (int a = 0; a < 3; ++a) {
      if (cell[a] > 0) push(i - static_cast<std::size_t>(stride[a]));
      if (cell[a] + 1 < d[a]) push(i + static_cast<std::size_t>(stride[a]));
    }
  }
}

/// ClassBlocks::reach for origins outside the grid: per octant, one pass in the octant's
/// direction, each cell reached when it is not occupied and lies on a face the walk may enter by
/// or follows a reached cell on one of the three axes.
template <typename Classes>
void fill_octant_reach(const GridSpec& spec, const Classes& class_of,
                       std::vector<std::uint8_t>& reach) {
  const Index3 d = spec.dims;
  const std::ptrdiff_t stride[3] = {1, d.x(), static_cast<std::ptrdiff_t>(d.x()) * d.y()};
  for (int o = 0; o < 8; ++o) {
    const auto bit = static_cast<std::uint8_t>(1u << o);
    const Index3 s((o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1);
    const Index3 start((s.array() > 0).select(0, d.array() - 1));
    Index3 c;
    for (int z = 0; z < d.z(); ++z) {
      c.z() = start.z() + s.z() * z;
      for (int y = 0; y < d.y(); ++y) {
        c.y() = start.y() + s.y() * y;
        c.x() = start.x();
        std::size_t i = spec.linear(c);
        for (int x = 0; x < d.x(); ++x, c.x() += s.x(), i += static_cast<std::size_t>(s.x())) {
          if (class_of(i) == ClassBlocks::kHasOccupied) continue;
          // The walk enters the grid by a face it moves away from, or comes from behind.
          const bool entered = x == 0 || y == 0 || z == 0 ||
                               (reach[i - static_cast<std::size_t>(s.x() * stride[0])] & bit) ||
                               (reach[i - static_cast<std::size_t>(s.y() * stride[1])] & bit) ||
                               (reach[i - static_cast<std::size_t>(s.z() * stride[2])] & bit);
          if (entered) reach[i] |= bit;
        }
      }
    }
  }
}

/// The classes of each coarse block (ClassBlocks::kCoarse), from its blocks'.
void fill_coarse_classes(ClassBlocks& blocks) {
  constexpr int kRatio = ClassBlocks::kCoarse / kBlock;
  blocks.coarse_dims = (blocks.dims.array() + (kRatio - 1)) / kRatio;
  blocks.coarse_classes.assign(static_cast<std::size_t>(blocks.coarse_dims.prod()), 0);
  Index3 b;
  for (b.z() = 0; b.z() < blocks.dims.z(); ++b.z()) {
    for (b.y() = 0; b.y() < blocks.dims.y(); ++b.y()) {
      for (b.x() = 0; b.x() < blocks.dims.x(); ++b.x()) {
        blocks.coarse_classes[blocks.coarse_at(b / kRatio)] |= blocks.classes[blocks.at(b)];
      }
    }
  }
}

}  // namespace

ClassBlocks summarize_classes(const GainMap& map, std::span<const Frustum> views, int num_threads) {
  const GridSpec& spec = map.spec();
  ClassBlocks blocks;
  blocks.dims = (spec.dims.array() + (kBlock - 1)) / kBlock;
  const auto n = static_cast<std::size_t>(blocks.dims.prod());
  blocks.classes.assign(n, 0);
  blocks.unobserved.assign(n, 0);
  blocks.entropy.assign(n, 0.0);
  for (auto& open : blocks.open) open.assign(n, 0);
  blocks.open_any.assign(n, 0);
  blocks.open_entropy.assign(n, 0.0);
  blocks.reach.assign(spec.num_cells(), 0);
  const bool inside = std::any_of(views.begin(), views.end(), [&](const Frustum& view) {
    return spec.contains(spec.lattice_index(view.origin()));
  });
  with_classes(map, [&](const auto& class_of) {
    if (inside) {
      fill_reachable(spec, class_of, views, blocks.reach);
    } else {
      fill_octant_reach(spec, class_of, blocks.reach);
    }
    run_with_threads(num_threads, [&] {
      tbb::parallel_for(0, blocks.dims.z(), [&](int bz) {
        for (int by = 0; by < blocks.dims.y(); ++by) {
          for (int bx = 0; bx < blocks.dims.x(); ++bx) {
            const Index3 b(bx, by, bz);
            const Index3 lo = b * kBlock;
            const Index3 hi = (lo.array() + kBlock).min(spec.dims.array());
            std::uint8_t classes = 0;
            std::uint32_t unobserved = 0;
            std::array<std::uint32_t, 8> open{};
            std::uint32_t open_any = 0;
            double entropy = 0.0, open_entropy = 0.0;
            for (int z = lo.z(); z < hi.z(); ++z) {
              for (int y = lo.y(); y < hi.y(); ++y) {
                std::size_t i = spec.linear(Index3(lo.x(), y, z));
                for (int x = lo.x(); x < hi.x(); ++x, ++i) {
                  const std::uint8_t bit = class_of(i);
                  classes |= bit;
                  if (bit == ClassBlocks::kHasUnobserved) {
                    const double h = map.value(i).entropy;
                    ++unobserved;
                    entropy += h;
                    const std::uint8_t reach = blocks.reach[i];
                    for (int o = 0; o < 8; ++o)
                      open[static_cast<std::size_t>(o)] += (reach >> o) & 1u;
                    if (reach != 0) {
                      ++open_any;
                      open_entropy += h;
                    }
                  }
                }
              }
            }
            const std::size_t k = blocks.at(b);
            blocks.classes[k] = classes;
            blocks.unobserved[k] = unobserved;
            blocks.entropy[k] = entropy;
            for (int o = 0; o < 8; ++o) blocks.open[o][k] = open[static_cast<std::size_t>(o)];
            blocks.open_entropy[k] = open_entropy;
            blocks.open_any[k] = open_any;
          }
        }
      });
    });
    return 0;
  });
  octant_depths(blocks, spec);
  fill_coarse_classes(blocks);
  return blocks;
}

std::vector<ViewGain> count_view_gains(const GainMap& map, const ClassBlocks* blocks,
                                       std::span<const Frustum> views, GainQuantity quantity,
                                       const GainConfig& config) {
  config.validate();
  if (!counts_classes(quantity)) {
    throw std::invalid_argument(
        "count_view_gains: counts the survival reading's cells or greedy's");
  }
  const GridSpec& spec = map.spec();
  std::vector<double> powers(static_cast<std::size_t>(detail::longest_ray(spec, views)) + 1);
  powers[0] = 1.0;
  for (std::size_t k = 1; k < powers.size(); ++k) powers[k] = powers[k - 1] * config.alpha;
  return with_classes(map, [&](const auto& class_of) {
    return detail::sum_by_origin(
        map, views, config.num_threads,
        [&](const Eigen::Vector3d& origin, const Index3& target) -> TargetPrediction {
          const RayCount r = count_ray(spec, class_of, blocks, origin, target, quantity);
          if (quantity == GainQuantity::kCount) {
            const double seen = r.occluded ? 0.0 : 1.0;
            return {seen, seen};
          }
          return {0.0, survival_seen(r, powers, config.epsilon)};
        });
  });
}

}  // namespace vantage
