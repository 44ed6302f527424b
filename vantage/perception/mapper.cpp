#include "vantage/perception/mapper.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "vantage/util/text.hpp"

namespace vantage {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void MapperConfig::validate() const {
  occupancy.validate();
  integration.validate();
  if (register_scans) icp.validate();
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
  if (!T_world_sensor_guess.matrix().allFinite()) {
    throw std::invalid_argument("scan pose is not finite");
  }
  for (std::size_t i = 0; i < points_sensor.size(); ++i) {
    if (!points_sensor[i].allFinite()) {
      throw std::invalid_argument(cat("scan point ", i, " is not finite (NaN or infinite)"));
    }
  }
  MapperUpdate update;
  update.T_world_sensor_guess = T_world_sensor_guess;
  update.T_world_sensor = T_world_sensor_guess;
  update.points = points_sensor.size();

  auto start = std::chrono::steady_clock::now();
  if (config_.register_scans && scans_ > 0 && !registered_.empty() && !points_sensor.empty()) {
    const perception::IcpResult icp =
        perception::register_scan(points_sensor, T_world_sensor_guess, registered_, config_.icp);
    update.icp_fitness = icp.fitness;
    if (icp.converged) {
      update.T_world_sensor = icp.T_world_sensor;
      update.registered = true;
    }
  }
  update.seconds_register = seconds_since(start);
  const PointCloud points_world = transform(update.T_world_sensor, points_sensor);

  start = std::chrono::steady_clock::now();
  PointCloud objects = config_.segment_table
                           ? perception::segment_table(points_world, config_.table).objects
                           : points_world;
  update.object_points = objects.size();
  update.seconds_segment = seconds_since(start);

  start = std::chrono::steady_clock::now();
  update.integration = integrate_scan(grid_, Scan{objects, Frustum(update.T_world_sensor, fov)},
                                      config_.integration);
  update.seconds_integrate = seconds_since(start);

  registered_.insert(registered_.end(), points_world.begin(), points_world.end());
  objects_.insert(objects_.end(), objects.begin(), objects.end());
  ++scans_;
  return update;
}

}  // namespace vantage
