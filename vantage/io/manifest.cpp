#include "vantage/io/manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <system_error>

#include "vantage/io/detail/manifest_sources.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/yaml_reader.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

std::string_view to_string(CloudFrame frame) {
  return frame == CloudFrame::kOptical ? "optical" : "x_forward";
}

CloudFrame parse_cloud_frame(std::string_view name) {
  if (name == "optical") return CloudFrame::kOptical;
  if (name == "x_forward") return CloudFrame::kXForward;
  throw std::invalid_argument(
      cat("unknown cloud frame '", name, "' (expected optical or x_forward)"));
}

Eigen::Matrix3d R_cloud_sensor(CloudFrame frame) {
  if (frame == CloudFrame::kXForward) return Eigen::Matrix3d::Identity();
  // Columns: the sensor's x (forward), y (left), z (up) in optical axes (z fwd, x right, y down).
  Eigen::Matrix3d R;
  R << 0, -1, 0,  //
      0, 0, -1,   //
      1, 0, 0;
  return R;
}

void PinholeIntrinsics::validate() const {
  if (!(std::isfinite(fx) && fx > 0.0)) {
    throw std::invalid_argument(cat("intrinsics.fx must be positive, got ", fx));
  }
  if (!(std::isfinite(fy) && fy > 0.0)) {
    throw std::invalid_argument(cat("intrinsics.fy must be positive, got ", fy));
  }
  if (width < 1) throw std::invalid_argument(cat("intrinsics.width must be >= 1, got ", width));
  if (height < 1) throw std::invalid_argument(cat("intrinsics.height must be >= 1, got ", height));
  if (!(std::isfinite(cx) && cx > -0.5 && cx < width - 0.5)) {
    throw std::invalid_argument(
        cat("intrinsics.cx must lie inside the image (-0.5, ", width - 0.5, "), got ", cx));
  }
  if (!(std::isfinite(cy) && cy > -0.5 && cy < height - 0.5)) {
    throw std::invalid_argument(
        cat("intrinsics.cy must lie inside the image (-0.5, ", height - 0.5, "), got ", cy));
  }
}

SensorFov fov_from_intrinsics(const PinholeIntrinsics& k, double min_range, double max_range) {
  k.validate();
  SensorFov fov;
  fov.h_fov = 2.0 * std::atan(std::min(k.cx + 0.5, k.width - 0.5 - k.cx) / k.fx);
  fov.v_fov = 2.0 * std::atan(std::min(k.cy + 0.5, k.height - 0.5 - k.cy) / k.fy);
  fov.min_range = min_range;
  fov.max_range = max_range;
  fov.validate();
  return fov;
}

GridSpec grid_for_roi(const Eigen::AlignedBox3d& roi, double resolution) {
  if (!(std::isfinite(resolution) && resolution > 0.0)) {
    throw std::invalid_argument(
        cat("resolution must be a positive number of metres, got ", resolution));
  }
  if (!roi.min().allFinite() || !roi.max().allFinite()) {
    throw std::invalid_argument("roi must be finite");
  }
  GridSpec spec;
  spec.resolution = resolution;
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) {
    const char* axis = a == 0 ? "x" : (a == 1 ? "y" : "z");
    if (!(roi.max()[a] > roi.min()[a])) {
      throw std::invalid_argument(cat("roi has zero or negative size: max.", axis, " (",
                                      roi.max()[a], ") must exceed min.", axis, " (", roi.min()[a],
                                      ")"));
    }
    // NOTE: the small slack keeps a bound that is a whole multiple of the resolution, up to
    // rounding, from adding a cell.
    const double lo = std::floor(roi.min()[a] / resolution + 1e-9);
    const double hi = std::ceil(roi.max()[a] / resolution - 1e-9);
    const double n = std::max(hi - lo, 1.0);
    cells *= n;
    if (n > static_cast<double>(kMaxGridCells) || cells > static_cast<double>(kMaxGridCells)) {
      throw std::invalid_argument(cat("grid too large: the roi at resolution ", resolution,
                                      " m needs more than ", kMaxGridCells, " cells"));
    }
    spec.origin[a] = lo * resolution;
    spec.dims[a] = static_cast<int>(n);
  }
  spec.validate();
  return spec;
}

namespace {

/// `sensor`: its frame, the depth images' encoding, and the field of view from intrinsics or
/// angles.
void read_sensor(const YamlField& root, Manifest& manifest) {
  const YamlField sensor = root.at("sensor");
  sensor.allow_keys({"frame", "intrinsics", "fov_deg", "min_range", "max_range", "depth"});
  if (const auto depth = sensor.get("depth")) {
    depth->allow_keys({"scale", "invalid"});
    DepthEncoding encoding;
    encoding.units_per_metre = depth->at("scale").positive();
    if (const auto invalid = depth->get("invalid")) {
      encoding.invalid = static_cast<std::uint16_t>(invalid->integer(0, 65535));
    }
    manifest.depth = encoding;
  }
  const YamlField frame = sensor.at("frame");
  try {
    manifest.frame = parse_cloud_frame(frame.text());
  } catch (const std::invalid_argument& e) {
    frame.fail(e.what());
  }
  const double min_range = sensor.at("min_range").number();
  const double max_range = sensor.at("max_range").number();
  const auto intrinsics = sensor.get("intrinsics");
  const auto fov_deg = sensor.get("fov_deg");
  if (intrinsics && fov_deg) sensor.fail("give intrinsics or fov_deg, not both");
  try {
    if (intrinsics) {
      intrinsics->allow_keys({"fx", "fy", "cx", "cy", "width", "height"});
      PinholeIntrinsics k;
      k.fx = intrinsics->at("fx").number();
      k.fy = intrinsics->at("fy").number();
      k.cx = intrinsics->at("cx").number();
      k.cy = intrinsics->at("cy").number();
      k.width = intrinsics->at("width").integer(1, std::numeric_limits<int>::max());
      k.height = intrinsics->at("height").integer(1, std::numeric_limits<int>::max());
      manifest.intrinsics = k;
      manifest.fov = fov_from_intrinsics(k, min_range, max_range);
    } else if (fov_deg) {
      fov_deg->allow_keys({"horizontal", "vertical"});
      manifest.fov.h_fov = deg2rad(fov_deg->at("horizontal").number());
      manifest.fov.v_fov = deg2rad(fov_deg->at("vertical").number());
      manifest.fov.min_range = min_range;
      manifest.fov.max_range = max_range;
      manifest.fov.validate();
    } else {
      sensor.fail("give the field of view as intrinsics or fov_deg");
    }
  } catch (const std::invalid_argument& e) {
    sensor.fail(e.what());
  }
}

/// `roi` and `resolution`: the region of interest and its grid.
void read_region(const YamlField& root, Manifest& manifest) {
  const YamlField roi = root.at("roi");
  roi.allow_keys({"min", "max"});
  manifest.roi = Eigen::AlignedBox3d(roi.at("min").vec3(), roi.at("max").vec3());
  const double resolution = root.at("resolution").positive();
  try {
    manifest.grid = grid_for_roi(manifest.roi, resolution);
  } catch (const std::invalid_argument& e) {
    roi.fail_as("", e.what());  // the message names roi or resolution
  }
}

/// `options`, each optional.
void read_manifest_options(const YamlField& options, ManifestOptions& out) {
  options.allow_keys(
      {"table_segmentation", "icp", "integration", "skip_non_finite", "table_height"});
  if (const auto n = options.get("table_height")) {
    out.table_height = n->number();
    if (std::abs(out.table_height) > kMaxWorldCoordinate) {
      n->fail(cat("must lie within ", kMaxWorldCoordinate, " m of 0, got ", out.table_height));
    }
  }
  if (const auto n = options.get("skip_non_finite")) out.skip_non_finite = n->boolean();
  if (const auto n = options.get("table_segmentation")) out.table_segmentation = n->boolean();
  if (const auto n = options.get("icp")) out.icp = n->boolean();
  if (const auto n = options.get("integration")) {
    try {
      out.integration = parse_integration_mode(n->text());
    } catch (const std::invalid_argument& e) {
      n->fail(e.what());
    }
  }
}

}  // namespace

Manifest read_manifest(const fs::path& path, const ManifestReadOptions& read_options) {
  Manifest manifest;
  std::error_code error;
  manifest.file = fs::is_directory(path, error) ? path / "manifest.yaml" : path;
  if (const std::string why = not_a_readable_file(manifest.file); !why.empty()) {
    throw std::runtime_error(
        cat(manifest.file.string(), ": ", why == "no such file" ? "no such manifest" : why));
  }
  const YamlField root =
      read_yaml_file(manifest.file,
                     "a manifest: give the folder that holds it, or a manifest YAML that lists it "
                     "(docs/manifest.md)");
  root.allow_keys({"version", "clouds", "trajectory", "tum", "recording", "sensor", "roi",
                   "resolution", "options"});
  if (const auto version = root.get("version")) {
    if (version->number() != 1.0) version->fail("only version 1 exists");
  }
  read_sensor(root, manifest);
  read_region(root, manifest);
  if (const auto options = root.get("options")) read_manifest_options(*options, manifest.options);
  const detail::ManifestEntries entries =
      detail::read_clouds(root, manifest.file.parent_path(), read_options, manifest);
  detail::read_poses(root, entries, manifest);
  detail::check_depth_images(root, manifest);
  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
  T_cloud_sensor.linear() = R_cloud_sensor(manifest.frame);
  for (ManifestCloud& cloud : manifest.clouds) {
    cloud.T_world_sensor = cloud.T_world_cloud * T_cloud_sensor;
  }
  return manifest;
}

}  // namespace vantage
