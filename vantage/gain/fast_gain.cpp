#include "vantage/gain/fast_gain.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
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
    codes_.assign((n * static_cast<std::size_t>(code_width_) + 3) / 4, 0u);
    switch (code_width_) {
      case 1:
        write_codes(log_odds, keys, reinterpret_cast<std::uint8_t*>(codes_.data()));
        break;
      case 2:
        write_codes(log_odds, keys, reinterpret_cast<std::uint16_t*>(codes_.data()));
        break;
      default:
        write_codes(log_odds, keys, codes_.data());
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
// Rays

/// How one view's rays are laid out: a pinhole image whose pixel (col, row) has its ray through
/// u = u0 + (col + 0.5) du, v = v0 + (row + 0.5) du on the plane x = 1 of the sensor frame. The
/// window is the field of view cut to the grid's image.
struct ViewRays {
  const Frustum* view = nullptr;
  Eigen::Matrix3d R;  // world <- sensor rotation
  Eigen::Vector3d origin;
  double u0 = 0, v0 = 0, du = 1;
  int cols = 0, rows = 0;
  double reach = 0;  // farthest distance a credited cell's point can lie from the origin [m]
  Index3 origin_cell;
  bool origin_inside = false;
};

ViewRays lay_out_rays(const GridSpec& spec, const Frustum& view, double ray_spacing) {
  ViewRays rays;
  rays.view = &view;
  rays.R = view.T_world_sensor().linear();
  rays.origin = view.origin();
  rays.origin_cell = spec.lattice_index(rays.origin);
  rays.origin_inside = spec.contains(rays.origin_cell);
  const SensorFov& fov = view.fov();
  const double tan_h = std::tan(fov.h_fov / 2.0);
  const double tan_v = std::tan(fov.v_fov / 2.0);

  // The grid's corners in the sensor frame: the deepest one sets the ray pitch, and when all lie
  // in front of the sensor their image bounds the window.
  double u_lo = -tan_h, u_hi = tan_h, v_lo = -tan_v, v_hi = tan_v;
  double depth = 0.0;
  bool all_in_front = true;
  double cu_lo = 1e300, cu_hi = -1e300, cv_lo = 1e300, cv_hi = -1e300;
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                                 (k & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d p = rays.R.transpose() * (corner - rays.origin);
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
  depth = std::min(depth, fov.max_range);
  if (depth <= 0.0 || u_hi <= u_lo || v_hi <= v_lo) return rays;  // no rays

  // NOTE: at depth x neighbouring rays lie x * du apart; a cell's inscribed ball has radius
  // res / 2, and the ray nearest a cell's centre passes within x * du / sqrt(2) of it. So
  // du = spacing * res / depth with spacing <= 1/sqrt(2) makes the owning ray cross its cell.
  rays.du = ray_spacing * spec.resolution / depth;
  rays.u0 = u_lo;
  rays.v0 = v_lo;
  rays.cols = static_cast<int>(std::ceil((u_hi - u_lo) / rays.du));
  rays.rows = static_cast<int>(std::ceil((v_hi - v_lo) / rays.du));
  rays.reach = fov.max_range + spec.resolution * 0.8660254037844386;
  return rays;
}

/// The pixel that owns a point: the one whose footprint holds the point's image.
struct Pixel {
  int col, row;
};
inline Pixel owner(const ViewRays& rays, const Eigen::Vector3d& p_world) {
  const Eigen::Vector3d p = rays.R.transpose() * (p_world - rays.origin);
  const double u = (p.y() / p.x() - rays.u0) / rays.du;
  const double v = (p.z() / p.x() - rays.v0) / rays.du;
  return {std::clamp(static_cast<int>(std::floor(u)), 0, rays.cols - 1),
          std::clamp(static_cast<int>(std::floor(v)), 0, rays.rows - 1)};
}

/// The model's state where a ray enters the grid, as a table: the free cells before the entry
/// all have occupancy p_min (MODEL.md), so the state depends only on how many there were.
struct EntryTable {
  EntryTable(const RayModel& model, double p_min, int max_cells)
      : prefix(model, p_min, std::max(max_cells, 1)) {}
  UniformPrefix prefix;
};

constexpr int kHistory = 64;  // states kept along a ray, a power of two
/// Cells of the exact ray replayed before a credited cell (docs/fast-gain.md).
constexpr int kReplayCells = 8;

/// One ray's contribution.
struct RaySum {
  double gain = 0.0;
  std::size_t targets = 0;
};

template <typename Code, bool kGreedy>
RaySum cast_ray(const GainMap& map, const Code* codes, const ViewRays& rays,
                const UniformPrefix& entry, const GainConfig& config, int col, int row) {
  RaySum sum;
  const GridSpec& spec = map.spec();
  const GainMap::Value* values = map.values().data();
  const Eigen::Vector3d dir = rays.R * Eigen::Vector3d(1.0, rays.u0 + (col + 0.5) * rays.du,
                                                       rays.v0 + (row + 0.5) * rays.du);
  const Eigen::Vector3d& o = rays.origin;

  // Clip the ray to the grid's box and to the range a credited cell can reach.
  double s_in = 0.0;
  double s_out = rays.reach / dir.norm();
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (o[a] < lo[a] || o[a] >= hi[a]) return sum;
      continue;
    }
    double t0 = (lo[a] - o[a]) / dir[a];
    double t1 = (hi[a] - o[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    s_in = std::max(s_in, t0);
    s_out = std::min(s_out, t1);
  }
  if (s_in >= s_out) return sum;

  const Index3 clamp_hi = spec.dims - Index3::Ones();
  Index3 cell =
      rays.origin_inside
          ? rays.origin_cell
          : spec.lattice_index(o + s_in * dir).cwiseMax(Index3::Zero()).cwiseMin(clamp_hi);
  const Index3 last =
      spec.lattice_index(o + s_out * dir).cwiseMax(Index3::Zero()).cwiseMin(clamp_hi);
  Index3 step, remaining;
  Eigen::Vector3d t_max, t_delta;
  for (int a = 0; a < 3; ++a) {
    step[a] = dir[a] > 0.0 ? 1 : -1;
    remaining[a] = std::max(0, (last[a] - cell[a]) * step[a]);
    if (dir[a] == 0.0 || remaining[a] == 0) {
      t_max[a] = std::numeric_limits<double>::infinity();
      t_delta[a] = 0.0;
      remaining[a] = 0;
      continue;
    }
    t_delta[a] = spec.resolution / std::abs(dir[a]);
    const double boundary = spec.origin[a] + (cell[a] + (step[a] > 0 ? 1 : 0)) * spec.resolution;
    t_max[a] = (boundary - o[a]) / dir[a];
  }
  const int m0 = (cell - rays.origin_cell).cwiseAbs().sum();
  const std::ptrdiff_t stride[3] = {1, spec.dims.x(),
                                    static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y()};
  auto linear = static_cast<std::ptrdiff_t>(spec.linear(cell));

  const double eps = config.epsilon;
  const detail::ModelStep model(config.alpha);
  detail::Filter state;
  detail::Filter history[kHistory];
  constexpr int K = kReplayCells;
  bool first = true;

  // The gain of a credited cell: its last cells replayed along the exact ray to its centre, from
  // the state this ray carried there (docs/fast-gain.md).
  auto replay = [&](const Index3& target, int m_target) {
    const Eigen::Vector3d c = spec.center(target);
    const Eigen::Vector3d delta = c - o;
    const double cells = delta.cwiseAbs().sum() / spec.resolution;
    const double s = K >= m_target ? 0.0 : std::max(0.0, 1.0 - K / cells);
    const Eigen::Vector3d from = o + s * delta;
    const int m_from = (spec.lattice_index(from) - rays.origin_cell).cwiseAbs().sum();
    const std::size_t target_linear = spec.linear(target);
    detail::Filter st;
    double g = 0.0;
    bool start = true;
    traverse(spec, from, c, [&](const Index3&, std::size_t lin, int m_rel) {
      const GainMap::Value& val = values[codes[lin]];
      const int m = m_from + m_rel;
      if (start) {
        start = false;
        if (m == 0) {
          st = detail::Filter::start(val.p);
        } else {
          const int prev = m - 1;
          const bool outside = m_rel > 0 || !spec.contains(spec.lattice_index(from));
          const detail::Filter before = (outside || prev < m0 || m_target - prev >= kHistory)
                                            ? detail::Filter(entry.at(m))
                                            : history[prev & (kHistory - 1)];
          st = model.step(before, val.p);
        }
      } else {
        st = model.step(st, val.p);
      }
      if (lin == target_linear) {
        g = val.entropy - entropy_bits(st.q);
        return false;
      }
      return true;
    });
    return g;
  };

  for (int m = m0;; ++m) {
    const GainMap::Value& value = values[codes[linear]];
    if constexpr (kGreedy) {
      if (value.state == CellState::kUnobserved) {
        const Eigen::Vector3d c = spec.center(cell);
        const Pixel px = owner(rays, c);
        if (px.col == col && px.row == row && rays.view->contains(c)) {
          sum.gain += 1.0;
          ++sum.targets;
        }
      } else if (value.state == CellState::kOccupied) {
        break;  // every cell behind is hidden
      }
    } else {
      if (first) {
        state = m == 0 ? detail::Filter::start(value.p)
                       : model.step(detail::Filter(entry.at(m)), value.p);
        first = false;
      } else {
        state = model.step(state, value.p);
      }
      history[m & (kHistory - 1)] = state;
      if (value.state == CellState::kUnobserved) {
        const Eigen::Vector3d c = spec.center(cell);
        const Pixel px = owner(rays, c);
        if (std::abs(state.q - 0.5) >= eps && px.col == col && px.row == row &&
            rays.view->contains(c)) {
          sum.gain += K > 0 ? replay(cell, m) : value.entropy - entropy_bits(state.q);  // eq. (4)
          ++sum.targets;
        }
      }
      if (state.v < eps) break;  // hidden
    }
    int axis = t_max[0] < t_max[1] ? 0 : 1;
    if (t_max[2] < t_max[axis]) axis = 2;
    if (remaining[axis] == 0) break;  // all axes exhausted: t_max is infinite everywhere
    cell[axis] += step[axis];
    linear += step[axis] * stride[axis];
    if (--remaining[axis] == 0) {
      t_max[axis] = std::numeric_limits<double>::infinity();
    } else {
      t_max[axis] += t_delta[axis];
    }
  }
  return sum;
}

template <typename Code>
std::vector<ViewGain> evaluate(const GainMap& map, std::span<const Frustum> views,
                               const GainConfig& config) {
  const GridSpec& spec = map.spec();
  const RayModel model(config.alpha);
  std::vector<ViewRays> layouts;
  layouts.reserve(views.size());
  int max_cells = 1;
  for (const Frustum& view : views) {
    layouts.push_back(lay_out_rays(spec, view, config.ray_spacing));
    max_cells = std::max(max_cells, max_ray_cells(spec, view.origin()));
  }
  const UniformPrefix entry(model, map.params().p_min, max_cells);

  // One task per image row of every view; row sums are added per view in row order.
  std::vector<std::size_t> first_row(views.size() + 1, 0);
  for (std::size_t i = 0; i < views.size(); ++i) {
    first_row[i + 1] = first_row[i] + static_cast<std::size_t>(layouts[i].rows);
  }
  std::vector<RaySum> row_sums(first_row.back());
  const Code* codes = map.codes<Code>();
  const bool greedy = config.method == GainMethod::kGreedy;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, row_sums.size()), [&](const auto& range) {
    std::size_t view = static_cast<std::size_t>(
        std::upper_bound(first_row.begin(), first_row.end(), range.begin()) - first_row.begin() -
        1);
    for (std::size_t r = range.begin(); r != range.end(); ++r) {
      while (r >= first_row[view + 1]) ++view;
      const ViewRays& rays = layouts[view];
      const int row = static_cast<int>(r - first_row[view]);
      RaySum sum;
      for (int col = 0; col < rays.cols; ++col) {
        const RaySum ray = greedy
                               ? cast_ray<Code, true>(map, codes, rays, entry, config, col, row)
                               : cast_ray<Code, false>(map, codes, rays, entry, config, col, row);
        sum.gain += ray.gain;
        sum.targets += ray.targets;
      }
      row_sums[r] = sum;
    }
  });

  std::vector<ViewGain> gains(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    for (std::size_t r = first_row[i]; r < first_row[i + 1]; ++r) {
      gains[i].gain += row_sums[r].gain;
      gains[i].targets += row_sums[r].targets;
    }
  }
  return gains;
}

}  // namespace

std::vector<ViewGain> fast_view_gains(const GainMap& map, std::span<const Frustum> views,
                                      const GainConfig& config) {
  config.validate();
  std::vector<ViewGain> gains;
  run_with_threads(config.num_threads, [&] {
    switch (map.code_width()) {
      case 1:
        gains = evaluate<std::uint8_t>(map, views, config);
        break;
      case 2:
        gains = evaluate<std::uint16_t>(map, views, config);
        break;
      default:
        gains = evaluate<std::uint32_t>(map, views, config);
        break;
    }
  });
  return gains;
}

std::vector<ViewGain> fast_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                      const GainConfig& config) {
  config.validate();
  return fast_view_gains(GainMap(grid, config.num_threads), views, config);
}

}  // namespace vantage
