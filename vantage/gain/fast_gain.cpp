#include "vantage/gain/fast_gain.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vantage/gain/ray_model.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

// ---------------------------------------------------------------------------------------------
// Snapshot

constexpr std::size_t kSnapshotChunk = std::size_t{1} << 16;

/// A total order on floats that matches numeric order for every non-NaN value.
std::uint32_t ordered_key(float f) {
  const auto b = std::bit_cast<std::uint32_t>(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float from_ordered_key(std::uint32_t k) {
  return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

template <typename Code>
void write_codes(std::span<const float> log_odds, std::span<const std::uint32_t> keys,
                 Code* codes) {
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, log_odds.size(), kSnapshotChunk), [&](const auto& r) {
        std::uint32_t last_key = ordered_key(log_odds[r.begin()]);
        auto last_code =
            static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), last_key) - keys.begin());
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint32_t key = ordered_key(log_odds[i]);
          if (key != last_key) {
            last_key = key;
            last_code =
                static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
          }
          codes[i] = last_code;
        }
      });
}

}  // namespace

GainMap::GainMap(const OccupancyGrid& grid, int num_threads)
    : spec_(grid.spec()), params_(grid.params()) {
  const std::span<const float> log_odds = grid.log_odds();
  const std::size_t n = log_odds.size();
  const std::size_t chunks = (n + kSnapshotChunk - 1) / kSnapshotChunk;
  std::vector<std::uint32_t> keys;
  run_with_threads(num_threads, [&] {
    // Distinct values per fixed chunk, then merged: the table does not depend on the threads.
    std::vector<std::vector<std::uint32_t>> distinct(chunks);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::vector<std::uint32_t>& out = distinct[c];
      const std::size_t end = std::min(n, (c + 1) * kSnapshotChunk);
      std::uint32_t last = ordered_key(log_odds[c * kSnapshotChunk]);
      out.push_back(last);
      for (std::size_t i = c * kSnapshotChunk; i < end; ++i) {
        const std::uint32_t key = ordered_key(log_odds[i]);
        if (key != last) out.push_back(last = key);
      }
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
    });
    for (const auto& part : distinct) keys.insert(keys.end(), part.begin(), part.end());
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

    values_.reserve(keys.size());
    for (const std::uint32_t key : keys) {
      const float l = from_ordered_key(key);
      Value v;
      v.p = logistic(l);  // as OccupancyGrid::probability
      v.entropy = entropy_bits(v.p);
      v.state = grid.state_of(l);
      values_.push_back(v);
    }
    code_width_ = keys.size() <= 0x100u ? 1 : (keys.size() <= 0x10000u ? 2 : 4);
    switch (code_width_) {
      case 1:
        codes8_.resize(n);
        write_codes(log_odds, keys, codes8_.data());
        break;
      case 2:
        codes16_.resize(n);
        write_codes(log_odds, keys, codes16_.data());
        break;
      default:
        codes32_.resize(n);
        write_codes(log_odds, keys, codes32_.data());
        break;
    }
  });
}

const GainMap::Value& GainMap::value(std::size_t i) const {
  switch (code_width_) {
    case 1:
      return values_[codes<std::uint8_t>()[i]];
    case 2:
      return values_[codes<std::uint16_t>()[i]];
    default:
      return values_[codes<std::uint32_t>()[i]];
  }
}

namespace {

// ---------------------------------------------------------------------------------------------
// What the rays read: per code the cell's occupancy and class; per block of kBlock^3 cells its
// code when all its cells share one, and how far around it every block does too.

constexpr int kBlockShift = 1;
constexpr int kBlock = 1 << kBlockShift;
constexpr std::uint16_t kMixed = 0xffff;

/// Cells of the exact ray replayed before a credited cell (docs/fast-gain.md).
constexpr int kReplayCells = 8;
/// A pinned cell is left uncredited, and a pinned ray jumps, only this many blocks inside a
/// uniform region: kSkipMargin * kBlock >= kReplayCells keeps every replay window inside it.
constexpr int kSkipMargin = 4;
static_assert(kSkipMargin * kBlock >= kReplayCells);
/// States kept along a ray for the replays, a power of two above kReplayCells.
constexpr int kHistory = 16;
/// A ray jumps a uniform region only once its state lies this close to the region's steady state.
constexpr double kSteadyTolerance = 1e-5;

struct Code {
  double p, q;  // occupancy and 1 - p
  double entropy;
  CellState state;
};

struct Blocks {
  Index3 dims;
  std::vector<std::uint16_t> code;       // the code all cells share, or kMixed
  std::vector<std::uint8_t> radius;      // the cube of blocks within this distance shares `code`
  std::vector<std::uint8_t> unobserved;  // the block holds an unobserved cell

  std::size_t index(const Index3& cell) const {
    return static_cast<std::size_t>(cell.x() >> kBlockShift) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(cell.y() >> kBlockShift) +
                static_cast<std::size_t>(dims.y()) *
                    static_cast<std::size_t>(cell.z() >> kBlockShift));
  }
};

template <typename CodeT>
Blocks summarize_blocks(const GridSpec& spec, const CodeT* codes, const std::vector<Code>& table) {
  Blocks blocks;
  blocks.dims = (spec.dims.array() + (kBlock - 1)) / kBlock;
  const Index3& bd = blocks.dims;
  const std::size_t n = static_cast<std::size_t>(bd.x()) * bd.y() * bd.z();
  blocks.code.assign(n, kMixed);
  blocks.radius.assign(n, 0);
  blocks.unobserved.assign(n, 0);
  tbb::parallel_for(0, bd.z(), [&](int bz) {
    for (int by = 0; by < bd.y(); ++by) {
      for (int bx = 0; bx < bd.x(); ++bx) {
        const Index3 lo(bx * kBlock, by * kBlock, bz * kBlock);
        const Index3 hi = (lo.array() + kBlock).min(spec.dims.array());
        const std::size_t first = spec.linear(lo);
        const auto code = static_cast<std::uint32_t>(codes[first]);
        bool uniform = code < kMixed;
        bool unobserved = false;
        for (int z = lo.z(); z < hi.z(); ++z) {
          for (int y = lo.y(); y < hi.y(); ++y) {
            const std::size_t row = spec.linear(Index3(lo.x(), y, z));
            for (int x = 0; x < hi.x() - lo.x(); ++x) {
              const auto c = codes[row + static_cast<std::size_t>(x)];
              uniform = uniform && c == codes[first];
              unobserved = unobserved || table[c].state == CellState::kUnobserved;
            }
          }
        }
        const std::size_t b =
            static_cast<std::size_t>(bx) +
            bd.x() * (static_cast<std::size_t>(by) + bd.y() * static_cast<std::size_t>(bz));
        if (uniform) blocks.code[b] = static_cast<std::uint16_t>(code);
        blocks.unobserved[b] = unobserved ? 1 : 0;
      }
    }
  });
  // A block is on a border when it is mixed, or a neighbour holds another code or lies outside
  // the grid. The radius is the
  // chessboard distance to the nearest border block (two chamfer passes, 26 neighbours): all
  // blocks within it share the block's code, because blocks off the border share their
  // neighbours' codes.
  constexpr std::uint8_t kFar = 255;
  std::vector<std::uint8_t> dist(n, kFar);
  auto at = [&](int x, int y, int z) {
    return static_cast<std::size_t>(x) +
           bd.x() * (static_cast<std::size_t>(y) + bd.y() * static_cast<std::size_t>(z));
  };
  for (int z = 0; z < bd.z(); ++z) {
    for (int y = 0; y < bd.y(); ++y) {
      for (int x = 0; x < bd.x(); ++x) {
        const std::uint16_t c = blocks.code[at(x, y, z)];
        bool border = c == kMixed;
        for (int dz = -1; dz <= 1 && !border; ++dz) {
          for (int dy = -1; dy <= 1 && !border; ++dy) {
            for (int dx = -1; dx <= 1 && !border; ++dx) {
              const int nx = x + dx, ny = y + dy, nz = z + dz;
              // Outside the grid counts as another code: rays come from there as free space.
              border = nx < 0 || ny < 0 || nz < 0 || nx >= bd.x() || ny >= bd.y() || nz >= bd.z() ||
                       blocks.code[at(nx, ny, nz)] != c;
            }
          }
        }
        if (border) dist[at(x, y, z)] = 0;
      }
    }
  }
  for (const int dir : {1, -1}) {
    const int z0 = dir > 0 ? 0 : bd.z() - 1, y0 = dir > 0 ? 0 : bd.y() - 1,
              x0 = dir > 0 ? 0 : bd.x() - 1;
    for (int z = z0; z >= 0 && z < bd.z(); z += dir) {
      for (int y = y0; y >= 0 && y < bd.y(); y += dir) {
        for (int x = x0; x >= 0 && x < bd.x(); x += dir) {
          std::uint8_t& d = dist[at(x, y, z)];
          for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
              for (int dx = -1; dx <= 1; ++dx) {
                // Only the neighbours this pass has already visited.
                const int order = dir * (dz * 9 + dy * 3 + dx);
                if (order >= 0) continue;
                const int nx = x + dx, ny = y + dy, nz = z + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= bd.x() || ny >= bd.y() || nz >= bd.z()) {
                  continue;
                }
                const std::uint8_t nd = dist[at(nx, ny, nz)];
                if (nd < kFar && nd + 1 < d) d = static_cast<std::uint8_t>(nd + 1);
              }
            }
          }
        }
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    blocks.radius[i] = blocks.code[i] == kMixed ? 0 : dist[i];
  }
  return blocks;
}

// ---------------------------------------------------------------------------------------------
// Rays

/// Views share rays when they share an origin; a group holds at most this many.
constexpr int kMaxGroup = 8;
/// A group's pinhole image reaches at most this far off its axis (tan 70 deg).
constexpr double kMaxImageTan = 2.7474774194546216;

/// The rays of views that share an origin: a pinhole image in the group's frame whose pixel
/// (col, row) has its ray through u = u0 + (col + 0.5) du, v = v0 + (row + 0.5) du on the plane
/// x = 1. The window covers every member's field of view, cut to the grid's image.
struct RayGroup {
  std::vector<std::size_t> members;  // view indices
  std::vector<const Frustum*> views;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();   // world <- group frame
  Eigen::Matrix3d Rt = Eigen::Matrix3d::Identity();  // group frame <- world
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double u0 = 0, v0 = 0, du = 1;
  int cols = 0, rows = 0;
  double reach = 0;  // farthest distance a credited cell's point can lie from the origin [m]
  Index3 origin_cell = Index3::Zero();
  bool origin_inside = false;
};

/// Extends [u_lo, u_hi] x [v_lo, v_hi] by the image corners of a view's field of view in the
/// frame `Rt`. False, leaving the bounds incomplete, when a corner lies behind the frame or, with
/// `limit`, more than kMaxImageTan off its axis.
bool fov_corners(const Frustum& view, const Eigen::Matrix3d& Rt, bool limit, double& u_lo,
                 double& u_hi, double& v_lo, double& v_hi) {
  const double th = std::tan(view.fov().h_fov / 2.0), tv = std::tan(view.fov().v_fov / 2.0);
  const Eigen::Matrix3d R = Rt * view.T_world_sensor().linear();
  for (const double sy : {-1.0, 1.0}) {
    for (const double sz : {-1.0, 1.0}) {
      const Eigen::Vector3d d = R * Eigen::Vector3d(1.0, sy * th, sz * tv);
      if (d.x() <= 0.0) return false;
      const double u = d.y() / d.x(), v = d.z() / d.x();
      if (limit && (std::abs(u) > kMaxImageTan || std::abs(v) > kMaxImageTan)) return false;
      u_lo = std::min(u_lo, u);
      u_hi = std::max(u_hi, u);
      v_lo = std::min(v_lo, v);
      v_hi = std::max(v_hi, v);
    }
  }
  return true;
}

/// The frame looking along the mean of the members' axes.
Eigen::Matrix3d group_frame(std::span<const Frustum* const> views) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), z = Eigen::Vector3d::Zero();
  for (const Frustum* v : views) {
    x += v->T_world_sensor().linear().col(0);
    z += v->T_world_sensor().linear().col(2);
  }
  if (x.norm() < 1e-9) return views.front()->T_world_sensor().linear();
  x.normalize();
  z -= z.dot(x) * x;
  if (z.norm() < 1e-9) return views.front()->T_world_sensor().linear();
  z.normalize();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

/// Whether the views fit one pinhole image in their mean frame.
bool fits(std::span<const Frustum* const> views) {
  const Eigen::Matrix3d Rt = group_frame(views).transpose();
  double u_lo = 1e300, u_hi = -1e300, v_lo = 1e300, v_hi = -1e300;
  for (const Frustum* v : views) {
    if (!fov_corners(*v, Rt, /*limit=*/true, u_lo, u_hi, v_lo, v_hi)) return false;
  }
  return true;
}

/// Views grouped by origin, in order of first appearance.
std::vector<RayGroup> group_views(std::span<const Frustum> views) {
  std::vector<RayGroup> groups;
  for (std::size_t i = 0; i < views.size(); ++i) {
    bool placed = false;
    for (RayGroup& g : groups) {
      if (g.members.size() >= static_cast<std::size_t>(kMaxGroup) ||
          g.views.front()->origin() != views[i].origin() ||
          g.views.front()->fov().max_range != views[i].fov().max_range) {
        continue;
      }
      std::vector<const Frustum*> trial = g.views;
      trial.push_back(&views[i]);
      if (!fits(trial)) continue;
      g.views = std::move(trial);
      g.members.push_back(i);
      placed = true;
      break;
    }
    if (!placed) {
      RayGroup g;
      g.members = {i};
      g.views = {&views[i]};
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

void lay_out_rays(const GridSpec& spec, double ray_spacing, RayGroup& rays) {
  rays.R = group_frame(rays.views);
  rays.Rt = rays.R.transpose();
  rays.origin = rays.views.front()->origin();
  rays.origin_cell = spec.lattice_index(rays.origin);
  rays.origin_inside = spec.contains(rays.origin_cell);
  double u_lo = 1e300, u_hi = -1e300, v_lo = 1e300, v_hi = -1e300;
  double max_range = 0.0;
  for (const Frustum* v : rays.views) {
    // Members other than the first fit the limit (fits()); the first may be wider than it, alone
    // in its group, and its image must still cover all of it. SensorFov keeps every corner in
    // front of a lone view.
    fov_corners(*v, rays.Rt, /*limit=*/false, u_lo, u_hi, v_lo, v_hi);
    max_range = std::max(max_range, v->fov().max_range);
  }

  // The grid's corners in the group frame: the deepest one sets the ray pitch, and when all lie
  // in front of the sensor their image bounds the window.
  double depth = 0.0;
  bool all_in_front = true;
  double cu_lo = 1e300, cu_hi = -1e300, cv_lo = 1e300, cv_hi = -1e300;
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                                 (k & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d p = rays.Rt * (corner - rays.origin);
    depth = std::max(depth, p.x());
    if (p.x() <= 1e-9) {
      all_in_front = false;
      continue;
    }
    cu_lo = std::min(cu_lo, p.y() / p.x());
    cu_hi = std::max(cu_hi, p.y() / p.x());
    cv_lo = std::min(cv_lo, p.z() / p.x());
    cv_hi = std::max(cv_hi, p.z() / p.x());
  }
  if (all_in_front) {
    u_lo = std::max(u_lo, cu_lo);
    u_hi = std::min(u_hi, cu_hi);
    v_lo = std::max(v_lo, cv_lo);
    v_hi = std::min(v_hi, cv_hi);
  }
  depth = std::min(depth, max_range);
  if (depth <= 0.0 || u_hi <= u_lo || v_hi <= v_lo) return;  // no rays

  // NOTE: at depth x neighbouring rays lie x * du apart; a cell's inscribed ball has radius
  // res / 2, and the ray nearest a cell's centre passes within x * du / sqrt(2) of it. So
  // du = spacing * res / depth with spacing <= 1/sqrt(2) makes the owning ray cross its cell.
  rays.du = ray_spacing * spec.resolution / depth;
  rays.u0 = u_lo;
  rays.v0 = v_lo;
  rays.cols = static_cast<int>(std::ceil((u_hi - u_lo) / rays.du));
  rays.rows = static_cast<int>(std::ceil((v_hi - v_lo) / rays.du));
  rays.reach = max_range + spec.resolution * 0.8660254037844386;
}

/// Rays are cast by tiles of kTile x kTile pixels, and only in tiles whose pixels may own an
/// unobserved cell.
constexpr int kTile = 8;

/// Marks the tiles of a group's image that the image of some block holding an unobserved cell
/// touches: a credited cell lies in its owner's pixel, so rays elsewhere cannot credit anything.
std::vector<std::uint8_t> live_tiles(const GridSpec& spec, const Blocks& blocks,
                                     const RayGroup& rays) {
  const int tiles_x = (rays.cols + kTile - 1) / kTile, tiles_y = (rays.rows + kTile - 1) / kTile;
  std::vector<std::uint8_t> live(static_cast<std::size_t>(tiles_x) * tiles_y, 0);
  if (live.empty()) return live;
  // Boxes of kBox^3 blocks (4^3 cells): fewer projections, still a tight mask.
  constexpr int kBox = 4 / kBlock;
  const Index3 bd = blocks.dims;
  const double edge = kBlock * spec.resolution;
  for (int z = 0; z < bd.z(); z += kBox) {
    for (int y = 0; y < bd.y(); y += kBox) {
      for (int x = 0; x < bd.x(); x += kBox) {
        bool any = false;
        for (int bz = z; bz < std::min(z + kBox, bd.z()) && !any; ++bz) {
          for (int by = y; by < std::min(y + kBox, bd.y()) && !any; ++by) {
            for (int bx = x; bx < std::min(x + kBox, bd.x()) && !any; ++bx) {
              any = blocks.unobserved[static_cast<std::size_t>(bx) +
                                      bd.x() * (static_cast<std::size_t>(by) +
                                                bd.y() * static_cast<std::size_t>(bz))] != 0;
            }
          }
        }
        if (!any) continue;
        const Eigen::Vector3d lo = spec.origin + Eigen::Vector3d(x, y, z) * edge;
        double c_lo = 1e300, c_hi = -1e300, r_lo = 1e300, r_hi = -1e300;
        for (int k = 0; k < 8; ++k) {
          const Eigen::Vector3d corner =
              lo + kBox * edge * Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1);
          const Eigen::Vector3d p = rays.Rt * (corner - rays.origin);
          if (p.x() <= 1e-9) {  // too close to call: every tile
            std::fill(live.begin(), live.end(), std::uint8_t{1});
            return live;
          }
          const double u = (p.y() / p.x() - rays.u0) / rays.du;
          const double v = (p.z() / p.x() - rays.v0) / rays.du;
          c_lo = std::min(c_lo, u);
          c_hi = std::max(c_hi, u);
          r_lo = std::min(r_lo, v);
          r_hi = std::max(r_hi, v);
        }
        if (c_hi < -1.0 || c_lo > rays.cols + 1.0 || r_hi < -1.0 || r_lo > rays.rows + 1.0) {
          continue;
        }
        const auto tile = [](double pixel, int n) {
          return std::clamp(static_cast<int>(std::floor(pixel)), 0, n - 1) / kTile;
        };
        const int tx0 = tile(c_lo - 1.0, rays.cols), tx1 = tile(c_hi + 1.0, rays.cols);
        const int ty0 = tile(r_lo - 1.0, rays.rows), ty1 = tile(r_hi + 1.0, rays.rows);
        for (int ty = ty0; ty <= ty1; ++ty) {
          std::fill_n(live.begin() + static_cast<std::ptrdiff_t>(ty) * tiles_x + tx0, tx1 - tx0 + 1,
                      std::uint8_t{1});
        }
      }
    }
  }
  return live;
}

/// Everything the rays of one evaluation share.
struct Shared {
  const GainMap* map = nullptr;
  const GridSpec* spec = nullptr;
  const Code* codes = nullptr;
  Blocks blocks;
  std::vector<double> t;              // a^m
  std::vector<detail::Odds> outside;  // outside[k]: the state after k cells of p_min, k >= 1
  std::vector<std::vector<detail::Odds>> steady;  // per code, the state after m + 1 cells of it
  double p_min = 0.12;
  double epsilon = 0.0;
};

/// One ray's contribution to each member of its group.
struct RaySum {
  double gain[kMaxGroup] = {};
  std::size_t targets[kMaxGroup] = {};

  void add(const RaySum& o, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      gain[i] += o.gain[i];
      targets[i] += o.targets[i];
    }
  }
};

/// An exact Amanatides–Woo walk along o + s * dir between two cells, with m counted from the
/// origin's cell. The state lives in scalars and each step picks its axis without a branch: the
/// axis choice is data-dependent and would mispredict on every diagonal ray.
struct Walk {
  Index3 cell;
  std::ptrdiff_t linear = 0;
  int m = 0;
  double tx = 0, ty = 0, tz = 0;  // ray parameter of the next boundary per axis; inf when done
  double dx = 0, dy = 0, dz = 0;  // parameter between boundaries per axis
  int rx = 0, ry = 0, rz = 0;     // steps left per axis
  int sx = 0, sy = 0, sz = 0;     // +1 or -1
  std::ptrdiff_t lx = 0, ly = 0, lz = 0;  // signed linear strides

  int step(int a) const { return a == 0 ? sx : (a == 1 ? sy : sz); }

  /// Starts in `first`, a cell the ray crosses, and ends in `last`.
  void start(const GridSpec& spec, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
             const Index3& first, const Index3& last, const Index3& origin_cell) {
    cell = first;
    const std::ptrdiff_t strides[3] = {1, spec.dims.x(),
                                       static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y()};
    double t_max[3], t_delta[3];
    int steps[3], left[3];
    for (int a = 0; a < 3; ++a) {
      steps[a] = dir[a] > 0.0 ? 1 : -1;
      left[a] = std::max(0, (last[a] - cell[a]) * steps[a]);
      if (dir[a] == 0.0 || left[a] == 0) {
        t_max[a] = std::numeric_limits<double>::infinity();
        t_delta[a] = 0.0;
        left[a] = 0;
        continue;
      }
      t_delta[a] = spec.resolution / std::abs(dir[a]);
      const double boundary = spec.origin[a] + (cell[a] + (steps[a] > 0 ? 1 : 0)) * spec.resolution;
      t_max[a] = (boundary - o[a]) / dir[a];
    }
    tx = t_max[0], ty = t_max[1], tz = t_max[2];
    dx = t_delta[0], dy = t_delta[1], dz = t_delta[2];
    rx = left[0], ry = left[1], rz = left[2];
    sx = steps[0], sy = steps[1], sz = steps[2];
    lx = sx * strides[0], ly = sy * strides[1], lz = sz * strides[2];
    m = (cell - origin_cell).cwiseAbs().sum();
    linear = static_cast<std::ptrdiff_t>(spec.linear(cell));
  }

  /// Moves to the next cell; false at the end. Always inlined: GCC kept it a call, about a tenth
  /// of the fast mode's time on 80 M steps.
  [[gnu::always_inline]] bool advance() {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const double t = std::min(tx, std::min(ty, tz));
    if (t == kInf) return false;  // no axis has steps left
    const bool x = tx == t;
    const bool y = !x && ty == t;
    const bool z = !x && !y;
    cell.x() += x ? sx : 0;
    cell.y() += y ? sy : 0;
    cell.z() += z ? sz : 0;
    linear += x ? lx : (y ? ly : lz);
    rx -= x;
    ry -= y;
    rz -= z;
    tx = x ? (rx > 0 ? tx + dx : kInf) : tx;
    ty = y ? (ry > 0 ? ty + dy : kInf) : ty;
    tz = z ? (rz > 0 ? tz + dz : kInf) : tz;
    ++m;
    return true;
  }
};

/// The ray parameter range [s_in, s_out] inside the grid's box, clipped to [0, s_max].
bool clip_to_grid(const GridSpec& spec, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                  double s_max, double& s_in, double& s_out) {
  s_in = 0.0;
  s_out = s_max;
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (o[a] < lo[a] || o[a] >= hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - o[a]) / dir[a];
    double t1 = (hi[a] - o[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    s_in = std::max(s_in, t0);
    s_out = std::min(s_out, t1);
  }
  return s_in < s_out;
}

Index3 cell_at(const GridSpec& spec, const Eigen::Vector3d& p) {
  return spec.lattice_index(p).cwiseMax(Index3::Zero()).cwiseMin(spec.dims - Index3::Ones());
}

/// entropy_bits, by its series about 1/2 where most replayed cells lie (error below 1e-13 there):
/// H(1/2 + x) = 1 - (1 / ln 2) sum_n (2x)^2n / (2n (2n - 1)).
inline double entropy_near_half(double q) {
  const double y = 4.0 * (q - 0.5) * (q - 0.5);  // (2x)^2
  if (y > 1e-4) return entropy_bits(q);
  return 1.0 - (y / 2.0 + y * y / 12.0 + y * y * y / 30.0) / std::numbers::ln2;
}

/// A state along the carrying ray, kept for the replays.
struct Kept {
  detail::Odds odds;
  double p;  // occupancy of the cell
};

/// The gain of a credited cell: the exact ray to its centre, replayed over its last cells from the
/// state the carrying ray had there (docs/fast-gain.md).
template <typename CodeT>
double replay(const Shared& sh, const CodeT* codes, const RayGroup& rays, const Kept* history,
              int ray_m0, const Index3& target, int m_target) {
  const GridSpec& spec = *sh.spec;
  const Eigen::Vector3d c = spec.center(target);
  const Eigen::Vector3d delta = c - rays.origin;
  const double cells = delta.cwiseAbs().sum() / spec.resolution;
  double s_from = m_target <= kReplayCells ? 0.0 : std::max(0.0, 1.0 - kReplayCells / cells);
  bool from_outside = false;
  if (!spec.contains(spec.lattice_index(rays.origin + s_from * delta))) {
    // The window starts before the grid: the cells there are free, a table lookup.
    double s_in = 0.0, s_out = 1.0;
    clip_to_grid(spec, rays.origin, delta, 1.0, s_in, s_out);
    s_from = std::max(s_from, s_in);
    from_outside = true;
  }
  Walk walk;
  walk.start(spec, rays.origin, delta, cell_at(spec, rays.origin + s_from * delta), target,
             rays.origin_cell);
  detail::Odds odds;
  double p_prev = sh.p_min;
  bool first = walk.m == 0;
  if (!first) {
    const int before = walk.m - 1;
    if (from_outside || before < ray_m0 || m_target - before >= kHistory) {
      odds = sh.outside[static_cast<std::size_t>(walk.m)];
    } else {
      const Kept& kept = history[before & (kHistory - 1)];
      odds = kept.odds;
      p_prev = kept.p;
    }
  }
  const Code* code = nullptr;
  for (;;) {
    code = &sh.codes[codes[walk.linear]];
    if (first) {
      odds = detail::Odds(1.0, code->p);  // the origin's cell
      first = false;
    } else {
      odds.step(sh.t[static_cast<std::size_t>(walk.m)], p_prev, code->p);
      if ((walk.m & 7) == 0) odds.renormalize();
    }
    p_prev = code->p;
    if (!walk.advance()) break;
  }
  return code->entropy - entropy_near_half(odds.posterior());  // eq. (4)
}

/// Moves `walk` to the last cell along the ray inside the cube of uniform blocks around its
/// cell, shrunk by `margin` blocks, when that skips at least two cells; [s_in, s_out] bounds the
/// ray.
bool jump_uniform(const GridSpec& spec, const Blocks& blocks, const Eigen::Vector3d& o,
                  const Eigen::Vector3d& dir, double s_in, double s_out, const Index3& last,
                  const Index3& origin_cell, int margin, Walk& walk) {
  const std::size_t block = blocks.index(walk.cell);
  const int r = blocks.radius[block] - margin;
  if (r < 0) return false;
  double s_exit = s_out;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) continue;
    const int b = (walk.cell[a] >> kBlockShift) + (dir[a] > 0.0 ? r + 1 : -r);
    const double plane = spec.origin[a] + std::clamp(b * kBlock, 0, spec.dims[a]) * spec.resolution;
    s_exit = std::min(s_exit, (plane - o[a]) / dir[a]);
  }
  const double s_land = s_exit - 1e-9 * (s_exit - s_in + 1.0);
  Index3 land = cell_at(spec, o + s_land * dir);
  // Stay within the uniform cube and never step back.
  for (int a = 0; a < 3; ++a) {
    land[a] = walk.step(a) > 0 ? std::clamp(land[a], walk.cell[a], last[a])
                               : std::clamp(land[a], last[a], walk.cell[a]);
  }
  if ((land - origin_cell).cwiseAbs().sum() <= walk.m + 1) return false;
  walk.start(spec, o, dir, land, last, origin_cell);
  return true;
}

/// The footprint of one pixel in the plane x = 1 of its group's frame, widened to infinity on
/// the border of the image, so that every point in front of the sensor has exactly one owner.
struct Footprint {
  double u_lo, u_hi, v_lo, v_hi;

  Footprint(const RayGroup& rays, int col, int row) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    // NOTE: a shared edge is the same expression for both pixels beside it, so the comparisons
    // in owns() split the points between them exactly.
    u_lo = col == 0 ? -kInf : rays.u0 + col * rays.du;
    u_hi = col == rays.cols - 1 ? kInf : rays.u0 + (col + 1) * rays.du;
    v_lo = row == 0 ? -kInf : rays.v0 + row * rays.du;
    v_hi = row == rays.rows - 1 ? kInf : rays.v0 + (row + 1) * rays.du;
  }

  /// Whether the image of a point holds in this footprint: the point in the group frame is
  /// compared against the footprint scaled to its depth, without a division.
  bool owns(const RayGroup& rays, const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d p = rays.Rt * (p_world - rays.origin);
    return p.x() > 0.0 && p.y() >= u_lo * p.x() && p.y() < u_hi * p.x() && p.z() >= v_lo * p.x() &&
           p.z() < v_hi * p.x();
  }
};

template <typename CodeT>
RaySum cast_ray(const Shared& sh, const CodeT* codes, const RayGroup& rays, int col, int row) {
  RaySum sum;
  const GridSpec& spec = *sh.spec;
  const Eigen::Vector3d dir = rays.R * Eigen::Vector3d(1.0, rays.u0 + (col + 0.5) * rays.du,
                                                       rays.v0 + (row + 0.5) * rays.du);
  const Eigen::Vector3d& o = rays.origin;
  double s_in, s_out;
  if (!clip_to_grid(spec, o, dir, rays.reach / dir.norm(), s_in, s_out)) return sum;
  const Index3 last = cell_at(spec, o + s_out * dir);
  Walk walk;
  walk.start(spec, o, dir, rays.origin_inside ? rays.origin_cell : cell_at(spec, o + s_in * dir),
             last, rays.origin_cell);
  const int m0 = walk.m;
  const Footprint footprint(rays, col, row);

  const double eps = sh.epsilon;
  std::size_t last_block = std::numeric_limits<std::size_t>::max();
  Kept history[kHistory];
  detail::Odds odds;
  double p_prev = sh.p_min;
  if (m0 > 0) odds = sh.outside[static_cast<std::size_t>(m0)];
  for (;;) {
    const auto code_index = static_cast<std::size_t>(codes[walk.linear]);
    const Code& code = sh.codes[code_index];
    {
      if (walk.m == 0) {
        odds = detail::Odds(1.0, code.p);  // the origin's cell: v_0 = 1, q_0 = p_0
      } else {
        odds.step(sh.t[static_cast<std::size_t>(walk.m)], p_prev, code.p);
        if ((walk.m & 7) == 0) odds.renormalize();
      }
      p_prev = code.p;
      history[walk.m & (kHistory - 1)] = {odds, code.p};
    }
    // A pinned cell deep in a uniform region gains nothing: within kSkipMargin blocks of it every
    // cell has its code, so its exact ray's last cells evolve exactly as this ray's did. Nearer a
    // border its own ray may graze known space and be re-armed, so it is replayed.
    const std::size_t block = sh.blocks.index(walk.cell);
    const bool deep = sh.blocks.code[block] == code_index && sh.blocks.radius[block] >= kSkipMargin;
    if (code.state == CellState::kUnobserved && !(deep && odds.pinned(eps))) {
      const Eigen::Vector3d c = spec.center(walk.cell);
      if (footprint.owns(rays, c)) {
        double g = 0.0;  // replayed once, for the first member that holds the cell
        bool replayed = false;
        for (std::size_t k = 0; k < rays.views.size(); ++k) {
          if (!rays.views[k]->contains(c)) continue;
          if (!replayed) {
            g = replay(sh, codes, rays, history, m0, walk.cell, walk.m);
            replayed = true;
          }
          sum.gain[k] += g;
          ++sum.targets[k];
        }
      }
    }
    if (odds.hidden(eps)) break;

    // A uniform region the state has settled in predicts nothing new until it ends: jump to its
    // last cell along the ray, with the state the table holds there.
    const bool new_block = block != last_block;
    last_block = block;
    if (new_block && sh.blocks.code[block] == code_index &&
        (code.state == CellState::kFree ||
         (code.state == CellState::kUnobserved && odds.pinned(eps)))) {
      const auto& steady = sh.steady[code_index];
      // |v - v_f| and |q - q_f| below the tolerance; f sums to 1 in both pairs.
      const detail::Odds& f = steady[static_cast<std::size_t>(walk.m)];
      const bool settled =
          std::abs(odds.n * f.d - odds.d * f.n) < kSteadyTolerance * (odds.n + odds.d) &&
          std::abs(odds.a * f.b - odds.b * f.a) < kSteadyTolerance * (odds.a + odds.b);
      if (settled && jump_uniform(spec, sh.blocks, o, dir, s_in, s_out, last, rays.origin_cell,
                                  code.state == CellState::kFree ? 0 : kSkipMargin, walk)) {
        odds = steady[static_cast<std::size_t>(walk.m)];
        for (int k = 0; k < kHistory && walk.m - k >= m0; ++k) {
          const int m = walk.m - k;
          history[m & (kHistory - 1)] = {steady[static_cast<std::size_t>(m)], code.p};
        }
        continue;  // the landing cell has the same code: nothing new to credit there
      }
    }
    if (!walk.advance()) break;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// The cheaper evaluation (GainEvaluation::kAuto). The exact mode's work follows the unobserved
// cells in view, times the length of their rays; the fast mode's follows its rays, whatever is
// left unobserved. Both are counted before any ray is cast, so the choice is a function of the
// map state and the views alone: deterministic, and the same for any thread count.

/// Unobserved cells are sampled on every kCostStride-th cell along each axis.
constexpr int kCostStride = 3;
/// Cost of one cell step of the exact mode in units of one ray of the fast mode: 4.4 ns against
/// 2.0 us of CPU, each within 15% over the built-in table tops after 1, 3 and 6 scans. Since the
/// rays got 20% cheaper the measured ratio is 2.2e-3 to 2.7e-3; the states it would decide
/// differently lie within 6% of each other in both modes (BENCHMARK.md, "The built-in scenes").
constexpr double kExactStepPerRay = 2.2e-3;

/// Whether the exact evaluation of `views` costs less than casting the rays of `groups` through
/// their `live` tiles.
bool exact_is_cheaper(const GainMap& map, std::span<const Frustum> views,
                      std::span<const RayGroup> groups,
                      std::span<const std::vector<std::uint8_t>> live) {
  double fast_rays = 0.0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const int tiles_x = (groups[g].cols + kTile - 1) / kTile;
    for (std::size_t i = 0; i < live[g].size(); ++i) {
      if (live[g][i] == 0) continue;
      const int tx = static_cast<int>(i % static_cast<std::size_t>(tiles_x));
      const int ty = static_cast<int>(i / static_cast<std::size_t>(tiles_x));
      fast_rays += static_cast<double>(std::min(kTile, groups[g].cols - tx * kTile)) *
                   std::min(kTile, groups[g].rows - ty * kTile);
    }
  }
  const GridSpec& spec = map.spec();
  std::vector<double> per_view(views.size(), 0.0);
  tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
    const Frustum& view = views[v];
    const Index3 origin = spec.lattice_index(view.origin());
    const detail::CellBox box = detail::cells_under(spec, view);
    double steps = 0.0;
    Index3 c;
    for (c.z() = box.lo.z(); c.z() <= box.hi.z(); c.z() += kCostStride) {
      for (c.y() = box.lo.y(); c.y() <= box.hi.y(); c.y() += kCostStride) {
        for (c.x() = box.lo.x(); c.x() <= box.hi.x(); c.x() += kCostStride) {
          if (map.value(spec.linear(c)).state != CellState::kUnobserved ||
              !view.contains(spec.center(c))) {
            continue;
          }
          steps += (c - origin).cwiseAbs().sum();  // a 6-connected ray: one cell per step
        }
      }
    }
    per_view[v] = steps * kCostStride * kCostStride * kCostStride;
  });
  double exact_steps = 0.0;
  for (const double steps : per_view) exact_steps += steps;
  return exact_steps * kExactStepPerRay < fast_rays;
}

/// The fast evaluation; with `pick_cheaper` it first weighs it against the exact one and returns
/// that when it is cheaper (exact_is_cheaper).
template <typename CodeT>
std::vector<ViewGain> evaluate(const GainMap& map, std::span<const Frustum> views,
                               const GainConfig& config, bool pick_cheaper) {
  const GridSpec& spec = map.spec();
  const RayModel model(config.alpha);
  std::vector<RayGroup> groups = group_views(views);
  int max_cells = 1;
  for (RayGroup& g : groups) {
    lay_out_rays(spec, config.ray_spacing, g);
    max_cells = std::max(max_cells, max_ray_cells(spec, g.origin));
  }

  Shared sh;
  sh.map = &map;
  sh.spec = &spec;
  sh.p_min = map.params().p_min;
  sh.epsilon = config.epsilon;
  std::vector<Code> code_table;
  for (const GainMap::Value& v : map.values())
    code_table.push_back({v.p, 1.0 - v.p, v.entropy, v.state});
  sh.codes = code_table.data();
  const CodeT* codes = map.codes<CodeT>();
  sh.blocks = summarize_blocks(spec, codes, code_table);
  std::vector<std::vector<std::uint8_t>> live(groups.size());
  tbb::parallel_for(std::size_t{0}, groups.size(),
                    [&](std::size_t g) { live[g] = live_tiles(spec, sh.blocks, groups[g]); });
  if (pick_cheaper && exact_is_cheaper(map, views, groups, live)) {
    return exact_view_gains(map, views, config);
  }

  sh.t.resize(static_cast<std::size_t>(max_cells) + 1);
  sh.t[0] = 1.0;
  for (std::size_t m = 1; m < sh.t.size(); ++m) sh.t[m] = sh.t[m - 1] * config.alpha;
  {
    const UniformPrefix outside(model, sh.p_min, max_cells + 1);
    sh.outside.resize(static_cast<std::size_t>(max_cells) + 1);
    for (int k = 1; k <= max_cells; ++k)
      sh.outside[static_cast<std::size_t>(k)] = detail::Odds(outside.at(k));
  }
  // Steady states of the codes that fill whole blocks.
  sh.steady.resize(code_table.size());
  {
    std::vector<bool> wanted(code_table.size(), false);
    for (const std::uint16_t c : sh.blocks.code) {
      if (c != kMixed && code_table[c].state != CellState::kOccupied) wanted[c] = true;
    }
    for (std::size_t c = 0; c < code_table.size(); ++c) {
      if (!wanted[c]) continue;
      const UniformPrefix run(model, code_table[c].p, max_cells + 1);
      auto& table = sh.steady[c];
      table.resize(static_cast<std::size_t>(max_cells) + 1);
      for (int m = 0; m <= max_cells; ++m)
        table[static_cast<std::size_t>(m)] = detail::Odds(run.at(m + 1));
    }
  }

  // One task per image row of every group; row sums are added per view in row order.
  std::vector<std::size_t> first_row(groups.size() + 1, 0);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    first_row[i + 1] = first_row[i] + static_cast<std::size_t>(groups[i].rows);
  }
  std::vector<RaySum> row_sums(first_row.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, row_sums.size()), [&](const auto& range) {
    std::size_t view = static_cast<std::size_t>(
        std::upper_bound(first_row.begin(), first_row.end(), range.begin()) - first_row.begin() -
        1);
    for (std::size_t r = range.begin(); r != range.end(); ++r) {
      while (r >= first_row[view + 1]) ++view;
      const RayGroup& rays = groups[view];
      const int row = static_cast<int>(r - first_row[view]);
      RaySum sum;
      const std::uint8_t* tiles = live[view].data() + static_cast<std::ptrdiff_t>(row / kTile) *
                                                          ((rays.cols + kTile - 1) / kTile);
      for (int col = 0; col < rays.cols; ++col) {
        if (tiles[col / kTile] == 0) {
          col += kTile - 1 - col % kTile;  // the rest of this tile
          continue;
        }
        sum.add(cast_ray(sh, codes, rays, col, row), rays.members.size());
      }
      row_sums[r] = sum;
    }
  });

  std::vector<ViewGain> gains(views.size());
  for (std::size_t i = 0; i < groups.size(); ++i) {
    for (std::size_t r = first_row[i]; r < first_row[i + 1]; ++r) {
      for (std::size_t k = 0; k < groups[i].members.size(); ++k) {
        ViewGain& g = gains[groups[i].members[k]];
        g.gain += row_sums[r].gain[k];
        g.targets += row_sums[r].targets[k];
      }
    }
  }
  return gains;
}

std::vector<ViewGain> evaluate_any_width(const GainMap& map, std::span<const Frustum> views,
                                         const GainConfig& config, bool pick_cheaper) {
  config.validate();
  if (config.method == GainMethod::kGreedy) return exact_view_gains(map, views, config);
  std::vector<ViewGain> gains;
  run_with_threads(config.num_threads, [&] {
    switch (map.code_width()) {
      case 1:
        gains = evaluate<std::uint8_t>(map, views, config, pick_cheaper);
        break;
      case 2:
        gains = evaluate<std::uint16_t>(map, views, config, pick_cheaper);
        break;
      default:
        gains = evaluate<std::uint32_t>(map, views, config, pick_cheaper);
        break;
    }
  });
  return gains;
}

}  // namespace

std::vector<ViewGain> fast_view_gains(const GainMap& map, std::span<const Frustum> views,
                                      const GainConfig& config) {
  return evaluate_any_width(map, views, config, /*pick_cheaper=*/false);
}

std::vector<ViewGain> cheapest_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                          const GainConfig& config) {
  config.validate();
  return evaluate_any_width(GainMap(grid, config.num_threads), views, config,
                            /*pick_cheaper=*/true);
}

std::vector<ViewGain> fast_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                      const GainConfig& config) {
  config.validate();
  return fast_view_gains(GainMap(grid, config.num_threads), views, config);
}

}  // namespace vantage
