// issue 53: a recording alone, planned without a manifest (`vantage plan FILE.bag --topic T`).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "vantage/io/recording.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// The half-angles of the widest points off the forward axis, on each image axis [rad].
struct HalfAngles {
  double horizontal = 0.0, vertical = 0.0;
};

/// Forward, horizontal and vertical coordinates of a point in a cloud frame.
Eigen::Vector3d sensor_axes(const Eigen::Vector3d& p, CloudFrame frame) {
  return frame == CloudFrame::kOptical ? Eigen::Vector3d(p.z(), p.x(), p.y())
                                       : Eigen::Vector3d(p.x(), p.y(), p.z());
}

/// The sensor: its range from the points, its field of view from CameraInfo or the points.
void sensor_of(const Recording& recording, const std::string& where, const std::string& topic,
               Manifest& manifest) {
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
  HalfAngles half;
  for (const RecordingFrame& frame : recording.frames) {
    for (const Eigen::Vector3d& p : frame.points) {
      const double range = p.norm();
      nearest = std::min(nearest, range);
      farthest = std::max(farthest, range);
      const Eigen::Vector3d a = sensor_axes(p, manifest.frame);
      if (a.x() > 0.0) {
        half.horizontal = std::max(half.horizontal, std::atan2(std::abs(a.y()), a.x()));
        half.vertical = std::max(half.vertical, std::atan2(std::abs(a.z()), a.x()));
      }
    }
  }
  if (!(farthest > 0.0)) {
    throw std::runtime_error(
        cat(where, ": the frames of ", printable(topic, 60), " hold no point to map"));
  }
  const double min_range = std::max(1.0, std::floor(nearest * 10.0)) / 10.0;
  const double max_range = std::max(min_range + 0.1, std::ceil(farthest * 10.0) / 10.0);
  try {
    if (recording.intrinsics) {
      manifest.intrinsics = recording.intrinsics;
      manifest.fov = fov_from_intrinsics(*recording.intrinsics, min_range, max_range);
    } else {
      constexpr double kDeg = std::numbers::pi / 180.0;
      // NOTE: whole degrees, at least 1 and at most 179, that hold every point in front.
      const auto whole_degrees = [&](double half_angle) {
        return std::clamp(std::ceil(2.0 * half_angle / kDeg), 1.0, 179.0) * kDeg;
      };
      manifest.fov = {whole_degrees(half.horizontal), whole_degrees(half.vertical), min_range,
                      max_range};
      manifest.fov.validate();
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(cat(where, ": the sensor of ", printable(topic, 60), ": ", e.what()));
  }
}

/// The region (given, or the posed frames' extent and a cell's margin) and the resolution
/// (given, or recording_resolution's).
void region_of(const RecordingAloneOptions& options, const std::string& where, Manifest& manifest) {
  const double resolution =
      options.resolution ? *options.resolution : recording_resolution(manifest.fov.max_range);
  if (options.roi) {
    manifest.roi = *options.roi;
  } else {
    Eigen::AlignedBox3d extent;
    for (const ManifestCloud& cloud : manifest.clouds) {
      if (cloud.pose_from_registration) continue;
      for (const Eigen::Vector3d& p : *cloud.points) extent.extend(cloud.T_world_cloud * p);
    }
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(resolution);
    manifest.roi = Eigen::AlignedBox3d(extent.min() - margin, extent.max() + margin);
  }
  try {
    manifest.grid = grid_for_roi(manifest.roi, resolution);
  } catch (const std::invalid_argument& e) {
    const Eigen::Vector3d& a = manifest.roi.min();
    const Eigen::Vector3d& b = manifest.roi.max();
    throw std::runtime_error(cat(where, ": ", options.roi ? "--roi" : "the frames' extent", " (",
                                 a.x(), ", ", a.y(), ", ", a.z(), " to ", b.x(), ", ", b.y(), ", ",
                                 b.z(), " m) at ", resolution, " m: ", e.what(),
                                 options.roi ? "" : " (give --roi or a coarser --resolution)"));
  }
}

}  // namespace

double recording_resolution(double max_range) {
  const double raw = max_range / 200.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade;
  for (const double m : {5.0, 2.0}) {
    if (m * decade <= raw) {
      step = m * decade;
      break;
    }
  }
  // NOTE: printed and read back, so that 0.005 is the double "0.005" a manifest would give.
  char text[32];
  std::snprintf(text, sizeof(text), "%.0e", step);
  return std::strtod(text, nullptr);
}

Manifest manifest_for_recording(const std::filesystem::path& path,
                                const RecordingAloneOptions& options) {
  Recording recording = read_recording(path, options.read);
  const std::string where = path.string();
  Manifest manifest;
  manifest.file = path;
  manifest.recording = path;
  manifest.salvage = recording.salvage;
  std::vector<RecordingFrame>& frames = recording.frames;
  manifest.frame = frames.front().frame_id.ends_with("optical_frame") ? CloudFrame::kOptical
                                                                      : CloudFrame::kXForward;
  sensor_of(recording, where, options.read.topic, manifest);

  // The frames, posed by tf; the first one tf does not pose defines the world.
  for (std::size_t i = 0; i < frames.size(); ++i) {
    RecordingFrame& frame = frames[i];
    ManifestCloud cloud;
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "%.6f", frame.stamp);
    cloud.file = cat(where, "@", stamp);
    cloud.stamp = frame.stamp;
    cloud.pose_from_registration = i > 0 && !frame.T_fixed_cloud;
    if (frame.T_fixed_cloud) cloud.T_world_cloud = *frame.T_fixed_cloud;
    cloud.non_finite = frame.non_finite;
    cloud.points = std::make_shared<const PointCloud>(std::move(frame.points));
    manifest.clouds.push_back(std::move(cloud));
  }
  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
  T_cloud_sensor.linear() = R_cloud_sensor(manifest.frame);
  for (ManifestCloud& cloud : manifest.clouds) {
    cloud.T_world_sensor = cloud.T_world_cloud * T_cloud_sensor;
  }
  region_of(options, where, manifest);
  return manifest;
}

}  // namespace vantage
