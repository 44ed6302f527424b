#include "vantage/views/hemisphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_set.hpp"
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
  // NOTE: the views a spacing makes are counted before one is made (issue 39: 1e-9 m was capped
  // without a word at 100 000 a ring).
  if (const double views = view_count(); views > static_cast<double>(kMaxCandidateViews)) {
    throw std::invalid_argument(cat("hemisphere.spacing (--view-spacing) ", spacing,
                                    " m makes about ", views, " views, more than the ",
                                    kMaxCandidateViews, " a decision scores: use a wider spacing"));
  }
  if (!(base.array().abs() <= kMaxWorldCoordinate).all()) {
    throw std::invalid_argument(
        cat("hemisphere.base must be finite, within ", kMaxWorldCoordinate, " m of the origin"));
  }
  if (!(reach > 0.0))
    throw std::invalid_argument(cat("hemisphere.reach must be > 0 m, got ", reach));
}

double HemisphereConfig::elevation(int k) const {
  return elevations == 1 ? 0.5 * (min_elevation + max_elevation)
                         : min_elevation + (max_elevation - min_elevation) * k / (elevations - 1);
}

double HemisphereConfig::ring_views(double radius, int k) const {
  return std::max(3.0,
                  std::ceil(2.0 * std::numbers::pi * radius * std::cos(elevation(k)) / spacing));
}

double HemisphereConfig::view_count() const {
  double views = 0.0;
  for (const double radius : radii) {
    for (int k = 0; k < elevations; ++k) views += ring_views(radius, k);
  }
  return views;
}

std::vector<Eigen::Isometry3d> hemisphere_poses(const HemisphereConfig& config) {
  config.validate();
  std::vector<Eigen::Isometry3d> poses;
  double nearest = std::numeric_limits<double>::infinity();
  for (const double radius : config.radii) {
    for (int k = 0; k < config.elevations; ++k) {
      const double elevation = config.elevation(k);
      // validate() bounded the count by kMaxCandidateViews.
      const int views = static_cast<int>(config.ring_views(radius, k));
      for (int j = 0; j < views; ++j) {
        const double azimuth = 2.0 * std::numbers::pi * j / views;
        const Eigen::Vector3d eye =
            config.center + radius * Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                                     std::cos(elevation) * std::sin(azimuth),
                                                     std::sin(elevation));
        const double distance = (eye - config.base).norm();
        nearest = std::min(nearest, distance);
        if (distance > config.reach) continue;
        poses.push_back(look_at(eye, config.center));
      }
    }
  }
  if (poses.empty()) {
    throw std::invalid_argument(
        cat("the arm reaches none of the hemisphere's ", config.view_count(), " views: its reach ",
            config.reach, " m from its base (", config.base.x(), ", ", config.base.y(), ", ",
            config.base.z(), ") falls short of the nearest, ", nearest,
            " m away (set --arm-base and --reach, or the scene's arm)"));
  }
  return poses;
}

PlacedViews hemisphere_candidates(const CandidateSite& site, const CandidateParams& params) {
  HemisphereConfig hemisphere = params.hemisphere.value_or(HemisphereConfig{});
  hemisphere.center = site.target;
  if (!params.hemisphere && (params.radius > 0.0 || !site.ring)) {
    // NOTE: an arm's views (issue 26): rings at 0.75, 1 and 1.25 times the ring's radius.
    const double r = params.radius > 0.0 ? params.radius : default_ring(site.region).radius;
    hemisphere.radii = {0.75 * r, r, 1.25 * r};
  }
  if (site.arm) {
    hemisphere.base = site.arm->base;
    hemisphere.reach = site.arm->reach;
  }
  return {.poses = hemisphere_poses(hemisphere), .travel = TravelRule{}};
}

}  // namespace vantage
