#include "vantage/perception/mapper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "vantage/perception/voxel_filter.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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

}  // namespace

void MapperConfig::validate() const {
  occupancy.validate();
  integration.validate();
  if (register_scans) {
    registration.validate();
    map.validate();
  }
  if (segment_table) table.validate();
}

Mapper::Mapper(const GridSpec& grid, const MapperConfig& config)
    : Mapper(OccupancyGrid(grid, config.occupancy), config) {}

Mapper::Mapper(OccupancyGrid grid, const MapperConfig& config)
    : config_(config), grid_(std::move(grid)) {
  config_.validate();
  reference_ = perception::VoxelMap(config_.map);
}

MapperUpdate Mapper::add_scan(const PointCloud& points_sensor,
                              const Eigen::Isometry3d& T_world_sensor_guess, const SensorFov& fov) {
  const ScanPart part{points_sensor, Eigen::Isometry3d::Identity(), fov};
  return add_scan(std::span<const ScanPart>(&part, 1), T_world_sensor_guess);
}

MapperUpdate Mapper::add_scan(std::span<const ScanPart> parts,
                              const Eigen::Isometry3d& T_world_sensor_guess) {
  if (!T_world_sensor_guess.matrix().allFinite()) {
    throw std::invalid_argument("scan pose is not finite");
  }
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
  MapperUpdate update;
  update.T_world_sensor_guess = T_world_sensor_guess;
  update.T_world_sensor = T_world_sensor_guess;

  // What each view contributes (its sensor frame): thinned, then the objects found at the guess.
  // NOTE: segmentation looks at the scan alone (the table and the objects on it move together),
  // so the guess serves as well as the corrected pose, and registration sees the objects only.
  std::vector<PointCloud> kept(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const ScanPart& part = parts[k];
    auto start = std::chrono::steady_clock::now();
    const Eigen::Isometry3d T_guess_part = compose(T_world_sensor_guess, part.T_scan_sensor);
    kept[k] = config_.thin_to_cells ? thin_to_cells(part.points_sensor, T_guess_part, grid_.spec())
                                    : part.points_sensor;
    update.points += part.points_sensor.size();
    update.seconds_integrate += seconds_since(start);
    start = std::chrono::steady_clock::now();
    if (config_.segment_table) {
      const perception::TableSegmentation table =
          perception::segment_table(transform(T_guess_part, kept[k]), config_.table);
      PointCloud objects;
      objects.reserve(table.object_indices.size());
      for (const std::size_t i : table.object_indices) objects.push_back(kept[k][i]);
      kept[k] = std::move(objects);
    }
    update.object_points += kept[k].size();
    update.seconds_segment += seconds_since(start);
  }

  auto start = std::chrono::steady_clock::now();
  bool trusted = scans_ == 0;  // the first scan defines the map frame
  if (config_.register_scans && scans_ > 0 && !reference_.empty()) {
    PointCloud scan;  // the scan's objects in its own frame
    for (std::size_t k = 0; k < parts.size(); ++k) {
      for (const Eigen::Vector3d& p : kept[k]) scan.push_back(parts[k].T_scan_sensor * p);
    }
    if (config_.register_overlap_only) scan = known_part(scan, T_world_sensor_guess, grid_);
    const perception::RegistrationResult r =
        perception::register_scan(scan, T_world_sensor_guess, reference_, config_.registration);
    update.registration = r.outcome;
    update.registered = r.accepted();
    trusted = r.accepted();
    update.T_world_sensor = r.T_world_sensor;
  }
  update.seconds_register = seconds_since(start);

  NetChange change(parts.size() > 1 ? grid_.spec().num_cells() : 0);
  PointCloud registered;  // the scan's objects in the world, for the reference
  for (std::size_t k = 0; k < parts.size(); ++k) {
    start = std::chrono::steady_clock::now();
    const Eigen::Isometry3d T_world_part = compose(update.T_world_sensor, parts[k].T_scan_sensor);
    const PointCloud objects = transform(T_world_part, kept[k]);
    IntegrationResult integration = integrate_scan(
        grid_, Scan{objects, Frustum(T_world_part, parts[k].fov)}, config_.integration);
    if (parts.size() > 1) {
      change.add(integration);
    } else {
      update.integration = std::move(integration);
    }
    if (config_.keep_object_cloud) objects_.insert(objects_.end(), objects.begin(), objects.end());
    if (config_.register_scans && trusted) {
      registered.insert(registered.end(), objects.begin(), objects.end());
    }
    update.seconds_integrate += seconds_since(start);
  }
  if (parts.size() > 1) update.integration = change.result();
  start = std::chrono::steady_clock::now();
  reference_.add(registered, update.T_world_sensor.translation());
  update.seconds_register += seconds_since(start);
  ++scans_;
  return update;
}

}  // namespace vantage
