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

/// One point per map cell of a world-frame cloud.
PointCloud cells_of(const PointCloud& points_world, const GridSpec& grid) {
  Eigen::Isometry3d T_grid_world = Eigen::Isometry3d::Identity();
  T_grid_world.translation() = -grid.origin;
  return transform(
      T_grid_world.inverse(),
      perception::voxel_downsample(transform(T_grid_world, points_world), grid.resolution));
}

/// The points of `cloud` within a square of half-side `reach` around (x, y) of `centre`.
PointCloud crop(const PointCloud& cloud, const Eigen::Vector3d& centre, double reach) {
  PointCloud out;
  for (const Eigen::Vector3d& p : cloud) {
    if (std::abs(p.x() - centre.x()) <= reach && std::abs(p.y() - centre.y()) <= reach) {
      out.push_back(p);
    }
  }
  return out;
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
  if (register_scans) icp.validate();
  if (!(max_correction_translation >= 0.0) || !(max_correction_rotation >= 0.0)) {
    throw std::invalid_argument(
        cat("mapper.max_correction_translation and mapper.max_correction_rotation must be >= 0, "
            "got ",
            max_correction_translation, " m and ", max_correction_rotation, " rad"));
  }
  if (segment_table) table.validate();
}

Mapper::Mapper(const GridSpec& grid, const MapperConfig& config)
    : Mapper(OccupancyGrid(grid, config.occupancy), config) {}

Mapper::Mapper(OccupancyGrid grid, const MapperConfig& config)
    : config_(config), grid_(std::move(grid)) {
  config_.validate();
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

  auto start = std::chrono::steady_clock::now();
  // The scan as one cloud in its own frame: what registration aligns.
  PointCloud merged;
  if (parts.size() != 1) {
    for (const ScanPart& part : parts) {
      for (const Eigen::Vector3d& p : part.points_sensor) merged.push_back(part.T_scan_sensor * p);
    }
  }
  const PointCloud& scan = parts.size() == 1 ? parts[0].points_sensor : merged;
  const PointCloud source =
      config_.thin_to_cells ? thin_to_cells(scan, T_world_sensor_guess, grid_.spec()) : scan;
  if (config_.register_scans && scans_ > 0 && !reference_.empty() && !source.empty()) {
    register_to_map(source, parts, update);
  }
  const PointCloud source_world = transform(update.T_world_sensor, source);
  reference_.insert(reference_.end(), source_world.begin(), source_world.end());
  if (config_.thin_to_cells) reference_ = cells_of(reference_, grid_.spec());
  update.seconds_register = seconds_since(start);

  NetChange change(parts.size() > 1 ? grid_.spec().num_cells() : 0);
  for (const ScanPart& part : parts) {
    start = std::chrono::steady_clock::now();
    const Eigen::Isometry3d T_world_part = compose(update.T_world_sensor, part.T_scan_sensor);
    const PointCloud points_world =
        transform(T_world_part, config_.thin_to_cells
                                    ? thin_to_cells(part.points_sensor, T_world_part, grid_.spec())
                                    : part.points_sensor);
    update.seconds_integrate += seconds_since(start);

    start = std::chrono::steady_clock::now();
    PointCloud objects = config_.segment_table
                             ? perception::segment_table(points_world, config_.table).objects
                             : points_world;
    update.points += part.points_sensor.size();
    update.object_points += objects.size();
    update.seconds_segment += seconds_since(start);

    start = std::chrono::steady_clock::now();
    IntegrationResult integration =
        integrate_scan(grid_, Scan{objects, Frustum(T_world_part, part.fov)}, config_.integration);
    if (parts.size() > 1) {
      change.add(integration);
    } else {
      update.integration = std::move(integration);
    }
    update.seconds_integrate += seconds_since(start);
    objects_.insert(objects_.end(), objects.begin(), objects.end());
  }
  if (parts.size() > 1) update.integration = change.result();
  ++scans_;
  return update;
}

void Mapper::register_to_map(const PointCloud& scan, std::span<const ScanPart> parts,
                             MapperUpdate& update) const {
  const Eigen::Isometry3d& guess = update.T_world_sensor_guess;
  PointCloud nearby, overlap;
  if (config_.register_overlap_only) {
    double max_range = 0.0;
    for (const ScanPart& part : parts) max_range = std::max(max_range, part.fov.max_range);
    const double reach = max_range + 2.0 * config_.icp.initial_correspondence_distance;
    nearby = crop(reference_, guess.translation(), reach);
    overlap = known_part(scan, guess, grid_);
    if (nearby.empty() || overlap.size() < 3) return;
  }
  const perception::IcpResult icp =
      config_.register_overlap_only
          ? perception::register_scan(overlap, guess, nearby, config_.icp)
          : perception::register_scan(scan, guess, reference_, config_.icp);
  update.icp_fitness = icp.fitness;
  const perception::PoseError step = perception::pose_error(icp.T_world_sensor, guess);
  if (icp.converged && step.translation <= config_.max_correction_translation &&
      step.rotation <= config_.max_correction_rotation) {
    update.T_world_sensor = icp.T_world_sensor;
    update.registered = true;
  }
}

}  // namespace vantage
