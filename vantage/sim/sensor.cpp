#include "vantage/sim/sensor.hpp"

#include <cmath>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage::sim {

std::string_view to_string(SensorType type) {
  return type == SensorType::kRangeFinder ? "range_finder" : "rgbd";
}

SensorType parse_sensor_type(std::string_view name) {
  if (name == "range_finder") return SensorType::kRangeFinder;
  if (name == "rgbd") return SensorType::kRgbd;
  throw std::invalid_argument(cat("sensor type '", name, "' is not range_finder or rgbd"));
}

void RangeNoise::validate() const {
  if (!(sigma >= 0.0 && std::isfinite(sigma))) {
    throw std::invalid_argument(cat("sensor.noise.sigma must be >= 0 m, got ", sigma));
  }
  if (!(sigma_quadratic >= 0.0 && std::isfinite(sigma_quadratic))) {
    throw std::invalid_argument(
        cat("sensor.noise.sigma_quadratic must be >= 0, got ", sigma_quadratic));
  }
  if (!(reference_range >= 0.0 && std::isfinite(reference_range))) {
    throw std::invalid_argument(
        cat("sensor.noise.reference_range must be >= 0 m, got ", reference_range));
  }
}

void SensorConfig::validate() const {
  fov.validate();
  noise.validate();
  if (type == SensorType::kRgbd) {
    if (width < 1 || width > 16384) {
      throw std::invalid_argument(cat("sensor.width must be in [1, 16384] pixels, got ", width));
    }
    if (height < 1 || height > 16384) {
      throw std::invalid_argument(cat("sensor.height must be in [1, 16384] pixels, got ", height));
    }
  } else {
    if (!(angular_resolution > 0.0 && angular_resolution <= fov.h_fov)) {
      throw std::invalid_argument(cat("sensor.angular_resolution must be in (0, h_fov], got ",
                                      angular_resolution * 180.0 / std::numbers::pi, " deg"));
    }
    if (!(tilt_resolution > 0.0 && tilt_resolution <= fov.v_fov)) {
      throw std::invalid_argument(cat("sensor.tilt_resolution must be in (0, v_fov], got ",
                                      tilt_resolution * 180.0 / std::numbers::pi, " deg"));
    }
    const double rays = (fov.h_fov / angular_resolution) * (fov.v_fov / tilt_resolution);
    if (rays > 16384.0 * 16384.0) {
      throw std::invalid_argument(cat("sensor: ", rays, " rays per scan is too many"));
    }
  }
  if (sweep_steps < 1 || sweep_steps > 3600) {
    throw std::invalid_argument(cat("sensor.sweep_steps must be in [1, 3600], got ", sweep_steps));
  }
}

SensorConfig hokuyo_sensor() {
  SensorConfig s;
  s.name = "hokuyo";
  s.type = SensorType::kRangeFinder;
  s.fov = {deg2rad(90.0), deg2rad(45.0), 0.1, 3.0};
  s.angular_resolution = deg2rad(0.25);
  s.tilt_resolution = deg2rad(0.25);
  s.noise = {0.002, 0.0, 0.0};
  s.sweep_steps = 4;
  return s;
}

SensorConfig kinect_sensor() {
  SensorConfig s;
  s.name = "kinect";
  s.type = SensorType::kRgbd;
  s.fov = {deg2rad(57.0), deg2rad(43.0), 0.5, 3.5};
  s.width = 640;
  s.height = 480;
  s.noise = {0.0012, 0.0019, 0.4};
  s.sweep_steps = 8;
  return s;
}

std::vector<std::string> builtin_sensor_names() { return {"hokuyo", "kinect"}; }

SensorConfig builtin_sensor(std::string_view name) {
  if (name == "hokuyo") return hokuyo_sensor();
  if (name == "kinect") return kinect_sensor();
  throw std::invalid_argument(cat("unknown sensor '", name, "' (built in: hokuyo, kinect)"));
}

std::vector<Eigen::Vector3d> ray_directions(const SensorConfig& sensor) {
  sensor.validate();
  std::vector<Eigen::Vector3d> dirs;
  if (sensor.type == SensorType::kRgbd) {
    // Pinhole: pixel (u, v) looks through its centre; u runs to the sensor's right (-y), v down.
    const double fx = 0.5 * sensor.width / std::tan(sensor.fov.h_fov / 2.0);
    const double fy = 0.5 * sensor.height / std::tan(sensor.fov.v_fov / 2.0);
    dirs.reserve(static_cast<std::size_t>(sensor.width) * sensor.height);
    for (int v = 0; v < sensor.height; ++v) {
      for (int u = 0; u < sensor.width; ++u) {
        dirs.push_back(Eigen::Vector3d(1.0, -(u + 0.5 - 0.5 * sensor.width) / fx,
                                       -(v + 0.5 - 0.5 * sensor.height) / fy)
                           .normalized());
      }
    }
    return dirs;
  }
  // Tilting line scanner: line j lies in the plane tilted by phi about the sensor's y axis, beam i
  // at angle theta within it. Its direction cos(theta) (cos phi, 0, sin phi) + sin(theta) (0, 1, 0)
  // has z / x = tan(phi) and y / x = tan(theta) / cos(phi).
  const int lines =
      std::max(1, static_cast<int>(std::lround(sensor.fov.v_fov / sensor.tilt_resolution)));
  const int beams =
      std::max(1, static_cast<int>(std::lround(sensor.fov.h_fov / sensor.angular_resolution)));
  const double tan_h = std::tan(sensor.fov.h_fov / 2.0);
  dirs.reserve(static_cast<std::size_t>(lines) * beams);
  for (int j = 0; j < lines; ++j) {
    const double phi = sensor.fov.v_fov / 2.0 - (j + 0.5) * sensor.fov.v_fov / lines;
    for (int i = 0; i < beams; ++i) {
      const double theta = sensor.fov.h_fov / 2.0 - (i + 0.5) * sensor.fov.h_fov / beams;
      const Eigen::Vector3d d(std::cos(theta) * std::cos(phi), std::sin(theta),
                              std::cos(theta) * std::sin(phi));
      // NOTE: the line's ends bend outside the frustum's flat sides at large tilt; the real
      // scanner's software clips its field of view the same way.
      if (std::abs(d.y()) > d.x() * tan_h) continue;
      dirs.push_back(d);
    }
  }
  return dirs;
}

}  // namespace vantage::sim
