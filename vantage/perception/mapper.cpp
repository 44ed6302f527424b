#include "vantage/perception/mapper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vantage/perception/voxel_filter.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// One point per map cell (the centroid of the cell's points), in the frame of `points`, which
/// `T_world_points` places in the world.
PointCloud thin_to_cells(const PointCloud& points, const Eigen::Isometry3d& T_world_points,
                         const GridSpec& grid) {
  // NOTE: shifted so that the filter's voxels are the grid's cells.
  Eigen::Isometry3d T_grid_points = T_world_points;
  T_grid_points.translation() -= grid.origin;
  const PointCloud thinned =
      perception::voxel_downsample(transform(T_grid_points, points), grid.resolution);
  return transform(T_grid_points.inverse(), thinned);
}

/// The points (scan frame) that land, under the pose guess, in cells the map already knows.
PointCloud known_part(const PointCloud& points, const Eigen::Isometry3d& T_world_points,
                      const OccupancyGrid& grid) {
  PointCloud out;
  for (const Eigen::Vector3d& p : points) {
    const std::optional<Index3> cell = grid.spec().find(T_world_points * p);
    if (cell && !grid.is_unobserved(grid.spec().linear(*cell))) out.push_back(p);
  }
  return out;
}

/// Every view's points in the scan's frame (the first view's sensor).
PointCloud in_scan_frame(const std::vector<ScanPart>& parts) {
  PointCloud out;
  for (const ScanPart& part : parts) {
    for (const Eigen::Vector3d& p : part.points_sensor) out.push_back(part.T_scan_sensor * p);
  }
  return out;
}

/// `T_world_scan * T_scan_sensor`, exactly `T_world_scan` for a view without a pan.
Eigen::Isometry3d compose(const Eigen::Isometry3d& T_world_scan,
                          const Eigen::Isometry3d& T_scan_sensor) {
  if ((T_scan_sensor.matrix().array() == Eigen::Matrix4d::Identity().array()).all()) {
    return T_world_scan;
  }
  return T_world_scan * T_scan_sensor;
}

/// Nets the cells that left and re-entered the unobserved set over several integrations (a
/// sweep's views), so that each cell counts once per scan.
class NetChange {
 public:
  explicit NetChange(std::size_t cells) : net_(cells, 0) {}
  void add(const IntegrationResult& r) {
    for (const std::uint32_t i : r.left_unobserved) step(i, -1);
    for (const std::uint32_t i : r.entered_unobserved) step(i, +1);
  }
  IntegrationResult result() const {
    IntegrationResult r;
    for (const std::uint32_t i : touched_) {
      if (net_[i] == -1) r.left_unobserved.push_back(i);
      if (net_[i] == +1) r.entered_unobserved.push_back(i);
    }
    return r;
  }

 private:
  void step(std::uint32_t i, int delta) {
    if (net_[i] == 0) touched_.push_back(i);
    net_[i] = static_cast<std::int8_t>(net_[i] + delta);
  }
  std::vector<std::int8_t> net_;
  std::vector<std::uint32_t> touched_;
};

/// Why a scan without a pose was refused, from its registration's check.
std::string describe_failure(const perception::RegistrationResult& r) {
  using perception::RegistrationOutcome;
  const std::string pairs = cat(r.correspondences, " of its ", r.points, " points paired");
  switch (r.outcome) {
    case RegistrationOutcome::kTooFewMatches:
      return cat("no pose given, and it does not overlap the map enough to register (", pairs, ")");
    case RegistrationOutcome::kOutsidePrior:
      return cat("no pose given, and registration moved it further than a frame's motion may (",
                 "squared Mahalanobis distance ", r.mahalanobis2, "; ", pairs, ")");
    case RegistrationOutcome::kUncertain:
      return cat("no pose given, and registration does not pin its pose (position sigma ",
                 r.position_sigma * 1000.0, " mm; ", pairs, ")");
    default:
      return cat("no pose given, and registration did not pass its check (",
                 perception::to_string(r.outcome), "; ", pairs, ")");
  }
}

/// Refuses a view whose pose or any point is not finite, naming it.
void check_parts(std::span<const ScanPart> parts) {
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string part = parts.size() > 1 ? cat("scan part ", k, " ") : std::string("scan ");
    if (!parts[k].T_scan_sensor.matrix().allFinite()) {
      throw std::invalid_argument(cat(part, "pose is not finite"));
    }
    for (std::size_t i = 0; i < parts[k].points_sensor.size(); ++i) {
      if (!parts[k].points_sensor[i].allFinite()) {
        throw std::invalid_argument(cat(part, "point ", i, " is not finite (NaN or infinite)"));
      }
    }
  }
}

/// What a view contributes, in its sensor frame: its points thinned to the grid's cells, then
/// the objects segmentation finds on the table at the scan's guess; counted and timed in
/// `update`.
ScanPart objects_of(const ScanPart& part, const Eigen::Isometry3d& T_world_sensor_guess,
                    const MapperConfig& config, const GridSpec& grid, MapperUpdate& update) {
  auto start = std::chrono::steady_clock::now();
  const Eigen::Isometry3d T_guess_part = compose(T_world_sensor_guess, part.T_scan_sensor);
  PointCloud kept = config.thin_to_cells ? thin_to_cells(part.points_sensor, T_guess_part, grid)
                                         : part.points_sensor;
  update.points += part.points_sensor.size();
  update.thinned_points += kept.size();
  update.seconds_integrate += seconds_since(start);
  start = std::chrono::steady_clock::now();
  if (config.segment_table) {
    const perception::TableSegmentation table =
        perception::segment_table(transform(T_guess_part, kept), config.table);
    update.table_views += table.found ? 1 : 0;
    PointCloud objects;
    objects.reserve(table.object_indices.size());
    for (const std::size_t i : table.object_indices) objects.push_back(kept[i]);
    kept = std::move(objects);
  }
  update.object_points += kept.size();
  update.seconds_segment += seconds_since(start);
  return {std::move(kept), part.T_scan_sensor, part.fov};
}

}  // namespace

void MapperConfig::validate() const {
  occupancy.validate();
  integration.validate();
  if (register_scans) {
    registration.validate();
    map.validate();
    unposed_prior.validate();
  }
  if (segment_table) table.validate();
  if (reregister_window < 0) {
    throw std::invalid_argument(cat("reregister_window must be >= 0, got ", reregister_window));
  }
}

Mapper::Mapper(const GridSpec& grid, const MapperConfig& config)
    : Mapper(OccupancyGrid(grid, config.occupancy), config) {}

Mapper::Mapper(OccupancyGrid grid, const MapperConfig& config)
    : config_(config), grid_(std::move(grid)) {
  config_.validate();
  reference_ = perception::VoxelMap(config_.map);
}

MapperUpdate Mapper::add_scan(const PointCloud& points_sensor,
                              const Eigen::Isometry3d& T_world_sensor_guess, const SensorFov& fov,
                              PoseGuess guess) {
  const ScanPart part{points_sensor, Eigen::Isometry3d::Identity(), fov};
  return add_scan(std::span<const ScanPart>(&part, 1), T_world_sensor_guess, guess);
}

MapperUpdate Mapper::add_scan(std::span<const ScanPart> parts,
                              const Eigen::Isometry3d& T_world_sensor_guess, PoseGuess guess) {
  const bool unposed = guess == PoseGuess::kPreviousScan;
  if (unposed && !config_.register_scans) {
    throw RegistrationFailed("no pose given, and registration is off (register_scans)");
  }
  if (unposed && scans_ == 0) {
    throw RegistrationFailed("no pose given, and no scan before it to register it to");
  }
  if (!T_world_sensor_guess.matrix().allFinite()) {
    throw std::invalid_argument("scan pose is not finite");
  }
  check_parts(parts);
  MapperUpdate update;
  update.T_world_sensor_guess = T_world_sensor_guess;
  update.T_world_sensor = T_world_sensor_guess;

  // What each view contributes (its sensor frame): thinned, then the objects found at the guess.
  // NOTE: segmentation looks at the scan alone (the table and the objects on it move together),
  // so the guess serves as well as the corrected pose, and registration sees the objects only.
  HeldScan scan{.index = scans_, .parts = {}, .T_world_sensor_guess = T_world_sensor_guess};
  for (const ScanPart& part : parts) {
    scan.parts.push_back(objects_of(part, T_world_sensor_guess, config_, grid_.spec(), update));
  }
  update.object_spread = perception::point_spread(in_scan_frame(scan.parts));
  place(scan, unposed, update);
  keep(std::move(scan), update);
  ++scans_;
  return update;
}

void Mapper::place(HeldScan& scan, bool unposed, MapperUpdate& update) {
  const auto start = std::chrono::steady_clock::now();
  scan.trusted = scans_ == 0;  // the first scan defines the map frame
  scan.T_world_sensor = scan.T_world_sensor_guess;
  if (unposed && reference_.empty()) {
    throw RegistrationFailed(
        "no pose given, and no map to register it to (the scans before it mapped no objects)");
  }
  if (config_.register_scans && scans_ > 0 && !reference_.empty()) {
    const perception::RegistrationResult r =
        register_held(scan, grid_, unposed ? config_.unposed_prior : config_.registration.prior);
    // NOTE: the check is the same as for a guess from odometry: a pose it would not trust is
    // no pose at all here, so the scan is refused before anything of it is mapped.
    if (unposed && !r.accepted()) throw RegistrationFailed(describe_failure(r));
    update.registration = r.outcome;
    update.registered = r.accepted();
    update.registration_result = r;
    scan.trusted = r.accepted();
    scan.T_world_sensor = r.T_world_sensor;
  }
  update.T_world_sensor = scan.T_world_sensor;
  if (config_.register_scans && scan.trusted) {
    reference_.add(world_points(scan), scan.T_world_sensor.translation());
    update.seconds_register += seconds_since(start);
    if (!held_.empty()) {
      update.reregistered = retry_pending(update.seconds_register, update.seconds_integrate);
    }
  } else {
    update.seconds_register += seconds_since(start);
  }
}

void Mapper::keep(HeldScan scan, MapperUpdate& update) {
  const auto start = std::chrono::steady_clock::now();
  if (config_.register_scans && config_.reregister_window > 0 && !scan.trusted && !checkpoint_) {
    checkpoint_ = grid_;
    checkpoint_objects_ = objects_.size();
  }
  update.integration = integrate(scan);
  if (checkpoint_) held_.push_back(std::move(scan));
  // NOTE: the oldest pending scan, once no later scan pinned it within the window, keeps its
  // guess for good, and so do the pending scans after it (the checkpoint precedes them all).
  if (!held_.empty() &&
      scans_ - held_.front().index >= static_cast<std::size_t>(config_.reregister_window)) {
    checkpoint_.reset();
    held_.clear();
  }
  update.seconds_integrate += seconds_since(start);
}

std::size_t Mapper::pending() const {
  return static_cast<std::size_t>(
      std::count_if(held_.begin(), held_.end(), [](const HeldScan& s) { return !s.trusted; }));
}

PointCloud Mapper::world_points(const HeldScan& scan) const {
  PointCloud out;
  for (const ScanPart& part : scan.parts) {
    const PointCloud objects =
        transform(compose(scan.T_world_sensor, part.T_scan_sensor), part.points_sensor);
    out.insert(out.end(), objects.begin(), objects.end());
  }
  return out;
}

perception::RegistrationResult Mapper::register_held(const HeldScan& scan,
                                                     const OccupancyGrid& known,
                                                     const perception::PoseSigma& prior) const {
  PointCloud points = in_scan_frame(scan.parts);
  if (config_.register_overlap_only) points = known_part(points, scan.T_world_sensor_guess, known);
  perception::RegistrationConfig registration = config_.registration;
  registration.prior = prior;
  return perception::register_scan(points, scan.T_world_sensor_guess, reference_, registration);
}

IntegrationResult Mapper::integrate(const HeldScan& scan) {
  NetChange change(scan.parts.size() > 1 ? grid_.spec().num_cells() : 0);
  IntegrationResult single;
  for (const ScanPart& part : scan.parts) {
    const Eigen::Isometry3d T_world_part = compose(scan.T_world_sensor, part.T_scan_sensor);
    const PointCloud objects = transform(T_world_part, part.points_sensor);
    IntegrationResult integration =
        integrate_scan(grid_, Scan{objects, Frustum(T_world_part, part.fov)}, config_.integration);
    if (scan.parts.size() > 1) {
      change.add(integration);
    } else {
      single = std::move(integration);
    }
    if (config_.keep_object_cloud) objects_.insert(objects_.end(), objects.begin(), objects.end());
  }
  return scan.parts.size() > 1 ? change.result() : single;
}

std::vector<MapperUpdate::Reregistered> Mapper::retry_pending(double& seconds_register,
                                                              double& seconds_integrate) {
  auto start = std::chrono::steady_clock::now();
  std::vector<MapperUpdate::Reregistered> passed;
  for (HeldScan& held : held_) {
    if (held.trusted) continue;
    // NOTE: the overlap is judged on the grid before the held scans, not on one they are in.
    const perception::RegistrationResult r =
        register_held(held, *checkpoint_, config_.registration.prior);
    if (!r.accepted()) continue;
    held.trusted = true;
    held.T_world_sensor = r.T_world_sensor;
    reference_.add(world_points(held), held.T_world_sensor.translation());
    passed.push_back({held.index, held.T_world_sensor});
  }
  seconds_register += seconds_since(start);
  if (passed.empty()) return passed;

  // The map as if every scan since the checkpoint had been registered when it came; the new
  // checkpoint is the grid just before the oldest scan still pending.
  start = std::chrono::steady_clock::now();
  grid_ = *std::exchange(checkpoint_, std::nullopt);
  objects_.resize(checkpoint_objects_);
  std::vector<HeldScan> still_held;
  for (HeldScan& held : held_) {
    if (!held.trusted && !checkpoint_) {
      checkpoint_ = grid_;
      checkpoint_objects_ = objects_.size();
    }
    integrate(held);
    if (checkpoint_) still_held.push_back(std::move(held));
  }
  held_ = std::move(still_held);
  seconds_integrate += seconds_since(start);
  return passed;
}

}  // namespace vantage
