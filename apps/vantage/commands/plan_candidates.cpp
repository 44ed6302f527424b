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
#include "vantage/views/candidate_sets.hpp"

namespace vantage::cli {

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

bool names_pose_file(const PlanOptions& o) {
  return !is_candidate_set(o.candidates) || find_candidate_set(o.candidates).needs_list;
}

namespace {

/// The registry's set that --candidates names: a pose file is the `file` set.
const CandidateSetRow& candidate_row(const PlanOptions& o) {
  return find_candidate_set(names_pose_file(o) ? "file" : o.candidates);
}

PlacedViews placed_views(const PlanOptions& o, const Eigen::AlignedBox3d& roi, CloudFrame frame,
                         const OccupancyGrid* grid) {
  CandidateSite site;
  site.target = roi.center();
  site.region = roi;
  site.grid = grid;
  CandidateParams params;
  params.radius = o.radius;
  params.height = o.height;
  // NOTE: plan's --views counts a ring's positions; each has the ring's yaw offsets.
  params.views = o.candidates == "ring"
                     ? o.views * static_cast<int>(RingConfig{}.yaw_offsets.size())
                     : o.views;
  params.band = sensor_band(o);
  if (names_pose_file(o)) {
    params.listed = read_candidate_poses(o.candidates, frame);  // run() checked that it exists
  }
  return candidate_row(o).build(site, params);
}

}  // namespace

std::optional<std::vector<Eigen::Isometry3d>> planned_poses(const PlanOptions& o,
                                                            const Eigen::AlignedBox3d& roi,
                                                            CloudFrame frame) {
  if (candidate_row(o).needs_map) return std::nullopt;
  return placed_views(o, roi, frame, nullptr).poses;
}

std::vector<Eigen::Isometry3d> candidate_poses(const PlanOptions& o, const Eigen::AlignedBox3d& roi,
                                               CloudFrame frame, const OccupancyGrid& grid) {
  PlacedViews views = placed_views(o, roi, frame, &grid);
  if (!o.json_only && !views.note.empty()) fmt::print("{}\n", views.note);
  return std::move(views.poses);
}

}  // namespace vantage::cli
