#pragma once
/// @file
/// The pinhole image of rays a metric casts from one view (models/metric_rays.hpp): its rays'
/// directions, the pitch they keep at the farthest cell in view, and what a coarser image's cells
/// stand for.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "vantage/gain/snapshot.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// The mean area a cell shows a ray, the cube's mean projection (a quarter of its surface,
/// Cauchy) [cells^2]: a lattice of parallel rays `a` cells apart crosses about min(1, kCellShadow
/// / a^2) of the cells it passes.
inline constexpr double kCellShadow = 1.5;

/// A view's pinhole image of rays: neighbouring rays `spacing` cells apart at the farthest corner
/// of the grid, every subsample-th along each axis cast.
struct RayImage {
  Eigen::Vector3d origin;
  Eigen::Matrix3d R;
  double tan_h, tan_v, su, sv;
  int rows, cols, first, step;
  double max_range, min_r2;
  bool all_in_range;  ///< every cell's centre lies at least the min range from the origin
  /// With coarser rays (coarseness k > 1): RayCell::weight at squared distance r2 from the origin
  /// [m^2] is clamp(weight_scale * r2, 1, k^2), k^2 times the squared spacing of the metric's own
  /// rays there [cells^2] over kCellShadow; 0 with the metric's own rays.
  double weight_scale = 0.0, most_weight = 1.0;

  RayImage(const GridSpec& spec, double spacing, int subsample, int coarseness,
           const Frustum& view) {
    const SensorFov& fov = view.fov();
    origin = view.origin();
    R = view.T_world_sensor().linear();
    double depth = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1) ? spec.max_corner().x() : spec.origin.x(),
                              (corner & 2) ? spec.max_corner().y() : spec.origin.y(),
                              (corner & 4) ? spec.max_corner().z() : spec.origin.z());
      depth = std::max(depth, (p - origin).norm());
    }
    depth = std::clamp(depth, spec.resolution, fov.max_range);
    const double du = spacing * spec.resolution / depth;
    tan_h = std::tan(fov.h_fov / 2.0);
    tan_v = std::tan(fov.v_fov / 2.0);
    cols = std::max(1, static_cast<int>(std::ceil(2.0 * tan_h / du)));
    rows = std::max(1, static_cast<int>(std::ceil(2.0 * tan_v / du)));
    su = 2.0 * tan_h / cols;
    sv = 2.0 * tan_v / rows;
    step = subsample * coarseness;
    first = step / 2;
    if (coarseness > 1) {
      const double k2 = static_cast<double>(coarseness) * coarseness;
      // NOTE: the metric's own rays lie subsample * su apart in the image, about as many
      // cells apart at distance r as that times r / resolution.
      const double own = subsample * std::max(su, sv) / spec.resolution;
      weight_scale = k2 * own * own / kCellShadow;
      most_weight = k2;
    }
    max_range = fov.max_range;
    min_r2 = fov.min_range * fov.min_range;
    // NOTE: cell centres lie in the grid's box, so none is nearer than the box itself.
    const Eigen::Vector3d gap =
        (spec.origin - origin).cwiseMax(origin - spec.max_corner()).cwiseMax(0.0);
    all_in_range = gap.squaredNorm() >= min_r2;
  }
  /// The rays cast (every one, whether it meets the grid or not).
  double count() const {
    const auto along = [&](int n) { return n > first ? (n - first + step - 1) / step : 0; };
    return static_cast<double>(along(rows)) * static_cast<double>(along(cols));
  }
  /// Narrows [row_lo, row_hi) x [col_lo, col_hi), rays of the image, to those whose image
  /// coordinates fall in the bounding rectangle of the grid box's projection, with a ray to spare
  /// on each side; every other ray misses the grid. Unchanged when the box reaches behind the
  /// sensor's image plane.
  void rays_on_grid(const GridSpec& spec, int& row_lo, int& row_hi, int& col_lo,
                    int& col_hi) const {
    row_lo = col_lo = first;
    row_hi = rows;
    col_hi = cols;
    double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo, v_lo = u_lo, v_hi = -u_lo;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1) ? spec.max_corner().x() : spec.origin.x(),
                              (corner & 2) ? spec.max_corner().y() : spec.origin.y(),
                              (corner & 4) ? spec.max_corner().z() : spec.origin.z());
      const Eigen::Vector3d q = R.transpose() * (p - origin);
      if (!(q.x() > 0.0)) return;
      u_lo = std::min(u_lo, q.y() / q.x());
      u_hi = std::max(u_hi, q.y() / q.x());
      v_lo = std::min(v_lo, q.z() / q.x());
      v_hi = std::max(v_hi, q.z() / q.x());
    }
    // Ray k of an axis lies at -tan + (k + 0.5) pitch; the first ray of the lattice first + j step
    // at or below k.
    const auto index = [&](double at, double tan, double pitch) {
      return static_cast<int>(std::floor((at + tan) / pitch - 0.5));
    };
    const auto lattice_up = [&](int k) {
      return k <= first ? first : first + (k - first + step - 1) / step * step;
    };
    row_lo = lattice_up(std::max(0, index(v_lo, tan_v, sv) - 1));
    row_hi = std::min(rows, index(v_hi, tan_v, sv) + 2);
    col_lo = lattice_up(std::max(0, index(u_lo, tan_h, su) - 1));
    col_hi = std::min(cols, index(u_hi, tan_h, su) + 2);
  }
  /// The rows [row_lo, row_hi] and columns [col_lo, col_hi] of the lattice (first + j step) whose
  /// rays may pass through the box centred at `centre_world` [m] with half edges `half_edges`
  /// along the world's axes [m], widened by `spare` of a ray on each side for rounding; false when
  /// none may. Every ray of the lattice when the box reaches behind the image plane.
  bool rays_through_box(const Eigen::Vector3d& centre_world, const Eigen::Vector3d& half_edges,
                        double spare, int& row_lo, int& row_hi, int& col_lo, int& col_hi) const {
    const Eigen::Vector3d centre = R.transpose() * (centre_world - origin);
    const Eigen::Matrix3d half = R.transpose() * half_edges.asDiagonal();
    double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo, v_lo = u_lo, v_hi = -u_lo;
    bool behind = false;
    for (int corner = 0; corner < 8; ++corner) {
      Eigen::Vector3d q = centre;
      for (int a = 0; a < 3; ++a) q += ((corner >> a) & 1 ? 1.0 : -1.0) * half.col(a);
      if (!(q.x() > 0.0)) {
        behind = true;
        break;
      }
      const double inverse = 1.0 / q.x();
      u_lo = std::min(u_lo, q.y() * inverse);
      u_hi = std::max(u_hi, q.y() * inverse);
      v_lo = std::min(v_lo, q.z() * inverse);
      v_hi = std::max(v_hi, q.z() * inverse);
    }
    // Ray k of an axis lies at -tan + (k + 0.5) pitch: those from the first at or above `lo` to
    // the last at or below `hi`, widened by `spare` of a pitch, on the lattice.
    const auto range = [&](double lo, double hi, double tan, double pitch, int n, int& k_lo,
                           int& k_hi) {
      int a = first, b = n - 1;
      if (!behind) {
        // NOTE: clamped before the cast, which a box near the image plane would overflow.
        const double most = 1e8;
        a = std::max(a, static_cast<int>(
                            std::clamp(std::ceil((lo + tan) / pitch - 0.5 - spare), -most, most)));
        b = std::min(b, static_cast<int>(
                            std::clamp(std::floor((hi + tan) / pitch - 0.5 + spare), -most, most)));
      }
      k_lo = first + (a - first + step - 1) / step * step;
      k_hi = b;
      return k_lo <= k_hi;
    };
    return range(u_lo, u_hi, tan_h, su, cols, col_lo, col_hi) &&
           range(v_lo, v_hi, tan_v, sv, rows, row_lo, row_hi);
  }
  Eigen::Vector3d direction(int row, int col) const {
    return (R * Eigen::Vector3d(1.0, -tan_h + (col + 0.5) * su, -tan_v + (row + 0.5) * sv))
        .normalized();
  }
};

}  // namespace vantage::detail
