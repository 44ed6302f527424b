#include "vantage/experiment/recorded.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "vantage/io/cloud_io.hpp"
#include "vantage/io/depth_image.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/trajectory.hpp"

namespace vantage {

MapperConfig mapper_config_for(const Manifest& manifest) {
  MapperConfig config;
  // NOTE: a cloud without a pose after the first is placed by registration, whatever `icp` says.
  config.register_scans =
      manifest.options.icp ||
      std::any_of(manifest.clouds.begin(), manifest.clouds.end(),
                  [](const ManifestCloud& c) { return c.pose_from_registration; });
  config.segment_table = manifest.options.table_segmentation;
  config.integration.mode = manifest.options.integration;
  return config;
}

namespace {

/// A cloud's points in its cloud frame: a PCD or PLY file's, or a depth image's one per pixel.
PointCloud read_frame(const Manifest& manifest, const ManifestCloud& cloud, CloudReadStats& stats) {
  if (cloud.points) {
    stats.non_finite_skipped = cloud.non_finite;
    return *cloud.points;
  }
  if (lower_extension(cloud.file) != ".png") {
    return read_point_cloud(cloud.file, {.skip_non_finite = manifest.options.skip_non_finite},
                            &stats);
  }
  const DepthImage image = read_depth_png(cloud.file);
  try {
    // NOTE: read_manifest requires both with a depth image; a Manifest built in code may not.
    if (!manifest.intrinsics || !manifest.depth) {
      throw std::invalid_argument("a depth image needs the manifest's intrinsics and depth");
    }
    PointCloud points = depth_to_points(image, *manifest.intrinsics, *manifest.depth);
    if (points.empty()) throw std::runtime_error("no pixel has depth");
    return points;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: {}", cloud.file.string(), e.what()));
  }
}

}  // namespace

void map_recorded(const Manifest& manifest, Mapper& mapper, const CloudCallback& on_cloud) {
  const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(manifest.frame).transpose();
  // The pose the last cloud was mapped at: the guess of the next one without a pose.
  std::optional<Eigen::Isometry3d> last_pose;
  for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
    const ManifestCloud& cloud = manifest.clouds[i];
    RecordedCloud recorded;
    recorded.index = i;
    CloudReadStats stats;
    PointCloud points;
    try {
      points = read_frame(manifest, cloud, stats);
    } catch (const NonFinitePointError& e) {
      throw std::runtime_error(fmt::format(
          "{} (an organized RGB-D cloud marks pixels without depth so: set "
          "options.skip_non_finite: "
          "true in {} to drop them)",
          e.what(), manifest.file.empty() ? "the manifest" : manifest.file.filename().string()));
    }
    recorded.non_finite_skipped = stats.non_finite_skipped;
    for (Eigen::Vector3d& p : points) p = R_sensor_cloud * p;
    try {
      Eigen::Isometry3d T_world_sensor = cloud.T_world_sensor;
      if (cloud.pose_from_table) {
        perception::TablePoseConfig table;
        table.table_height = manifest.options.table_height;
        table.table = mapper.config().table;
        recorded.table_pose = perception::estimate_table_pose(points, table);
        if (!recorded.table_pose) {
          throw std::runtime_error(fmt::format(
              "no pose given, and no table to take one from: no plane of {} or more points lies "
              "below the sensor within {:.0f} deg of its up axis (give the cloud a pose)",
              table.table.min_inliers, table.max_tilt * 180.0 / std::numbers::pi));
        }
        T_world_sensor = recorded.table_pose->T_world_sensor;
      }
      PoseGuess guess = PoseGuess::kOdometry;
      if (cloud.pose_from_registration) {
        guess = PoseGuess::kPreviousScan;
        if (last_pose) T_world_sensor = *last_pose;
      }
      recorded.update = mapper.add_scan(points, T_world_sensor, manifest.fov, guess);
    } catch (const RegistrationFailed& e) {
      throw std::runtime_error(fmt::format(
          "{}: {} (cloud {} of {}, registered to the map of {})", cloud.file.string(), e.what(),
          i + 1, manifest.clouds.size(),
          i == 1 ? manifest.clouds[0].file.filename().string() : fmt::format("clouds 1 to {}", i)));
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}: {}", cloud.file.string(), e.what()));
    }
    last_pose = recorded.update.T_world_sensor;
    if (on_cloud) on_cloud(recorded);
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
