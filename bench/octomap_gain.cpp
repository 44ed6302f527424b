#include "bench/octomap_gain.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "vantage/gain/model.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage::bench {
namespace {

octomap::point3d to_point(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

/// Cuts the image window [u_lo, u_hi] x [v_lo, v_hi] (on the plane x = 1 of the frame `Rt` at
/// `origin`) to the image of the grid's box when the whole box lies in front, and returns the
/// depth of the box's farthest corner, capped at `max_range` [m]: the depth that sets the ray
/// pitch. The workload of the removed fast evaluation, kept so that the yardstick stays the same.
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

}  // namespace

std::unique_ptr<octomap::OcTree> to_octree(const OccupancyGrid& grid) {
  const GridSpec& spec = grid.spec();
  const Eigen::Vector3d lattice = spec.origin / spec.resolution;
  if ((lattice - lattice.array().round().matrix()).cwiseAbs().maxCoeff() > 1e-9) {
    throw std::invalid_argument("to_octree: the grid's cells do not lie on OctoMap's keys");
  }
  auto tree = std::make_unique<octomap::OcTree>(spec.resolution);
  const OccupancyParams& p = grid.params();
  tree->setProbHit(p.p_hit);
  tree->setProbMiss(p.p_miss);
  tree->setClampingThresMin(p.p_min);
  tree->setClampingThresMax(p.p_max);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const float l = grid.log_odds(i);
    if (l == 0.0f) continue;  // unknown: no node, as in OctoMap
    tree->setNodeValue(to_point(spec.center(spec.unravel(i))), l, /*lazy_eval=*/true);
  }
  tree->updateInnerOccupancy();
  return tree;
}

OctoMapGains octomap_view_gains(const octomap::OcTree& tree, const GridSpec& spec,
                                const OccupancyParams& params, std::span<const Frustum> views,
                                const GainConfig& config) {
  config.validate();
  OctoMapGains out;
  out.gains.resize(views.size());
  std::atomic<std::size_t> rays{0}, keys{0};
  const float free_max = static_cast<float>(logit(0.4));
  const float occupied_min = static_cast<float>(logit(0.6));
  const double eps = config.epsilon;

  run_with_threads(config.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t vi) {
      const Frustum& view = views[vi];
      const Eigen::Matrix3d R = view.T_world_sensor().linear();
      const Eigen::Vector3d o = view.origin();
      const RayTables<PaperModel> tables(config.alpha, params.p_min, max_ray_cells(spec, o) + 1);

      // The pixel grid: the field of view cut to the grid's image, the fast mode's pitch.
      const double th = std::tan(view.fov().h_fov / 2), tv = std::tan(view.fov().v_fov / 2);
      double u_lo = -th, u_hi = th, v_lo = -tv, v_hi = tv;
      const double depth =
          cut_to_grid(spec, R.transpose(), o, view.fov().max_range, u_lo, u_hi, v_lo, v_hi);
      if (depth <= 0.0 || u_hi <= u_lo || v_hi <= v_lo) return;
      const double du = config.ray_spacing * spec.resolution / depth;
      const int cols = static_cast<int>(std::ceil((u_hi - u_lo) / du));
      const int rows = static_cast<int>(std::ceil((v_hi - v_lo) / du));
      const double reach = view.fov().max_range + spec.resolution * 0.8660254037844386;

      octomap::KeySet credited;  // count each cell once per view
      octomap::KeyRay ray;
      const octomap::OcTreeKey k_origin = tree.coordToKey(to_point(o));
      // The grid's cells as keys: beyond them is the free space of docs/model.md, not OctoMap's
      // unknown.
      const octomap::OcTreeKey k_lo = tree.coordToKey(to_point(spec.center(Index3::Zero())));
      const octomap::OcTreeKey k_hi =
          tree.coordToKey(to_point(spec.center(spec.dims - Index3::Ones())));
      auto in_grid = [&](const octomap::OcTreeKey& k) {
        for (int a = 0; a < 3; ++a) {
          if (k[a] < k_lo[a] || k[a] > k_hi[a]) return false;
        }
        return true;
      };
      ViewGain gain;
      std::size_t view_keys = 0;
      for (int row = 0; row < rows; ++row) {
        for (int col = 0; col < cols; ++col) {
          const Eigen::Vector3d dir =
              R * Eigen::Vector3d(1.0, u_lo + (col + 0.5) * du, v_lo + (row + 0.5) * du);
          // Clip to the grid: the cells before it are free (docs/model.md), a table lookup.
          double s_in = 0.0, s_out = reach / dir.norm();
          if (!clip_to_grid(spec, o, dir, s_in, s_out) || s_in >= s_out) continue;
          const double nudge = 1e-6 * spec.resolution / dir.norm();
          const octomap::point3d from = to_point(o + (s_in + nudge) * dir);
          const octomap::point3d to = to_point(o + (s_out - nudge) * dir);
          if (!tree.computeRayKeys(from, to, ray)) continue;
          ray.addKey(tree.coordToKey(to));  // computeRayKeys leaves out the end's cell
          const octomap::OcTreeKey& first = *ray.begin();
          int m = std::abs(int(first[0]) - int(k_origin[0])) +
                  std::abs(int(first[1]) - int(k_origin[1])) +
                  std::abs(int(first[2]) - int(k_origin[2]));
          RayOdds odds;
          double p_prev = params.p_min;
          bool start = true;
          for (const octomap::OcTreeKey& key : ray) {
            ++view_keys;
            const bool inside = in_grid(key);
            const octomap::OcTreeNode* node = inside ? tree.search(key) : nullptr;
            const float l = node ? node->getLogOdds() : (inside ? 0.0f : free_max - 1.0f);
            const double p = node ? node->getOccupancy() : (inside ? 0.5 : params.p_min);
            if (start) {
              odds = tables.enter(m, p);
              start = false;
            } else {
              tables.step(odds, m, p_prev, p);
            }
            p_prev = p;
            const bool unobserved = l > free_max && l < occupied_min;
            if (unobserved && !odds.pinned(eps)) {
              const octomap::point3d c = tree.keyToCoord(key);
              if (view.contains(Eigen::Vector3d(c.x(), c.y(), c.z())) &&
                  credited.insert(key).second) {
                gain.gain += entropy_bits(p) - entropy_bits(odds.posterior());
                ++gain.targets;
              }
            }
            if (odds.hidden(eps)) break;
            ++m;
          }
        }
      }
      out.gains[vi] = gain;
      rays += static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
      keys += view_keys;
    });
  });
  out.rays = rays;
  out.keys = keys;
  return out;
}

}  // namespace vantage::bench
