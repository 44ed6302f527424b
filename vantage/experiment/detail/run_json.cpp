// run.json (detail/run_json.hpp): an exploration's document, its scene, settings, scans and
// candidates.

#include "vantage/experiment/detail/run_json.hpp"

#include <fmt/core.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>

#include "vantage/experiment/results.hpp"

namespace vantage::detail {
namespace {

using nlohmann::json;

json pose_json(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{"position", {T.translation().x(), T.translation().y(), T.translation().z()}},
          {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

/// The mapper's registration settings, as run.json records them.
json registration_json(const MapperConfig& mapper) {
  const perception::RegistrationConfig& reg = mapper.registration;
  return {{"enabled", mapper.register_scans},
          {"prior",
           {{"x", reg.prior.x},
            {"y", reg.prior.y},
            {"z", reg.prior.z},
            {"roll", reg.prior.roll},
            {"pitch", reg.prior.pitch},
            {"yaw", reg.prior.yaw}}},
          {"sensor_sigma", reg.sensor_sigma},
          {"sigmas", reg.sigmas},
          {"min_distance", reg.min_distance},
          {"voxel_size", reg.voxel_size},
          {"map_voxel_size", mapper.map.voxel_size},
          {"max_iterations", reg.max_iterations},
          {"convergence", reg.convergence},
          {"degenerate_ratio", reg.degenerate_ratio},
          {"independent_points", reg.independent_points},
          {"max_position_sigma", reg.max_position_sigma},
          {"max_mahalanobis2", reg.max_mahalanobis2},
          {"min_correspondences", reg.min_correspondences},
          {"min_overlap", reg.min_overlap},
          {"start_sigmas", reg.start_sigmas},
          {"ambiguity_cost", reg.ambiguity_cost},
          {"reregister_window", mapper.reregister_window},
          {"thin_to_cells", mapper.thin_to_cells},
          {"overlap_only", mapper.register_overlap_only}};
}

/// An office's exploration settings, as run.json records them.
json office_json(const OfficeConfig& office) {
  return {{"frontier_band", office.frontier_band},
          {"min_frontier_cells", office.min_frontier_cells},
          {"max_frontier_radius", office.max_frontier_radius},
          {"min_obstacle_height", office.min_obstacle_height},
          {"unknown_blocks", office.unknown_blocks},
          {"min_move", office.min_move},
          {"project_stops", office.project_stops}};
}

json config_json(const ExplorationConfig& config, const sim::Scene& scene) {
  const GainConfig& gain = config.planner.gain;
  const MapperConfig& mapper = config.mapper;
  // NOTE: what the decision plans: --method sequence's defaults where it was not told.
  const SequenceConfig sequence = sequence_of(config.planner);
  return {
      {"method", config.greedy_oracle ? kGreedyOracleName : to_string(config.planner.method)},
      {"alpha", config.auto_alpha ? json("auto") : json(gain.alpha)},
      {"objective", to_string(config.planner.objective)},
      {"observability",
       {{"alphas", config.observability.alphas},
        {"prior", config.observability.prior},
        {"recency", config.observability.recency}}},
      {"evaluation", to_string(gain.evaluation)},
      {"search", config.planner.search ? to_string(*config.planner.search) : "default"},
      {"sample", 1 << config.planner.sequence.sample_bits},
      {"swept_rays", config.planner.swept_rays},
      {"epsilon", gain.epsilon},
      {"lambda", config.planner.lambda},
      {"candidates", run_candidate_set(scene, config)},
      // NOTE: what "travel" measures, said where the figures are.
      {"travel_rule", scene.kind == sim::SceneKind::kOffice
                          ? "the path driven on the floor [m]"
                          : run_travel_rule(scene, config).describe()},
      {"sequence",
       {{"horizon", sequence.horizon},
        {"travel_weight_per_m", sequence.travel_weight},
        {"shortlist", sequence.shortlist},
        {"active", sequence.active()}}},
      {"scans", config.scans},
      {"min_gain", config.min_gain},
      {"revisit", config.revisit},
      {"greedy_reference", config.planner.greedy_reference},
      {"start", config.start},
      {"seed", config.seed},
      {"num_threads", gain.num_threads},
      {"integration", to_string(mapper.integration.mode)},
      {"hole_filling",
       {{"enabled", mapper.integration.hole_filling.enabled},
        {"beta", mapper.integration.hole_filling.beta},
        {"eta", mapper.integration.hole_filling.eta}}},
      {"occupancy",
       {{"p_hit", mapper.occupancy.p_hit},
        {"p_miss", mapper.occupancy.p_miss},
        {"p_min", mapper.occupancy.p_min},
        {"p_max", mapper.occupancy.p_max}}},
      {"registration", registration_json(mapper)},
      {"table_segmentation", mapper.segment_table},
      {"office", office_json(config.office)},
  };
}

json scan_json(const ScanRecord& r) {
  json j = {{"scan", r.scan},
            {"view", r.view},
            {"pose", pose_json(r.T_world_sensor)},
            {"actual_gain", r.actual_gain},
            {"reentered", r.reentered},
            {"unobserved", r.unobserved},
            {"coverage", r.coverage},
            {"surface_coverage", r.surface_coverage ? json(*r.surface_coverage) : json(nullptr)},
            {"raw_surface_coverage",
             r.raw_surface_coverage ? json(*r.raw_surface_coverage) : json(nullptr)},
            {"points", r.points},
            {"object_points", r.object_points},
            {"pose_error",
             {{"before_m", r.pose_error_before},
              {"after_m", r.pose_error_after},
              {"before_rad", r.yaw_error_before},
              {"after_rad", r.yaw_error_after},
              {"final_m", r.pose_error_final},
              {"final_rad", r.yaw_error_final},
              {"displacement_before_m", r.displacement_before},
              {"displacement_after_m", r.displacement_after},
              {"displacement_final_m", r.displacement_final}}},
            {"registration", perception::to_string(r.registration)},
            {"registration_figures",
             {{"position_sigma_m", r.registration_sigma},
              {"mahalanobis2", r.registration_mahalanobis2},
              {"pairs", r.registration_pairs},
              {"points", r.registration_points}}},
            {"reregistered", r.reregistered},
            {"seconds",
             {{"scan", r.seconds.scan},
              {"register", r.seconds.register_scan},
              {"segment", r.seconds.segment},
              {"integrate", r.seconds.integrate},
              {"plan", r.seconds.plan},
              {"candidates", r.seconds.candidates},
              {"reference", r.seconds.reference},
              {"calibrate", r.seconds.calibrate}}},
            {"travel_m", r.travel},
            {"fallback", r.fallback},
            {"candidates", r.candidates}};
  if (r.goal) j["goal"] = {r.goal->x(), r.goal->y(), r.goal->z()};
  json path = json::array();
  for (const Eigen::Vector3d& p : r.path) path.push_back({p.x(), p.y(), p.z()});
  j["path"] = path;
  j["predicted_gain"] = r.predicted_gain ? json(*r.predicted_gain) : json(nullptr);
  j["greedy_predicted_gain"] =
      r.greedy_predicted_gain ? json(*r.greedy_predicted_gain) : json(nullptr);
  j["predicted_cells"] = r.predicted_cells ? json(*r.predicted_cells) : json(nullptr);
  j["alpha"] = r.alpha ? json(*r.alpha) : json(nullptr);
  if (r.surface_rates) j["surface_rates"] = *r.surface_rates;
  j["search"] = r.search.empty() ? json(nullptr) : json(r.search);
  if (!r.calibration.empty()) j["calibration_cells"] = r.calibration;
  json considered = json::array();
  for (const CandidateRecord& c : r.considered) {
    considered.push_back(
        {{"view", c.view},
         {"pose", pose_json(c.T_world_sensor)},
         {"predicted_gain", c.predicted_gain},
         {"greedy_predicted_gain",
          c.greedy_predicted_gain ? json(*c.greedy_predicted_gain) : json(nullptr)},
         {"predicted_cells", c.predicted_cells},
         {"estimated", c.estimated}});
  }
  j["considered"] = considered;
  return j;
}

/// The scene as run.json records it: its name, source, kind, grid (the map's, `spec`), rooms
/// and sensor.
json scene_json(const sim::Scene& scene, const GridSpec& spec) {
  json rooms = json::array();
  for (const sim::Room& room : scene.rooms) {
    rooms.push_back({{"name", room.name},
                     {"min", {room.area.min().x(), room.area.min().y()}},
                     {"max", {room.area.max().x(), room.area.max().y()}}});
  }
  const SensorFov& fov = scene.fov();
  return {{"name", scene.name},
          {"source", scene.source},
          {"grid",
           {{"origin", {spec.origin.x(), spec.origin.y(), spec.origin.z()}},
            {"resolution", spec.resolution},
            {"dims", {spec.dims.x(), spec.dims.y(), spec.dims.z()}}}},
          {"rooms", rooms},
          {"kind", sim::to_string(scene.kind)},
          {"sensor",
           {{"h_fov_rad", fov.h_fov},
            {"v_fov_rad", fov.v_fov},
            {"min_range_m", fov.min_range},
            {"max_range_m", fov.max_range},
            {"sweep_steps", scene.sensor.sweep_steps}}}};
}

/// The hemisphere of a run's candidates, as run.json's config records it.
json hemisphere_json(const HemisphereConfig& h, std::size_t views) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  return {{"center_m", {h.center.x(), h.center.y(), h.center.z()}},
          {"radii_m", h.radii},
          {"elevations", h.elevations},
          {"min_elevation_deg", h.min_elevation * kDeg},
          {"max_elevation_deg", h.max_elevation * kDeg},
          {"spacing_m", h.spacing},
          {"arm_base_m", {h.base.x(), h.base.y(), h.base.z()}},
          {"arm_reach_m", std::isfinite(h.reach) ? json(h.reach) : json(nullptr)},
          {"views", views}};
}

}  // namespace

json run_json(const sim::Scene& scene, const GridSpec& spec, const ExplorationConfig& config,
              const ExplorationResult& result) {
  const std::string rule = fmt::format(
      "a surface cell of the objects (table and floor excluded) is covered once a registered "
      "point lies {}; surface_coverage divides by the cells the candidate views and starts hit "
      "with noise-free scans, raw_surface_coverage by all object surface cells",
      config.coverage_tolerance.describe());
  json run = {{"vantage_version", VANTAGE_VERSION},
              {"scene", scene_json(scene, spec)},
              {"config", config_json(config, scene)},
              {"stop_reason", result.stop_reason},
              {"observable_cells", result.observable_cells},
              {"surface_cells", result.surface_cells},
              {"visible_surface_cells", result.visible_surface_cells},
              {"surface_coverage_rule", rule},
              {"coverage_tolerance_cells", config.coverage_tolerance.cells},
              {"coverage_tolerance_m", config.coverage_tolerance.metres},
              {"scans", json::array()},
              {"candidates", json::array()}};
  if (scene.kind != sim::SceneKind::kOffice && run_candidate_set(scene, config) == "hemisphere") {
    run["config"]["hemisphere"] =
        hemisphere_json(run_hemisphere(scene, config), result.candidates.size());
  }
  for (const ScanRecord& r : result.scans) run["scans"].push_back(scan_json(r));
  for (const Eigen::Isometry3d& pose : result.candidates) {
    run["candidates"].push_back(pose_json(pose));
  }
  // NOTE: docs/model.md, "Bits are not cells": the probabilistic gain is information, greedy's
  // (which every other method decides by) a count of cells.
  run["gain_units"] = {
      {"predicted_gain", has_observability(config.planner.method) ? "bits" : "cells"},
      {"greedy_predicted_gain", "cells"},
      {"predicted_cells", "cells"}};
  const GainUnits units = gain_units(config.planner);
  run["units"] = units_json(units);
  run["objective"] = units.objective;
  run["sensor"] = sensor_json(scene.fov());
  return run;
}

}  // namespace vantage::detail
