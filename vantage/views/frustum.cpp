#include "vantage/views/frustum.hpp"

#include <stdexcept>

#include "vantage/map/grid_spec.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

void SensorFov::validate() const {
  if (!(h_fov > 0.0 && h_fov < std::numbers::pi)) {
    throw std::invalid_argument(
        cat("sensor.h_fov must lie in (0, 180) degrees, got ", h_fov * 180.0 / std::numbers::pi));
  }
  if (!(v_fov > 0.0 && v_fov < std::numbers::pi)) {
    throw std::invalid_argument(
        cat("sensor.v_fov must lie in (0, 180) degrees, got ", v_fov * 180.0 / std::numbers::pi));
  }
  if (!(min_range >= 0.0 && std::isfinite(min_range))) {
    throw std::invalid_argument(cat("sensor.min_range must be >= 0 m, got ", min_range));
  }
  if (!(max_range > min_range && max_range <= kMaxWorldCoordinate)) {
    throw std::invalid_argument(cat("sensor.max_range (", max_range, " m) must exceed min_range (",
                                    min_range, " m) and be at most ", kMaxWorldCoordinate, " m"));
  }
}

Frustum::Frustum(const Eigen::Isometry3d& T_world_sensor, const SensorFov& fov)
    : T_world_sensor_(T_world_sensor), fov_(fov) {
  fov_.validate();
  if (!T_world_sensor_.matrix().allFinite()) {
    throw std::invalid_argument("frustum pose must be finite");
  }
  T_sensor_world_ = T_world_sensor_.inverse();
  tan_h_ = std::tan(fov_.h_fov / 2.0);
  tan_v_ = std::tan(fov_.v_fov / 2.0);
  min_r2_ = fov_.min_range * fov_.min_range;
  max_r2_ = fov_.max_range * fov_.max_range;
}

Eigen::AlignedBox3d Frustum::bounds() const {
  // Every point of the frustum has 0 < x <= max_range and |y| <= x tan_h, |z| <= x tan_v, so the
  // pyramid cut at x = max_range holds it.
  Eigen::AlignedBox3d box(origin());
  const double x = fov_.max_range;
  for (const double sy : {-1.0, 1.0}) {
    for (const double sz : {-1.0, 1.0}) {
      box.extend(T_world_sensor_ * Eigen::Vector3d(x, sy * x * tan_h_, sz * x * tan_v_));
    }
  }
  return box;
}

}  // namespace vantage
