#include "vantage/experiment/recorded.hpp"

#include <fmt/core.h>

#include <stdexcept>

#include "vantage/io/cloud_io.hpp"
#include "vantage/io/trajectory.hpp"

namespace vantage {

MapperConfig mapper_config_for(const Manifest& manifest) {
  MapperConfig config;
  config.register_scans = manifest.options.icp;
  config.segment_table = manifest.options.table_segmentation;
  config.integration.mode = manifest.options.integration;
  return config;
}

void map_recorded(const Manifest& manifest, Mapper& mapper, const CloudCallback& on_cloud) {
  const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(manifest.frame).transpose();
  for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
    const ManifestCloud& cloud = manifest.clouds[i];
    PointCloud points =
        read_point_cloud(cloud.file, {.skip_non_finite = manifest.options.skip_non_finite});
    for (Eigen::Vector3d& p : points) p = R_sensor_cloud * p;
    try {
      const MapperUpdate update = mapper.add_scan(points, cloud.T_world_sensor, manifest.fov);
      if (on_cloud) on_cloud(i, update);
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}: {}", cloud.file.string(), e.what()));
    }
  }
}

std::vector<Eigen::Isometry3d> read_candidate_poses(const std::filesystem::path& path,
                                                    CloudFrame frame) {
  const Eigen::Matrix3d R = R_cloud_sensor(frame);
  std::vector<Eigen::Isometry3d> poses;
  for (const StampedPose& pose : read_tum_trajectory(path)) {
    Eigen::Isometry3d T_world_sensor = pose.T_world_frame;
    T_world_sensor.linear() = pose.T_world_frame.linear() * R;
    poses.push_back(T_world_sensor);
  }
  if (poses.empty()) throw std::runtime_error(fmt::format("{}: no candidate poses", path.string()));
  return poses;
}

}  // namespace vantage
