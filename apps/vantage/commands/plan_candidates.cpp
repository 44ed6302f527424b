// `vantage plan`'s sensor without a manifest and its candidate views (plan.hpp).

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "commands/plan.hpp"
#include "shell.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/views/frontier.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::cli {
namespace {

/// Frontier candidates with what was left out.
struct FrontierViews {
  std::vector<Eigen::Isometry3d> poses;
  std::size_t regions = 0;
  std::size_t dropped = 0;  ///< views whose place is not known free (unknown or occupied)
};

/// Four level views (yaw 0, 90, 180, 270 degrees) at the centroid of every frontier region; with
/// a sensor band, frontier cells are taken in the band (the layers holding min..max) and each
/// view is put at a height within it. A view whose place is not a known free cell is dropped:
/// a robot cannot stand in unknown or occupied space.
FrontierViews frontier_poses(const OccupancyGrid& grid,
                             const std::optional<std::pair<double, double>>& band) {
  FrontierConfig config;
  const double half = 0.5 * grid.spec().resolution;
  if (band) {
    config.min_z = band->first - half;
    config.max_z = band->second + half;
  }
  FrontierViews views;
  const std::vector<FrontierRegion> regions = frontier_regions(grid, config);
  views.regions = regions.size();
  for (const FrontierRegion& region : regions) {
    Eigen::Vector3d place = region.centroid;
    if (band) place.z() = std::clamp(place.z(), band->first, band->second);
    const std::optional<Index3> cell = grid.spec().find(place);
    if (!cell || grid.state(grid.spec().linear(*cell)) != CellState::kFree) {
      views.dropped += 4;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::AngleAxisd(k * std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ())
                          .toRotationMatrix();
      pose.translation() = place;
      views.poses.push_back(pose);
    }
  }
  if (views.poses.empty()) {
    throw std::runtime_error(
        regions.empty()
            ? std::string(band ? "the map has no frontier regions at --sensor-height to plan from"
                               : "the map has no frontier regions to plan from")
            : fmt::format("none of the {} frontier regions' centroids lies in a known free cell "
                          "(try --sensor-height)",
                          regions.size()));
  }
  return views;
}

}  // namespace

SensorFov fov_from_options(const PlanOptions& o) {
  const auto fov = parse_numbers(o.fov_deg, "--fov-deg");
  const auto range = parse_numbers(o.range, "--range");
  if (fov.size() != 2) throw UsageError("--fov-deg takes two numbers: h,v");
  if (range.size() != 2) throw UsageError("--range takes two numbers: min,max");
  SensorFov result{deg2rad(fov[0]), deg2rad(fov[1]), range[0], range[1]};
  try {
    result.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--fov-deg/--range: {}", e.what()));
  }
  return result;
}

std::optional<std::pair<double, double>> sensor_band(const PlanOptions& o) {
  if (o.sensor_height.empty()) return std::nullopt;
  const std::vector<double> v = parse_numbers(o.sensor_height, "--sensor-height");
  if (v.size() > 2) throw UsageError("--sensor-height takes a height or a range: h, or min,max");
  for (const double h : v) {
    if (!std::isfinite(h) || std::abs(h) > kMaxWorldCoordinate) {
      throw UsageError(
          fmt::format("--sensor-height: {} m is not a height within {} m", h, kMaxWorldCoordinate));
    }
  }
  const double lo = v.front(), hi = v.back();
  if (lo > hi) throw UsageError(fmt::format("--sensor-height: min {} exceeds max {}", lo, hi));
  return std::pair{lo, hi};
}

std::optional<std::vector<Eigen::Isometry3d>> planned_poses(const PlanOptions& o,
                                                            const Eigen::AlignedBox3d& roi,
                                                            CloudFrame frame) {
  const Eigen::Vector3d center = roi.center();
  const double half_diagonal = 0.5 * roi.sizes().head<2>().norm();
  if (o.candidates == "ring") {
    RingConfig ring = default_ring(roi);  // the rule vt.ring_candidates shares
    if (o.radius > 0.0) ring.radius = o.radius;
    if (!std::isnan(o.height)) ring.height = o.height;
    if (o.views > 0) ring.positions = o.views;
    return ring_poses(ring);
  }
  if (o.candidates == "sphere") {
    SphereConfig sphere;
    sphere.center = center;
    sphere.radius = o.radius > 0.0 ? o.radius : std::max(1.0, 2.0 * half_diagonal);
    sphere.views = o.views > 0 ? o.views : 50;
    return sphere_poses(sphere);
  }
  if (o.candidates == "hemisphere") {
    // NOTE: an arm's views (issue 26): rings at 0.75, 1 and 1.25 times the ring's radius.
    HemisphereConfig hemisphere;
    hemisphere.center = center;
    const double radius = o.radius > 0.0 ? o.radius : default_ring(roi).radius;
    hemisphere.radii = {0.75 * radius, radius, 1.25 * radius};
    return hemisphere_poses(hemisphere);
  }
  if (o.candidates == "frontier") return std::nullopt;
  return read_candidate_poses(o.candidates, frame);  // run() checked that the file exists
}

std::vector<Eigen::Isometry3d> candidate_poses(const PlanOptions& o, const Eigen::AlignedBox3d& roi,
                                               CloudFrame frame, const OccupancyGrid& grid) {
  if (auto poses = planned_poses(o, roi, frame)) return std::move(*poses);
  const FrontierViews views = frontier_poses(grid, sensor_band(o));
  if (!o.json_only) {
    fmt::print("frontier: {} regions, {} views{}\n", views.regions, views.poses.size(),
               views.dropped > 0
                   ? fmt::format(" ({} dropped: their place is not known free)", views.dropped)
                   : "");
  }
  return views.poses;
}

}  // namespace vantage::cli
