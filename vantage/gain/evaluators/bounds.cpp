#include "vantage/gain/evaluators/bounds.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "vantage/util/parallel.hpp"

namespace vantage {
namespace {

constexpr int kShift = ClassBlocks::kShift;
constexpr int kBlock = ClassBlocks::kBlock;

/// Whether the box [lo, hi] (world) may meet the view's frustum: false only when all its corners
/// lie outside one of the frustum's planes or its range.
bool may_meet(const Frustum& view, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
              double tan_h, double tan_v) {
  const Eigen::Vector3d o = view.origin();
  const double near = (o.cwiseMax(lo).cwiseMin(hi) - o).norm();
  if (near > view.fov().max_range) return false;
  const Eigen::Vector3d far = (o - lo).cwiseAbs().cwiseMax((o - hi).cwiseAbs());
  if (far.norm() < view.fov().min_range) return false;
  const Eigen::Isometry3d T_sensor_world = view.T_world_sensor().inverse();
  std::array<int, 5> outside{};  // behind, left, right, above, below
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                                 (k & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d p = T_sensor_world * corner;
    outside[0] += p.x() <= 0.0;
    outside[1] += p.y() > p.x() * tan_h;
    outside[2] += p.y() < -p.x() * tan_h;
    outside[3] += p.z() > p.x() * tan_v;
    outside[4] += p.z() < -p.x() * tan_v;
  }
  return std::none_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

/// A lower bound on the unobserved cells before any cell of block `b` on its ray from `o`
/// (docs/decision.md, "The bound"): the block lies `depth` blocks deep in unobserved space on
/// the origin's side, so every cell of it lies d = kBlock (depth - 1) + 1 cells deep, and a ray
/// to it crosses at least d - 1 unobserved cells, and on each axis a the boundaries that its
/// slope r_a (that axis's displacement over the largest) makes it cross while it leaves them.
int unobserved_floor(const ClassBlocks& blocks, const GridSpec& spec, const Index3& b,
                     const Eigen::Vector3d& o) {
  const Index3 lo = b * kBlock;
  const Index3 hi = (lo.array() + (kBlock - 1)).min(spec.dims.array() - 1);
  const Eigen::Vector3d c_lo = spec.center(lo), c_hi = spec.center(hi);
  const Index3 oc = spec.lattice_index(o);
  // The octants the origin may lie in, seen from the block's cells: per axis, one side or both.
  int depth = 255;
  for (int oct = 0; oct < 8; ++oct) {
    bool possible = true;
    for (int a = 0; a < 3 && possible; ++a) {
      const bool higher = (oct >> a) & 1;
      possible = higher ? oc[a] >= lo[a] : oc[a] <= hi[a];
    }
    if (possible) depth = std::min<int>(depth, blocks.depth[oct][blocks.at(b)]);
  }
  if (depth == 0) return 0;
  const int d = kBlock * (depth - 1) + 1;
  Eigen::Vector3d gap, reach;
  for (int a = 0; a < 3; ++a) {
    gap[a] = std::max({0.0, c_lo[a] - o[a], o[a] - c_hi[a]});
    reach[a] = std::max(std::abs(c_lo[a] - o[a]), std::abs(c_hi[a] - o[a]));
  }
  const double largest = reach.maxCoeff();
  int crossings = 0;
  if (largest > 0.0) {
    for (int a = 0; a < 3; ++a) {
      const double r = gap[a] / largest;
      crossings += std::max(0, static_cast<int>(std::floor((d - 0.5) * r - 0.5)));
    }
  }
  return std::max(d - 1, crossings);
}

/// The unobserved cells of block `b` that some walk from `o` may reach: those open in the
/// octants the rays to the block's cells may run in (per axis one, or both), each counted once.
std::uint32_t open_toward(const ClassBlocks& blocks, const GridSpec& spec, const Index3& b,
                          const Eigen::Vector3d& o) {
  const std::size_t i = blocks.at(b);
  std::uint32_t open = 0;
  const Eigen::Vector3d c_lo = spec.center(b * kBlock);
  const Eigen::Vector3d c_hi =
      spec.center(((b.array() + 1) * kBlock - 1).min(spec.dims.array() - 1).matrix());
  for (int oct = 0; oct < 8; ++oct) {
    bool possible = true;
    for (int a = 0; a < 3 && possible; ++a) {
      possible = ((oct >> a) & 1) ? c_hi[a] > o[a] : c_lo[a] <= o[a];
    }
    if (possible) open += blocks.open[oct][i];
  }
  return std::min(open, blocks.open_any[i]);
}

}  // namespace

std::vector<double> view_upper_bounds(const ClassBlocks& blocks, const GridSpec& spec,
                                      const GainMap& map, std::span<const Frustum> views,
                                      GainQuantity quantity, double alpha) {
  if (quantity == GainQuantity::kMetric) {
    throw std::invalid_argument("view_upper_bounds: no block bounds a metric's value");
  }
  std::vector<double> bounds(views.size(), 0.0);
  const std::size_t max_depth = 3 * static_cast<std::size_t>(blocks.dims.maxCoeff() + 1) * kBlock;
  std::vector<double> powers(max_depth + 1);
  powers[0] = 1.0;
  for (std::size_t k = 1; k < powers.size(); ++k) powers[k] = powers[k - 1] * alpha;
  tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
    const Frustum& view = views[v];
    const CellBox box = cells_under(spec, view);
    if (box.empty()) return;
    const Eigen::Vector3d o = view.origin();
    // NOTE: a sensor inside unobserved space may have unobserved cells all around it: no depth
    // can be counted on then.
    const Index3 oc = spec.lattice_index(o);
    const bool deep_origin =
        spec.contains(oc) && map.value(spec.linear(oc)).state == CellState::kUnobserved;
    const double tan_h = std::tan(0.5 * view.fov().h_fov);
    const double tan_v = std::tan(0.5 * view.fov().v_fov);
    const Index3 blo(box.lo.x() >> kShift, box.lo.y() >> kShift, box.lo.z() >> kShift);
    const Index3 bhi(box.hi.x() >> kShift, box.hi.y() >> kShift, box.hi.z() >> kShift);
    double sum = 0.0;
    Index3 b;
    for (b.z() = blo.z(); b.z() <= bhi.z(); ++b.z()) {
      for (b.y() = blo.y(); b.y() <= bhi.y(); ++b.y()) {
        for (b.x() = blo.x(); b.x() <= bhi.x(); ++b.x()) {
          const std::size_t i = blocks.at(b);
          const std::uint32_t open = open_toward(blocks, spec, b, o);
          const bool all =
              quantity == GainQuantity::kPaperBits || quantity == GainQuantity::kPaperCells;
          if ((all ? blocks.unobserved[i] : open) == 0) continue;
          const Index3 lo = b * kBlock;
          const Index3 hi = (lo.array() + kBlock).min(spec.dims.array());
          if (!may_meet(view, spec.origin + lo.cast<double>() * spec.resolution,
                        spec.origin + hi.cast<double>() * spec.resolution, tan_h, tan_v)) {
            continue;
          }
          switch (quantity) {
            case GainQuantity::kSurvivalCells: {
              const int n = deep_origin ? 0 : unobserved_floor(blocks, spec, b, o);
              sum += open * powers[std::min<std::size_t>(n, max_depth)];
              break;
            }
            case GainQuantity::kCount:
              sum += open;
              break;
            case GainQuantity::kPaperCells:
              sum += blocks.unobserved[i];
              break;
            case GainQuantity::kSurvivalBits:
              sum += blocks.open_entropy[i];
              break;
            case GainQuantity::kPaperBits:
              sum += blocks.entropy[i];
              break;
            case GainQuantity::kMetric:  // refused above
              break;
          }
        }
      }
    }
    // NOTE: the exact sums add the same terms in another order; a relative margin far above
    // the rounding keeps the bound a bound.
    bounds[v] = sum * (1.0 + 1e-9) + 1e-9;
  });
  return bounds;
}

}  // namespace vantage
