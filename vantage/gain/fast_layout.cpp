#include "vantage/gain/fast_layout.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "vantage/map/traversal.hpp"

namespace vantage::detail {
namespace {

/// A group's pinhole image reaches at most this far off its axis (tan 70 deg).
constexpr double kMaxImageTan = 2.7474774194546216;

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

}  // namespace

double cut_to_grid(const GridSpec& spec, const Eigen::Matrix3d& Rt, const Eigen::Vector3d& origin,
                   double max_range, double& u_lo, double& u_hi, double& v_lo, double& v_hi) {
  // The grid's corners in the frame: the deepest one sets the ray pitch, and when all lie in
  // front of the sensor their image bounds the window.
  double depth = 0.0;
  bool all_in_front = true;
  double cu_lo = 1e300, cu_hi = -1e300, cv_lo = 1e300, cv_hi = -1e300;
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                                 (k & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d p = Rt * (corner - origin);
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
  return std::min(depth, max_range);
}

namespace {

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

  const double depth = cut_to_grid(spec, rays.Rt, rays.origin, max_range, u_lo, u_hi, v_lo, v_hi);
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

/// Marks the tiles of a group's image that the image of some block holding an unobserved cell
/// touches: a credited cell lies in its owner's pixel, so rays elsewhere cannot credit anything.
std::vector<std::uint8_t> live_tiles(const GridSpec& spec, const BlockSummary& blocks,
                                     const RayGroup& rays) {
  const int tiles_x = (rays.cols + kTile - 1) / kTile, tiles_y = (rays.rows + kTile - 1) / kTile;
  std::vector<std::uint8_t> live(static_cast<std::size_t>(tiles_x) * tiles_y, 0);
  if (live.empty()) return live;
  // Boxes of kBox^3 blocks (4^3 cells): fewer projections, still a tight mask.
  constexpr int kBox = 4 / BlockSummary::kBlock;
  const Index3 bd = blocks.dims;
  const double edge = BlockSummary::kBlock * spec.resolution;
  for (int z = 0; z < bd.z(); z += kBox) {
    for (int y = 0; y < bd.y(); y += kBox) {
      for (int x = 0; x < bd.x(); x += kBox) {
        bool any = false;
        for (int bz = z; bz < std::min(z + kBox, bd.z()) && !any; ++bz) {
          for (int by = y; by < std::min(y + kBox, bd.y()) && !any; ++by) {
            for (int bx = x; bx < std::min(x + kBox, bd.x()) && !any; ++bx) {
              any = blocks.unobserved[blocks.at(bx, by, bz)] != 0;
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

}  // namespace

double FastPlan::live_rays() const {
  double rays = 0.0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const int tiles_x = (groups[g].cols + kTile - 1) / kTile;
    for (std::size_t i = 0; i < live[g].size(); ++i) {
      if (live[g][i] == 0) continue;
      const int tx = static_cast<int>(i % static_cast<std::size_t>(tiles_x));
      const int ty = static_cast<int>(i / static_cast<std::size_t>(tiles_x));
      rays += static_cast<double>(std::min(kTile, groups[g].cols - tx * kTile)) *
              std::min(kTile, groups[g].rows - ty * kTile);
    }
  }
  return rays;
}

FastPlan plan_rays(const GainMap& map, std::span<const Frustum> views, const GainConfig& config) {
  const GridSpec& spec = map.spec();
  FastPlan plan;
  plan.groups = group_views(views);
  for (RayGroup& g : plan.groups) {
    lay_out_rays(spec, config.ray_spacing, g);
    plan.max_cells = std::max(plan.max_cells, max_ray_cells(spec, g.origin));
  }
  plan.blocks = summarize_blocks(map);
  plan.live.resize(plan.groups.size());
  tbb::parallel_for(std::size_t{0}, plan.groups.size(), [&](std::size_t g) {
    plan.live[g] = live_tiles(spec, plan.blocks, plan.groups[g]);
  });
  return plan;
}

}  // namespace vantage::detail
