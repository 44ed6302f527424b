#include "vantage/views/sphere.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include "vantage/map/grid_spec.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_set.hpp"
#include "vantage/views/detail/placement.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {

void SphereConfig::validate() const {
  detail::validate_placement("sphere", center, radius);
  if (views < 1) throw std::invalid_argument(cat("sphere.views must be >= 1, got ", views));
  if (static_cast<std::uint64_t>(views) > kMaxCandidateViews) {
    throw std::invalid_argument(cat("sphere.views (", views, ") is more than the ",
                                    kMaxCandidateViews, " views a decision scores"));
  }
  const double half_pi = std::numbers::pi / 2.0;
  if (!(min_elevation >= -half_pi && min_elevation < max_elevation && max_elevation <= half_pi)) {
    throw std::invalid_argument(cat("sphere elevations must satisfy -90 <= min (",
                                    min_elevation * 180.0 / std::numbers::pi, ") < max (",
                                    max_elevation * 180.0 / std::numbers::pi, ") <= 90 degrees"));
  }
}

std::vector<Eigen::Isometry3d> sphere_poses(const SphereConfig& config) {
  config.validate();
  // Fibonacci lattice: heights uniform in sin(elevation) (equal areas), azimuths by the golden
  // angle.
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double z_lo = std::sin(config.min_elevation);
  const double z_hi = std::sin(config.max_elevation);
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(static_cast<std::size_t>(config.views));
  for (int i = 0; i < config.views; ++i) {
    const double z = z_lo + (z_hi - z_lo) * (i + 0.5) / config.views;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double azimuth = golden_angle * i;
    const Eigen::Vector3d direction(r * std::cos(azimuth), r * std::sin(azimuth), z);
    poses.push_back(look_at(config.center + config.radius * direction, config.center));
  }
  return poses;
}

PlacedViews sphere_candidates(const CandidateSite& site, const CandidateParams& params) {
  SphereConfig sphere;
  sphere.center = site.target;
  const double half_diagonal = 0.5 * site.region.sizes().head<2>().norm();
  sphere.radius = params.radius > 0.0 ? params.radius : std::max(1.0, 2.0 * half_diagonal);
  sphere.views = params.views > 0 ? params.views : 50;
  return {.poses = sphere_poses(sphere), .travel = TravelRule{}};
}

SphereConfig object_view_sphere(const Eigen::Vector3d& center, double radius, int views) {
  SphereConfig sphere;
  sphere.center = center;
  sphere.radius = radius;
  sphere.views = views;
  sphere.min_elevation = -std::numbers::pi / 2.0;
  sphere.max_elevation = std::numbers::pi / 2.0;
  return sphere;
}

PlacedViews view_sphere_candidates(const CandidateSite& site, const CandidateParams& params) {
  // NOTE: an object scene's own sphere, else one around the region at the band's default radius.
  const double half_diagonal = 0.5 * site.region.sizes().norm();
  SphereConfig sphere = site.sphere
                            ? *site.sphere
                            : object_view_sphere(site.target, std::max(1.0, 2.0 * half_diagonal));
  if (params.radius > 0.0) sphere.radius = params.radius;
  if (params.views > 0) sphere.views = params.views;
  return {.poses = sphere_poses(sphere),
          .travel = {TravelRule::Kind::kSphereArc, sphere.center, sphere.radius}};
}

}  // namespace vantage
