// An exploration's settings, checked, and what a scene implies for them (exploration.hpp): the
// candidate set, the arm's hemisphere, the odometry prior, the mapper's defaults, an office
// stop's sweep.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/experiment/detail/explorer.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_sets.hpp"

namespace vantage {

void OfficeConfig::validate() const {
  if (!(frontier_band >= 0.0 && std::isfinite(frontier_band))) {
    throw std::invalid_argument(cat("office.frontier_band must be >= 0 m, got ", frontier_band));
  }
  if (min_frontier_cells < 1) {
    throw std::invalid_argument(
        cat("office.min_frontier_cells must be >= 1, got ", min_frontier_cells));
  }
  if (!(max_frontier_radius >= 0.0 && std::isfinite(max_frontier_radius))) {
    throw std::invalid_argument(
        cat("office.max_frontier_radius must be >= 0 m, got ", max_frontier_radius));
  }
  if (!std::isfinite(min_obstacle_height)) {
    throw std::invalid_argument(
        cat("office.min_obstacle_height must be finite, got ", min_obstacle_height));
  }
  if (!(min_move >= 0.0 && std::isfinite(min_move))) {
    throw std::invalid_argument(cat("office.min_move must be >= 0 m, got ", min_move));
  }
}

void ExplorationConfig::validate() const {
  planner.validate();
  mapper.validate();
  if (scans < 1) throw std::invalid_argument(cat("explore.scans must be >= 1, got ", scans));
  if (!(min_gain >= 0.0)) {
    throw std::invalid_argument(cat("explore.min_gain must be >= 0, got ", min_gain));
  }
  if (start < 0) throw std::invalid_argument(cat("explore.start must be >= 0, got ", start));
  if (pose_noise) pose_noise->validate();
  office.validate();
  hemisphere.validate();
  if (arm && !(arm->reach > 0.0)) {
    throw std::invalid_argument(cat("explore.arm.reach must be > 0 m, got ", arm->reach));
  }
  if (!candidates.empty()) {
    const CandidateSetRow& row = find_candidate_set(candidates);  // throws naming the sets
    if (row.needs_map || row.needs_list) {
      throw std::invalid_argument(cat("explore.candidates: '", candidates,
                                      "' is not placed around a scene (use ring, hemisphere, "
                                      "sphere or view-sphere)"));
    }
  }
  try {
    coverage_tolerance.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(cat("explore.coverage_tolerance: ", e.what()));
  }
}

HemisphereConfig run_hemisphere(const sim::Scene& scene, const ExplorationConfig& config) {
  HemisphereConfig h = config.hemisphere;
  h.center = scene.mount.target;
  const std::optional<ArmReach>& arm = config.arm ? config.arm : scene.arm;
  if (arm) {
    h.base = arm->base;
    h.reach = arm->reach;
  }
  return h;
}

perception::PoseSigma odometry_prior(const sim::PoseNoise& noise) {
  // NOTE: the simulated error has no height, roll or pitch; the prior keeps a little slack there
  // (PoseSigma's defaults), and a floor where a sigma is 0, which the prior cannot weigh.
  constexpr double kFloor = 1e-4;
  perception::PoseSigma prior;
  prior.x = std::max(noise.x, kFloor);
  prior.y = std::max(noise.y, kFloor);
  prior.yaw = std::max(noise.yaw, kFloor);
  return prior;
}

AlphaSetting default_alpha_setting(PlannerMethod method, double paper) {
  return uses_survival_reading(method) ? AlphaSetting{true, kSurvivalAlpha}
                                       : AlphaSetting{false, default_alpha(method, paper)};
}

MapperConfig default_mapper_config(const sim::Scene& scene) {
  MapperConfig config;
  config.segment_table = scene.kind == sim::SceneKind::kTableTop;  // objects float: no table
  for (const sim::Shape& shape : scene.shapes) {
    if (shape.kind != "table") continue;
    // NOTE: seen from above (an arm's views), the floor around the table is the largest
    // horizontal plane; the table is the one within 5 cm of the scene's table top.
    constexpr double kTableSlack = 0.05;  // [m]
    config.table.min_table_z = shape.bounds().max().z() - kTableSlack;
    config.table.max_table_z = shape.bounds().max().z() + kTableSlack;
  }
  config.registration.prior = odometry_prior(kDefaultPoseNoise);
  if (scene.kind == sim::SceneKind::kOffice) {
    // A sweep is registered as a whole, thinned to one point per map cell, against the sweeps so
    // far at the same resolution; Kinect noise of up to 2 cm at 3.5 m.
    config.thin_to_cells = true;
    config.register_overlap_only = true;
    config.map.voxel_size = scene.grid.resolution;
    config.registration.voxel_size = scene.grid.resolution;
    // NOTE: a point thinned to its cell's centroid is off its surface by up to half a cell: the
    // quantisation's sigma (resolution / sqrt(12)) adds to the Kinect's 1 cm.
    config.registration.sensor_sigma = std::hypot(0.01, scene.grid.resolution / std::sqrt(12.0));
    config.registration.min_distance = 2.0 * scene.grid.resolution;
    // NOTE: a sweep's posterior rarely knows the position better than the prior along one
    // direction (the floor outweighs the walls); 1 cm keeps the sweeps that pin it.
    config.registration.max_position_sigma = 0.01;
    // NOTE: a retry that passes integrates every sweep since the fallback again (~1 s each).
    config.reregister_window = 3;
  }
  return config;
}

std::vector<Frustum> sweep_frusta(const sim::Scene& scene,
                                  const Eigen::Isometry3d& T_world_sensor) {
  const int steps = scene.sensor.sweep_steps;
  SensorFov fov = scene.fov();
  fov.h_fov = std::min(fov.h_fov, 2.0 * std::numbers::pi / steps);
  std::vector<Frustum> frusta;
  for (int k = 0; k < steps; ++k) {
    Eigen::Isometry3d T = T_world_sensor;
    T.linear() = Eigen::AngleAxisd(2.0 * std::numbers::pi * k / steps, Eigen::Vector3d::UnitZ()) *
                 T_world_sensor.linear();
    frusta.emplace_back(T, fov);
  }
  return frusta;
}

std::string run_candidate_set(const sim::Scene& scene, const ExplorationConfig& config) {
  if (!config.candidates.empty()) return config.candidates;
  switch (scene.kind) {
    case sim::SceneKind::kTableTop:
      return "ring";
    case sim::SceneKind::kOffice:
      return "stops";
    case sim::SceneKind::kObject:
      return "view-sphere";
  }
  return "ring";
}

PlacedViews run_candidate_views(const sim::Scene& scene, const ExplorationConfig& config) {
  CandidateSite site;
  site.target = scene.mount.target;
  site.region = Eigen::AlignedBox3d(scene.grid.origin, scene.grid.max_corner());
  if (scene.kind == sim::SceneKind::kTableTop) site.ring = scene.ring;
  site.sphere = scene.view_sphere;
  site.arm = config.arm ? config.arm : scene.arm;
  CandidateParams params = config.views;
  params.hemisphere = config.hemisphere;
  return build_candidates(run_candidate_set(scene, config), site, params);
}

std::vector<Eigen::Isometry3d> run_candidates(const sim::Scene& scene,
                                              const ExplorationConfig& config) {
  return run_candidate_views(scene, config).poses;
}

TravelRule run_travel_rule(const sim::Scene& scene, const ExplorationConfig& config) {
  return run_candidate_views(scene, config).travel;
}

}  // namespace vantage
