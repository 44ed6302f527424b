#include "vantage/io/manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/io/detail/manifest_sources.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/io/yaml_reader.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool is_cloud_file(const fs::path& path) {
  const std::string ext = lower(path.extension().string());
  return ext == ".pcd" || ext == ".ply";
}

bool is_depth_image(const fs::path& path) { return lower(path.extension().string()) == ".png"; }

// 4 rows of 4 numbers, or 16 numbers row by row; then checked to be rigid.
Eigen::Isometry3d rigid(const YamlField& f) {
  Eigen::Matrix4d m;
  if (f.is_sequence() && f.size() == 4 && f[0].is_sequence()) {
    for (std::size_t r = 0; r < 4; ++r) {
      const YamlField row = f[r];
      if (!row.is_sequence() || row.size() != 4) row.fail("must be a row of 4 numbers");
      for (std::size_t c = 0; c < 4; ++c) {
        m(static_cast<int>(r), static_cast<int>(c)) = row[c].number();
      }
    }
  } else if (f.is_sequence() && f.size() == 16) {
    for (std::size_t k = 0; k < 16; ++k) {
      m(static_cast<int>(k / 4), static_cast<int>(k % 4)) = f[k].number();
    }
  } else {
    f.fail("must be a 4x4 matrix: 4 rows of 4 numbers, or 16 numbers row by row");
  }
  const std::string problem = rigid_transform_problem(m);
  if (!problem.empty()) f.fail(cat("not a rigid transform: ", problem));
  Eigen::Isometry3d T;
  T.matrix() = m;
  return T;
}

// The stamp a cloud is matched by: its `stamp`, else its file name if that is a number.
std::optional<double> stamp_from_name(const fs::path& file) {
  const std::string stem = file.stem().string();
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(stem.data(), stem.data() + stem.size(), value);
  if (ec != std::errc() || ptr != stem.data() + stem.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

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

Manifest read_manifest(const fs::path& path, const ManifestReadOptions& read_options) {
  Manifest manifest;
  std::error_code error;
  manifest.file = fs::is_directory(path, error) ? path / "manifest.yaml" : path;
  if (const std::string why = not_a_readable_file(manifest.file); !why.empty()) {
    throw std::runtime_error(
        cat(manifest.file.string(), ": ", why == "no such file" ? "no such manifest" : why));
  }
  const fs::path folder = manifest.file.parent_path();
  const YamlField root =
      read_yaml_file(manifest.file,
                     "a manifest: give the folder that holds it, or a manifest YAML that lists it "
                     "(docs/manifest.md)");
  root.allow_keys({"version", "clouds", "trajectory", "tum", "recording", "sensor", "roi",
                   "resolution", "options"});
  if (const auto version = root.get("version")) {
    if (version->number() != 1.0) version->fail("only version 1 exists");
  }

  // Sensor.
  {
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

  // Region of interest and resolution.
  {
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

  // Options.
  if (const auto options = root.get("options")) {
    options->allow_keys(
        {"table_segmentation", "icp", "integration", "skip_non_finite", "table_height"});
    if (const auto n = options->get("table_height")) {
      manifest.options.table_height = n->number();
      if (std::abs(manifest.options.table_height) > kMaxWorldCoordinate) {
        n->fail(cat("must lie within ", kMaxWorldCoordinate, " m of 0, got ",
                    manifest.options.table_height));
      }
    }
    if (const auto n = options->get("skip_non_finite")) {
      manifest.options.skip_non_finite = n->boolean();
    }
    if (const auto n = options->get("table_segmentation")) {
      manifest.options.table_segmentation = n->boolean();
    }
    if (const auto n = options->get("icp")) manifest.options.icp = n->boolean();
    if (const auto n = options->get("integration")) {
      try {
        manifest.options.integration = parse_integration_mode(n->text());
      } catch (const std::invalid_argument& e) {
        n->fail(e.what());
      }
    }
  }

  // Clouds: listed, or every .pcd/.ply beside the manifest.
  // The YAML entry of each cloud, for poses and errors; nothing for clouds found in the folder.
  std::vector<std::optional<YamlField>> entries;
  // Where a cloud's problem is reported: its entry, else the manifest's root.
  const auto at_entry = [&](std::size_t i) -> const YamlField& {
    return entries[i] ? *entries[i] : root;
  };
  // Clouds posed as they were read (a TUM folder's ground truth).
  std::vector<bool> posed;
  const auto tum = root.get("tum");
  const auto recording = root.get("recording");
  if (tum || recording) {
    const YamlField& key = tum ? *tum : *recording;
    if (tum && recording) key.fail("give a TUM folder or a recording, not both");
    if (root.has("clouds")) key.fail("give clouds, a TUM folder or a recording, not two");
    if (root.has("trajectory")) key.fail("its poses come with it: give no trajectory");
    if (tum) {
      detail::read_tum_key(*tum, folder, read_options, manifest);
    } else {
      detail::read_recording_key(*recording, folder, read_options, manifest);
    }
    posed.resize(manifest.clouds.size());
    for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
      posed[i] = !manifest.clouds[i].pose_from_registration;
    }
    entries.assign(manifest.clouds.size(), std::nullopt);
  } else if (read_options.every || read_options.topic) {
    root.fail_as("",
                 "--every and --topic choose frames of a TUM folder or a recording, and the "
                 "manifest names neither (tum, recording)");
  } else if (const auto clouds = root.get("clouds")) {
    const std::vector<YamlField> items = clouds->items();
    if (items.empty()) clouds->fail("is empty");
    for (const YamlField& entry : items) {
      entry.allow_keys({"file", "pose", "stamp"});
      const YamlField file = entry.at("file");
      ManifestCloud cloud;
      cloud.file = (folder / file.text()).lexically_normal();
      if (!is_cloud_file(cloud.file) && !is_depth_image(cloud.file)) {
        file.fail(cat("'", cloud.file.string(), "' is not a .pcd, .ply or .png file"));
      }
      if (const std::string why =
              input_file_problem(cloud.file, is_depth_image(cloud.file) ? InputKind::kDepthImage
                                                                        : InputKind::kPointCloud);
          !why.empty()) {
        file.fail(cat(cloud.file.string(), ": ", why));
      }
      if (const auto stamp = entry.get("stamp")) cloud.stamp = stamp->number();
      manifest.clouds.push_back(cloud);
      entries.push_back(entry);
    }
  } else {
    for (const auto& item :
         fs::directory_iterator(folder.empty() ? fs::path(".") : folder, error)) {
      if (!is_cloud_file(item.path())) continue;
      // NOTE: an entry named as a cloud that is no file (a folder, a FIFO) is said by name, not
      // skipped to be found missing later as "N poses but M clouds" (issue 53).
      if (const std::string why = input_file_problem(item.path(), InputKind::kPointCloud);
          !why.empty()) {
        root.fail_as("clouds", cat("missing, so the folder's .pcd and .ply files are taken, and ",
                                   item.path().string(), " ", why));
      }
      {
        ManifestCloud cloud;
        cloud.file = item.path().lexically_normal();
        manifest.clouds.push_back(cloud);
      }
    }
    std::sort(manifest.clouds.begin(), manifest.clouds.end(),
              [](const ManifestCloud& a, const ManifestCloud& b) {
                return a.file.filename().string() < b.file.filename().string();
              });
    if (manifest.clouds.empty()) {
      root.fail_as("clouds",
                   cat("missing, and the folder ", folder.string(), " holds no .pcd or .ply file"));
    }
    entries.assign(manifest.clouds.size(), std::nullopt);
  }

  // Poses: one matrix per cloud, or a trajectory.
  if (const auto trajectory = root.get("trajectory")) {
    trajectory->allow_keys({"file", "match", "max_time_difference"});
    for (const std::optional<YamlField>& entry : entries) {
      if (entry && entry->has("pose")) {
        entry->at("pose").fail("give poses per cloud or a trajectory, not both");
      }
    }
    const YamlField file = trajectory->at("file");
    manifest.trajectory = (folder / file.text()).lexically_normal();
    if (const auto match = trajectory->get("match")) {
      const std::string name = match->text();
      if (name == "order") {
        manifest.match = PoseMatch::kOrder;
      } else if (name == "timestamp") {
        manifest.match = PoseMatch::kTimestamp;
      } else {
        match->fail(cat("unknown '", name, "' (expected order or timestamp)"));
      }
    }
    if (const auto dt = trajectory->get("max_time_difference")) {
      manifest.max_time_difference = dt->positive();
    }
    if (const std::string why = input_file_problem(*manifest.trajectory, InputKind::kPoses);
        !why.empty()) {
      file.fail(cat(manifest.trajectory->string(), ": ", why));
    }
    const std::vector<StampedPose> poses = read_tum_trajectory(*manifest.trajectory);
    const std::string traj = manifest.trajectory->filename().string();
    if (manifest.match == PoseMatch::kOrder) {
      if (poses.size() != manifest.clouds.size()) {
        trajectory->fail(cat(traj, " holds ", poses.size(), " poses but there are ",
                             manifest.clouds.size(),
                             " clouds (match: order pairs them one to one)"));
      }
      for (std::size_t i = 0; i < poses.size(); ++i) {
        manifest.clouds[i].T_world_cloud = poses[i].T_world_frame;
      }
    } else {
      if (poses.empty()) trajectory->fail(cat(traj, " holds no poses"));
      for (std::size_t i = 1; i < poses.size(); ++i) {
        if (!(poses[i].stamp > poses[i - 1].stamp)) {
          trajectory->fail(cat(traj, ": time stamps must increase for match: timestamp (pose ", i,
                               " at ", poses[i].stamp, " s follows ", poses[i - 1].stamp, " s)"));
        }
      }
      for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
        ManifestCloud& cloud = manifest.clouds[i];
        const std::string key = cat("clouds[", i, "]");
        if (!cloud.stamp) cloud.stamp = stamp_from_name(cloud.file);
        if (!cloud.stamp) {
          at_entry(i).fail_as(key, cat("no stamp to match the trajectory by: give ", key,
                                       ".stamp, or name the file by its time stamp (",
                                       cloud.file.filename().string(), ")"));
        }
        const double t = *cloud.stamp;
        // Nearest pose in time; ties go to the earlier pose.
        const auto after =
            std::lower_bound(poses.begin(), poses.end(), t,
                             [](const StampedPose& p, double stamp) { return p.stamp < stamp; });
        auto best = after == poses.end() ? std::prev(after) : after;
        if (after != poses.begin() &&
            (after == poses.end() || t - std::prev(after)->stamp <= after->stamp - t)) {
          best = std::prev(after);
        }
        const double dt = std::abs(best->stamp - t);
        if (dt > manifest.max_time_difference) {
          (entries[i] ? *entries[i] : *trajectory)
              .fail_as(key, cat("no pose in ", traj, " within ", manifest.max_time_difference,
                                " s of stamp ", t, " (the nearest is ", dt, " s away)"));
        }
        cloud.T_world_cloud = best->T_world_frame;
      }
    }
  } else {
    posed.resize(manifest.clouds.size());
    for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
      const std::string key = cat("clouds[", i, "].pose");
      manifest.clouds[i].pose_from_registration = false;
      if (posed[i]) continue;
      if (entries[i] && entries[i]->has("pose")) {
        manifest.clouds[i].T_world_cloud = rigid(entries[i]->at("pose"));
        continue;
      }
      // A PCD file may carry its own pose (VIEWPOINT), as PCL and strands' nbv_planning record it.
      const std::optional<Eigen::Isometry3d> viewpoint =
          is_depth_image(manifest.clouds[i].file) || manifest.clouds[i].points
              ? std::nullopt
              : read_cloud_viewpoint(manifest.clouds[i].file);
      const std::string name = manifest.clouds[i].file.filename().string();
      // NOTE: only the first cloud defines the world (a pose from the table would define it
      // again, and disagree); each later cloud without a pose is registered to the map so far.
      if (!viewpoint && i > 0) {
        manifest.clouds[i].pose_from_registration = true;
        continue;
      }
      if (!viewpoint && manifest.options.table_segmentation) {
        manifest.clouds[i].pose_from_table = true;
        continue;
      }
      if (!viewpoint) {
        at_entry(i).fail_as(key,
                            cat("missing: the first cloud ", name,
                                " has no pose (give it a pose, a trajectory, a "
                                "VIEWPOINT other than the identity in the PCD file, or "
                                "options.table_segmentation: true for a pose from the table)"));
      }
      manifest.clouds[i].T_world_cloud = *viewpoint;
      manifest.clouds[i].pose_from_viewpoint = true;
    }
  }

  detail::check_depth_images(root, manifest);
  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
  T_cloud_sensor.linear() = R_cloud_sensor(manifest.frame);
  for (ManifestCloud& cloud : manifest.clouds) {
    cloud.T_world_sensor = cloud.T_world_cloud * T_cloud_sensor;
  }
  return manifest;
}

}  // namespace vantage
