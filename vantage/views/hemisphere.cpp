#include "vantage/views/hemisphere.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vantage/util/text.hpp"
#include "vantage/views/detail/placement.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {

void HemisphereConfig::validate() const {
  if (radii.empty()) throw std::invalid_argument("hemisphere.radii must hold at least one radius");
  for (const double r : radii) detail::validate_placement("hemisphere", center, r);
  const double half_pi = std::numbers::pi / 2.0;
  if (!(min_elevation >= 0.0 && min_elevation <= max_elevation && max_elevation < half_pi)) {
    throw std::invalid_argument(cat("hemisphere elevations must satisfy 0 <= min (",
                                    min_elevation * 180.0 / std::numbers::pi, ") <= max (",
                                    max_elevation * 180.0 / std::numbers::pi, ") < 90 degrees"));
  }
  if (elevations < 1 || elevations > 1000) {
    throw std::invalid_argument(
        cat("hemisphere.elevations must lie in [1, 1000], got ", elevations));
  }
  if (!(spacing > 0.0 && std::isfinite(spacing))) {
    throw std::invalid_argument(cat("hemisphere.spacing must be > 0 m, got ", spacing));
  }
  if (!(base.array().abs() <= kMaxWorldCoordinate).all()) {
    throw std::invalid_argument(
        cat("hemisphere.base must be finite, within ", kMaxWorldCoordinate, " m of the origin"));
  }
  if (!(reach > 0.0))
    throw std::invalid_argument(cat("hemisphere.reach must be > 0 m, got ", reach));
}

std::vector<Eigen::Isometry3d> hemisphere_poses(const HemisphereConfig& config) {
  config.validate();
  std::vector<Eigen::Isometry3d> poses;
  for (const double radius : config.radii) {
    for (int k = 0; k < config.elevations; ++k) {
      const double elevation =
          config.elevations == 1
              ? 0.5 * (config.min_elevation + config.max_elevation)
              : config.min_elevation +
                    (config.max_elevation - config.min_elevation) * k / (config.elevations - 1);
      const double ring = radius * std::cos(elevation);
      // NOTE: a bound on the count keeps a tiny spacing from asking for millions of views.
      const int views = static_cast<int>(
          std::clamp(std::ceil(2.0 * std::numbers::pi * ring / config.spacing), 3.0, 100000.0));
      for (int j = 0; j < views; ++j) {
        const double azimuth = 2.0 * std::numbers::pi * j / views;
        const Eigen::Vector3d eye =
            config.center + radius * Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                                     std::cos(elevation) * std::sin(azimuth),
                                                     std::sin(elevation));
        if ((eye - config.base).norm() > config.reach) continue;
        poses.push_back(look_at(eye, config.center));
      }
    }
  }
  return poses;
}

}  // namespace vantage
