// The explorer's scans (detail/explorer.hpp): a decision taken, its view scanned and mapped,
// and the record of what it did (timings, pose errors before and after registration, the cells
// it saw, the coverage), with the fits of alpha and of the surface rates updated from it.

#include <algorithm>

#include "vantage/experiment/detail/explorer.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

const ScanRecord& Explorer::take(Decision next) {
  const int k = static_cast<int>(result_.scans.size()) + 1;
  ScanRecord record;
  record.scan = k;
  record.view = next.view;
  record.T_world_sensor = next.pose;
  record.predicted_gain = next.predicted;
  record.greedy_predicted_gain = next.greedy_predicted;
  record.predicted_cells = next.predicted_cells;
  record.alpha = next.alpha;
  record.surface_rates = next.surface_rates;
  record.seconds.plan = next.seconds;
  record.seconds.candidates = next.candidate_seconds;
  record.seconds.reference = next.reference_seconds;
  record.travel = next.travel;
  record.fallback = next.fallback;
  record.goal = next.goal;
  record.path = std::move(next.path);
  if (!office_ && !result_.scans.empty()) {  // an office's decision drove its own path
    record.path = planner_.sequence.travel.path(result_.scans.back().T_world_sensor.translation(),
                                                record.T_world_sensor.translation());
  }
  record.candidates = next.candidates;
  record.considered = std::move(next.considered);
  record.search = std::move(next.search);

  // --alpha auto: what the view about to be scanned would see under every candidate a, set
  // against what it does see. The first scan calibrates too (on the empty map).
  if (fit_) {
    const auto start = Clock::now();
    const std::vector<Frustum> views = views_at(record.T_world_sensor);
    GainConfig gain = planner_.gain;
    gain.method = planner_.method.gain;
    record.calibration = expected_cells_by_alpha(mapper_.grid(), views, gain, fit_->alphas());
    record.seconds.calibrate = seconds_since(start);
  }
  if (surface_fit_) surface_fit_->before(mapper_.grid(), planner_.gain.num_threads);
  if (office_) {
    observe_sweep(k, record);
  } else {
    observe_view(k, record);
  }
  if (surface_fit_) {
    surface_fit_->after(mapper_.grid());
    planner_.gain.surface_rates = surface_fit_->rates();
  }
  if (fit_) {
    fit_->record(record.calibration, static_cast<double>(record.actual_gain));
    planner_.gain.alpha = fit_->alpha();
  }
  record.unobserved = mapper_.grid().counts().unobserved;
  record.coverage = coverage(mapper_.grid(), truth_.observable);
  if (surface_ != nullptr) {
    // NOTE: recounted from all registered points each scan: a re-registration moves earlier
    // scans' points too.
    const SurfaceCoverage s = surface_coverage(*surface_, mapper_.object_cloud());
    record.surface_coverage = s.visible;
    record.raw_surface_coverage = s.raw;
  }
  result_.scans.push_back(std::move(record));

  if (k == config_.scans) {
    done_ = true;
    result_.stop_reason = "took every scan asked for";
  } else if (!office_ && !config_.revisit &&
             std::find(taken_.begin(), taken_.end(), false) == taken_.end()) {
    done_ = true;
    result_.stop_reason = cat("every candidate view has been taken after scan ", k);
  }
  return result_.scans.back();
}

void Explorer::record_update(const MapperUpdate& update, const Eigen::Isometry3d& truth,
                             ScanRecord& record) {
  // NOTE: the errors are judged at truth, the integrated points where the scan saw them.
  const perception::PointSpread points = update.object_spread.transformed(truth);
  record.seconds.register_scan = update.seconds_register;
  record.seconds.segment = update.seconds_segment;
  record.seconds.integrate = update.seconds_integrate;
  const perception::PoseError before =
      perception::pose_error(update.T_world_sensor_guess, truth, points);
  const perception::PoseError after = perception::pose_error(update.T_world_sensor, truth, points);
  record.points_spread = points;
  record.pose_error_before = before.translation;
  record.yaw_error_before = before.rotation;
  record.displacement_before = before.displacement;
  record.pose_error_after = after.translation;
  record.yaw_error_after = after.rotation;
  record.displacement_after = after.displacement;
  record.pose_error_final = after.translation;
  record.displacement_final = after.displacement;
  record.registration = update.registration;
  record.registration_sigma = update.registration_result.position_sigma;
  record.registration_mahalanobis2 = update.registration_result.mahalanobis2;
  record.registration_pairs = update.registration_result.correspondences;
  record.registration_points = update.registration_result.points;
  record.yaw_error_final = after.rotation;
  record.points = update.points;
  record.object_points = update.object_points;
  record.actual_gain = update.integration.left_unobserved.size();
  record.reentered = update.integration.entered_unobserved.size();
}

void Explorer::observe_view(int k, ScanRecord& record) {
  const Eigen::Isometry3d& pose = record.T_world_sensor;
  const auto u = static_cast<std::uint64_t>(k);
  auto start = Clock::now();
  const sim::SimulatedScan scan = world_.scan(pose, stream_seed(config_.seed, u, 1));
  // NOTE: the first scan defines the map frame, so its pose is taken as known (§4.1); later
  // moves carry the scene's pose noise.
  const Eigen::Isometry3d believed =
      k == 1 ? pose : world_.noisy_pose(pose, stream_seed(config_.seed, u, 2));
  record.seconds.scan = seconds_since(start);

  const MapperUpdate update = mapper_.add_scan(scan.points_sensor, believed, scan.fov);
  record_update(update, pose, record);
  record_reregistered(update, record);
}

void Explorer::record_reregistered(const MapperUpdate& update, ScanRecord& record) {
  for (const MapperUpdate::Reregistered& r : update.reregistered) {
    ScanRecord& earlier = result_.scans.at(r.scan);
    const perception::PoseError error =
        perception::pose_error(r.T_world_sensor, earlier.T_world_sensor, earlier.points_spread);
    earlier.pose_error_final = error.translation;
    earlier.yaw_error_final = error.rotation;
    earlier.displacement_final = error.displacement;
    record.reregistered.push_back(earlier.scan);
  }
}

std::vector<Frustum> Explorer::views_at(const Eigen::Isometry3d& pose) const {
  return office_ ? sweep_frusta(scene_, pose) : std::vector<Frustum>{Frustum(pose, scene_.fov())};
}

}  // namespace vantage::detail
