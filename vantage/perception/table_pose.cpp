#include "vantage/perception/table_pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage::perception {

void TablePoseConfig::validate() const {
  if (!std::isfinite(table_height) || std::abs(table_height) > 1e5) {
    throw std::invalid_argument(
        cat("table_height must be a finite height within 1e5 m, got ", table_height));
  }
  if (!(max_tilt > 0.0 && max_tilt < std::numbers::pi / 2)) {
    throw std::invalid_argument(cat("max_tilt must be in (0, pi/2) rad, got ", max_tilt));
  }
  table.validate();
}

std::optional<TablePose> estimate_table_pose(const PointCloud& points_sensor,
                                             const TablePoseConfig& config) {
  config.validate();
  TableConfig search = config.table;
  search.max_angle = config.max_tilt;
  // NOTE: no height limits: the sensor's z is not the world's up, and a table far ahead of a
  // camera looking down lies above its level; the sensor must lie above the plane (d > 0).
  search.min_table_z = -std::numeric_limits<double>::infinity();
  search.max_table_z = std::numeric_limits<double>::infinity();
  const TableSegmentation table = segment_table(points_sensor, search);
  if (!table.found) return std::nullopt;
  const Eigen::Vector3d n = table.plane.head<3>();  // up, unit
  const double d = table.plane[3];                  // the sensor's height above the plane
  if (!(d > 0.0)) return std::nullopt;

  // The origin: below the objects' centroid, on the plane.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  if (!table.objects.empty()) {
    for (const Eigen::Vector3d& p : table.objects) centre += p;
    centre /= static_cast<double>(table.objects.size());
  } else {
    for (const Eigen::Vector3d& p : table.table_hull) centre += p;
    centre /= static_cast<double>(table.table_hull.size());
  }
  centre -= (n.dot(centre) + d) * n;

  // NOTE: the forward axis projected onto the table; a camera looking straight down has none,
  // and then the top of its image (its up axis) points forward.
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - n.x() * n;
  if (x.norm() < 0.1) x = Eigen::Vector3d::UnitZ() - n.z() * n;
  x.normalize();
  Eigen::Matrix3d R_world_sensor;
  R_world_sensor.row(0) = x.transpose();
  R_world_sensor.row(1) = n.cross(x).transpose();
  R_world_sensor.row(2) = n.transpose();

  TablePose pose;
  pose.T_world_sensor.linear() = R_world_sensor;
  pose.T_world_sensor.translation() =
      -R_world_sensor * centre + Eigen::Vector3d(0.0, 0.0, config.table_height);
  pose.height_above_table = d;
  pose.tilt = std::asin(std::clamp(-n.x(), -1.0, 1.0));
  pose.table_points = table.table_inliers;
  pose.object_points = table.objects.size();
  return pose;
}

}  // namespace vantage::perception
