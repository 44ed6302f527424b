#include "vantage/io/manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/trajectory.hpp"
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

// Reads one YAML document with errors of the form "file:line: key: what".
class Reader {
 public:
  explicit Reader(fs::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    const YAML::Mark mark = at.Mark();
    const std::string line = mark.line >= 0 ? cat(":", mark.line + 1) : std::string();
    throw std::runtime_error(cat(file_.string(), line, ": ", key, key.empty() ? "" : ": ", what));
  }

  // A map with only the allowed keys.
  void check_map(const YAML::Node& node, const std::string& key,
                 std::initializer_list<std::string_view> allowed) const {
    if (!node.IsMap()) fail(node, key, "must be a map");
    for (const auto& entry : node) {
      const std::string name = entry.first.Scalar();
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        std::string list;
        for (std::string_view a : allowed) list += cat(list.empty() ? "" : ", ", a);
        fail(entry.first, key.empty() ? name : cat(key, ".", name),
             cat("unknown key (expected one of: ", list, ")"));
      }
    }
  }

  YAML::Node required(const YAML::Node& map, const std::string& key, const char* name) const {
    const YAML::Node node = map[name];
    if (!node) fail(map, join(key, name), "missing");
    return node;
  }

  static std::string join(const std::string& key, const char* name) {
    return key.empty() ? std::string(name) : cat(key, ".", name);
  }

  double number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "must be a number");
    const std::string text = node.Scalar();
    const std::string l = lower(text);
    if (l == ".nan" || l == "nan") fail(node, key, "is NaN");
    if (l == ".inf" || l == "+.inf" || l == "-.inf" || l == "inf" || l == "-inf") {
      fail(node, key, "is infinite");
    }
    std::string_view view = text;
    if (view.starts_with("+")) view.remove_prefix(1);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(view.data(), view.data() + view.size(), value);
    if (ec != std::errc() || ptr != view.data() + view.size() || view.empty()) {
      fail(node, key, cat("'", text, "' is not a number"));
    }
    if (!std::isfinite(value)) fail(node, key, "is not finite");
    return value;
  }

  double positive(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value > 0.0)) fail(node, key, cat("must be positive, got ", value));
    return value;
  }

  int positive_integer(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (value != std::floor(value) || value < 1.0 || value > std::numeric_limits<int>::max()) {
      fail(node, key, cat("must be a positive whole number, got ", node.Scalar()));
    }
    return static_cast<int>(value);
  }

  bool boolean(const YAML::Node& node, const std::string& key) const {
    bool value = false;
    if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
      fail(node, key, "must be true or false");
    }
    return value;
  }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, key, "must be a non-empty string");
    return node.Scalar();
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(node, key, "must be a list of 3 numbers");
    Eigen::Vector3d v;
    for (std::size_t i = 0; i < 3; ++i)
      v[static_cast<int>(i)] = number(node[i], cat(key, "[", i, "]"));
    return v;
  }

  // 4 rows of 4 numbers, or 16 numbers row by row; then checked to be rigid.
  Eigen::Isometry3d rigid(const YAML::Node& node, const std::string& key) const {
    Eigen::Matrix4d m;
    if (node.IsSequence() && node.size() == 4 && node[0].IsSequence()) {
      for (std::size_t r = 0; r < 4; ++r) {
        const YAML::Node row = node[r];
        if (!row.IsSequence() || row.size() != 4) {
          fail(row, cat(key, "[", r, "]"), "must be a row of 4 numbers");
        }
        for (std::size_t c = 0; c < 4; ++c) {
          m(static_cast<int>(r), static_cast<int>(c)) =
              number(row[c], cat(key, "[", r, "][", c, "]"));
        }
      }
    } else if (node.IsSequence() && node.size() == 16) {
      for (std::size_t k = 0; k < 16; ++k) {
        m(static_cast<int>(k / 4), static_cast<int>(k % 4)) =
            number(node[k], cat(key, "[", k, "]"));
      }
    } else {
      fail(node, key, "must be a 4x4 matrix: 4 rows of 4 numbers, or 16 numbers row by row");
    }
    const std::string problem = rigid_transform_problem(m);
    if (!problem.empty()) fail(node, key, cat("not a rigid transform: ", problem));
    Eigen::Isometry3d T;
    T.matrix() = m;
    return T;
  }

  const fs::path& file() const { return file_; }

 private:
  fs::path file_;
};

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

Manifest read_manifest(const fs::path& path) {
  Manifest manifest;
  std::error_code error;
  manifest.file = fs::is_directory(path, error) ? path / "manifest.yaml" : path;
  if (!fs::is_regular_file(manifest.file, error)) {
    throw std::runtime_error(cat(manifest.file.string(), ": no such manifest"));
  }
  const fs::path folder = manifest.file.parent_path();
  const Reader in(manifest.file);

  YAML::Node root;
  try {
    root = YAML::LoadFile(manifest.file.string());
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.line >= 0 ? cat(":", e.mark.line + 1) : std::string();
    throw std::runtime_error(cat(manifest.file.string(), line, ": ", e.msg));
  }
  if (!root.IsMap()) in.fail(root, "manifest", "must be a YAML map of settings");
  in.check_map(root, "",
               {"version", "clouds", "trajectory", "sensor", "roi", "resolution", "options"});
  if (const YAML::Node version = root["version"]) {
    if (in.number(version, "version") != 1.0) in.fail(version, "version", "only version 1 exists");
  }

  // Sensor.
  {
    const YAML::Node sensor = in.required(root, "", "sensor");
    in.check_map(sensor, "sensor", {"frame", "intrinsics", "fov_deg", "min_range", "max_range"});
    const YAML::Node frame = in.required(sensor, "sensor", "frame");
    try {
      manifest.frame = parse_cloud_frame(in.text(frame, "sensor.frame"));
    } catch (const std::invalid_argument& e) {
      in.fail(frame, "sensor.frame", e.what());
    }
    const double min_range =
        in.number(in.required(sensor, "sensor", "min_range"), "sensor.min_range");
    const double max_range =
        in.number(in.required(sensor, "sensor", "max_range"), "sensor.max_range");
    const YAML::Node intrinsics = sensor["intrinsics"];
    const YAML::Node fov_deg = sensor["fov_deg"];
    if (intrinsics && fov_deg) in.fail(sensor, "sensor", "give intrinsics or fov_deg, not both");
    try {
      if (intrinsics) {
        in.check_map(intrinsics, "sensor.intrinsics", {"fx", "fy", "cx", "cy", "width", "height"});
        PinholeIntrinsics k;
        const auto field = [&](const char* name) {
          return in.required(intrinsics, "sensor.intrinsics", name);
        };
        k.fx = in.number(field("fx"), "sensor.intrinsics.fx");
        k.fy = in.number(field("fy"), "sensor.intrinsics.fy");
        k.cx = in.number(field("cx"), "sensor.intrinsics.cx");
        k.cy = in.number(field("cy"), "sensor.intrinsics.cy");
        k.width = in.positive_integer(field("width"), "sensor.intrinsics.width");
        k.height = in.positive_integer(field("height"), "sensor.intrinsics.height");
        manifest.intrinsics = k;
        manifest.fov = fov_from_intrinsics(k, min_range, max_range);
      } else if (fov_deg) {
        in.check_map(fov_deg, "sensor.fov_deg", {"horizontal", "vertical"});
        manifest.fov.h_fov = deg2rad(in.number(in.required(fov_deg, "sensor.fov_deg", "horizontal"),
                                               "sensor.fov_deg.horizontal"));
        manifest.fov.v_fov = deg2rad(in.number(in.required(fov_deg, "sensor.fov_deg", "vertical"),
                                               "sensor.fov_deg.vertical"));
        manifest.fov.min_range = min_range;
        manifest.fov.max_range = max_range;
        manifest.fov.validate();
      } else {
        in.fail(sensor, "sensor", "give the field of view as intrinsics or fov_deg");
      }
    } catch (const std::invalid_argument& e) {
      in.fail(sensor, "sensor", e.what());
    }
  }

  // Region of interest and resolution.
  {
    const YAML::Node roi = in.required(root, "", "roi");
    in.check_map(roi, "roi", {"min", "max"});
    const Eigen::Vector3d lo = in.vector3(in.required(roi, "roi", "min"), "roi.min");
    const Eigen::Vector3d hi = in.vector3(in.required(roi, "roi", "max"), "roi.max");
    manifest.roi = Eigen::AlignedBox3d(lo, hi);
    const YAML::Node resolution = in.required(root, "", "resolution");
    const double res = in.number(resolution, "resolution");
    if (!(res > 0.0)) in.fail(resolution, "resolution", cat("must be positive, got ", res));
    try {
      manifest.grid = grid_for_roi(manifest.roi, res);
    } catch (const std::invalid_argument& e) {
      in.fail(roi, "", e.what());  // the message names roi or resolution
    }
  }

  // Options.
  if (const YAML::Node options = root["options"]) {
    in.check_map(options, "options",
                 {"table_segmentation", "icp", "integration", "skip_non_finite"});
    if (const YAML::Node n = options["skip_non_finite"]) {
      manifest.options.skip_non_finite = in.boolean(n, "options.skip_non_finite");
    }
    if (const YAML::Node n = options["table_segmentation"]) {
      manifest.options.table_segmentation = in.boolean(n, "options.table_segmentation");
    }
    if (const YAML::Node n = options["icp"]) manifest.options.icp = in.boolean(n, "options.icp");
    if (const YAML::Node n = options["integration"]) {
      try {
        manifest.options.integration = parse_integration_mode(in.text(n, "options.integration"));
      } catch (const std::invalid_argument& e) {
        in.fail(n, "options.integration", e.what());
      }
    }
  }

  // Clouds: listed, or every .pcd/.ply beside the manifest.
  // The YAML entry of each cloud, for poses and errors; a null node for clouds found in the folder.
  std::vector<YAML::Node> entries;
  const auto listed = [&](std::size_t i) -> const YAML::Node& { return entries[i]; };
  if (const YAML::Node clouds = root["clouds"]) {
    if (!clouds.IsSequence()) in.fail(clouds, "clouds", "must be a list");
    if (clouds.size() == 0) in.fail(clouds, "clouds", "is empty");
    for (std::size_t i = 0; i < clouds.size(); ++i) {
      const std::string key = cat("clouds[", i, "]");
      const YAML::Node entry = clouds[i];
      in.check_map(entry, key, {"file", "pose", "stamp"});
      const YAML::Node file = in.required(entry, key, "file");
      ManifestCloud cloud;
      cloud.file = (folder / in.text(file, key + ".file")).lexically_normal();
      if (!is_cloud_file(cloud.file)) {
        in.fail(file, key + ".file", cat("'", cloud.file.string(), "' is not a .pcd or .ply file"));
      }
      if (!fs::is_regular_file(cloud.file, error)) {
        in.fail(file, key + ".file", cat("no such file: ", cloud.file.string()));
      }
      if (const YAML::Node stamp = entry["stamp"]) cloud.stamp = in.number(stamp, key + ".stamp");
      manifest.clouds.push_back(cloud);
      entries.push_back(entry);
    }
  } else {
    for (const auto& item :
         fs::directory_iterator(folder.empty() ? fs::path(".") : folder, error)) {
      if (item.is_regular_file() && is_cloud_file(item.path())) {
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
      in.fail(root, "clouds",
              cat("missing, and the folder ", folder.string(), " holds no .pcd or .ply file"));
    }
    entries.assign(manifest.clouds.size(), YAML::Node());
  }

  // Poses: one matrix per cloud, or a trajectory.
  if (const YAML::Node trajectory = root["trajectory"]) {
    in.check_map(trajectory, "trajectory", {"file", "match", "max_time_difference"});
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (listed(i).IsMap() && listed(i)["pose"]) {
        in.fail(listed(i)["pose"], cat("clouds[", i, "].pose"),
                "give poses per cloud or a trajectory, not both");
      }
    }
    const YAML::Node file = in.required(trajectory, "trajectory", "file");
    manifest.trajectory = (folder / in.text(file, "trajectory.file")).lexically_normal();
    if (const YAML::Node match = trajectory["match"]) {
      const std::string name = in.text(match, "trajectory.match");
      if (name == "order") {
        manifest.match = PoseMatch::kOrder;
      } else if (name == "timestamp") {
        manifest.match = PoseMatch::kTimestamp;
      } else {
        in.fail(match, "trajectory.match",
                cat("unknown '", name, "' (expected order or timestamp)"));
      }
    }
    if (const YAML::Node dt = trajectory["max_time_difference"]) {
      manifest.max_time_difference = in.positive(dt, "trajectory.max_time_difference");
    }
    if (!fs::is_regular_file(*manifest.trajectory, error)) {
      in.fail(file, "trajectory.file", cat("no such file: ", manifest.trajectory->string()));
    }
    const std::vector<StampedPose> poses = read_tum_trajectory(*manifest.trajectory);
    const std::string traj = manifest.trajectory->filename().string();
    if (manifest.match == PoseMatch::kOrder) {
      if (poses.size() != manifest.clouds.size()) {
        in.fail(trajectory, "trajectory",
                cat(traj, " holds ", poses.size(), " poses but there are ", manifest.clouds.size(),
                    " clouds (match: order pairs them one to one)"));
      }
      for (std::size_t i = 0; i < poses.size(); ++i) {
        manifest.clouds[i].T_world_cloud = poses[i].T_world_frame;
      }
    } else {
      if (poses.empty()) in.fail(trajectory, "trajectory", cat(traj, " holds no poses"));
      for (std::size_t i = 1; i < poses.size(); ++i) {
        if (!(poses[i].stamp > poses[i - 1].stamp)) {
          in.fail(trajectory, "trajectory",
                  cat(traj, ": time stamps must increase for match: timestamp (pose ", i, " at ",
                      poses[i].stamp, " s follows ", poses[i - 1].stamp, " s)"));
        }
      }
      for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
        ManifestCloud& cloud = manifest.clouds[i];
        const std::string key = cat("clouds[", i, "]");
        if (!cloud.stamp) cloud.stamp = stamp_from_name(cloud.file);
        if (!cloud.stamp) {
          in.fail(listed(i).IsMap() ? listed(i) : root, key,
                  cat("no stamp to match the trajectory by: give ", key,
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
          in.fail(listed(i).IsMap() ? listed(i) : trajectory, key,
                  cat("no pose in ", traj, " within ", manifest.max_time_difference, " s of stamp ",
                      t, " (the nearest is ", dt, " s away)"));
        }
        cloud.T_world_cloud = best->T_world_frame;
      }
    }
  } else {
    for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
      const std::string key = cat("clouds[", i, "]");
      if (!listed(i).IsMap() || !listed(i)["pose"]) {
        in.fail(listed(i).IsMap() ? listed(i) : root, key + ".pose",
                cat("missing: cloud ", manifest.clouds[i].file.filename().string(),
                    " has no pose (give a pose per cloud, or a trajectory)"));
      }
      manifest.clouds[i].T_world_cloud = in.rigid(listed(i)["pose"], key + ".pose");
    }
  }

  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
  T_cloud_sensor.linear() = R_cloud_sensor(manifest.frame);
  for (ManifestCloud& cloud : manifest.clouds) {
    cloud.T_world_sensor = cloud.T_world_cloud * T_cloud_sensor;
  }
  return manifest;
}

void write_manifest(const fs::path& path, const Manifest& manifest) {
  const fs::path folder = fs::absolute(path).parent_path();
  YAML::Emitter out;
  out.SetDoublePrecision(std::numeric_limits<double>::max_digits10);
  out << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << 1;
  out << YAML::Key << "clouds" << YAML::Value << YAML::BeginSeq;
  for (const ManifestCloud& cloud : manifest.clouds) {
    out << YAML::BeginMap;
    fs::path file = fs::absolute(cloud.file).lexically_relative(folder);
    if (file.empty()) file = fs::absolute(cloud.file);
    out << YAML::Key << "file" << YAML::Value << file.generic_string();
    out << YAML::Key << "pose" << YAML::Value << YAML::BeginSeq;
    const Eigen::Matrix4d m = cloud.T_world_cloud.matrix();
    for (int r = 0; r < 4; ++r) {
      out << YAML::Flow << YAML::BeginSeq;
      for (int c = 0; c < 4; ++c) out << m(r, c);
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
    if (cloud.stamp) out << YAML::Key << "stamp" << YAML::Value << *cloud.stamp;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;

  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "frame" << YAML::Value << std::string(to_string(manifest.frame));
  if (manifest.intrinsics) {
    const PinholeIntrinsics& k = *manifest.intrinsics;
    out << YAML::Key << "intrinsics" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "fx" << YAML::Value << k.fx << YAML::Key << "fy" << YAML::Value << k.fy;
    out << YAML::Key << "cx" << YAML::Value << k.cx << YAML::Key << "cy" << YAML::Value << k.cy;
    out << YAML::Key << "width" << YAML::Value << k.width;
    out << YAML::Key << "height" << YAML::Value << k.height;
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "fov_deg" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "horizontal" << YAML::Value
        << manifest.fov.h_fov * 180.0 / std::numbers::pi;
    out << YAML::Key << "vertical" << YAML::Value << manifest.fov.v_fov * 180.0 / std::numbers::pi;
    out << YAML::EndMap;
  }
  out << YAML::Key << "min_range" << YAML::Value << manifest.fov.min_range;
  out << YAML::Key << "max_range" << YAML::Value << manifest.fov.max_range;
  out << YAML::EndMap;

  const auto vec = [&](const Eigen::Vector3d& v) {
    out << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
  };
  out << YAML::Key << "roi" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "min" << YAML::Value;
  vec(manifest.roi.min());
  out << YAML::Key << "max" << YAML::Value;
  vec(manifest.roi.max());
  out << YAML::EndMap;
  out << YAML::Key << "resolution" << YAML::Value << manifest.grid.resolution;

  out << YAML::Key << "options" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "table_segmentation" << YAML::Value << manifest.options.table_segmentation;
  out << YAML::Key << "icp" << YAML::Value << manifest.options.icp;
  out << YAML::Key << "integration" << YAML::Value
      << std::string(to_string(manifest.options.integration));
  out << YAML::Key << "skip_non_finite" << YAML::Value << manifest.options.skip_non_finite;
  out << YAML::EndMap;
  out << YAML::EndMap;
  if (!out.good()) throw std::runtime_error(cat(path.string(), ": ", out.GetLastError()));
  write_atomically(path, cat(out.c_str(), "\n"));
}

}  // namespace vantage
