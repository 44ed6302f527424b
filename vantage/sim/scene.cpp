#include "vantage/sim/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/sim/builtin_models.hpp"
#include "vantage/sim/builtin_scenes.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::string text;
  try {
    text = read_input_file(path, InputKind::kSettings);
  } catch (const FormatError& e) {
    throw std::runtime_error(cat("scene file ", path.string(), ": ", e.what()));
  }
  if (const std::string_view format = sniff_format(text); !format.empty() && format != "JSON") {
    throw std::runtime_error(
        cat(path.string(), ": is ", format, ", not a scene file (YAML, docs/scenes.md)"));
  }
  return text;
}

}  // namespace

std::string_view to_string(SceneKind kind) {
  switch (kind) {
    case SceneKind::kTableTop:
      return "tabletop";
    case SceneKind::kOffice:
      return "office";
    case SceneKind::kObject:
      return "object";
  }
  return "unknown";
}

Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = xyz;
  return T;
}

Eigen::Isometry3d SensorMount::sensor_pose(double x, double y, double yaw) const {
  const Eigen::Vector3d eye(x, y, height);
  if (aims_at_target) return look_at(eye, target);
  return pose_from_xyz_rpy(eye, {0.0, pitch, yaw});
}

void PoseNoise::validate() const {
  if (!(x >= 0.0 && std::isfinite(x)))
    throw std::invalid_argument(cat("pose_noise.x must be >= 0, got ", x));
  if (!(y >= 0.0 && std::isfinite(y)))
    throw std::invalid_argument(cat("pose_noise.y must be >= 0, got ", y));
  if (!(yaw >= 0.0 && std::isfinite(yaw))) {
    throw std::invalid_argument(cat("pose_noise.yaw must be >= 0, got ", yaw));
  }
}

std::vector<Eigen::Isometry3d> Scene::candidate_poses() const {
  if (kind == SceneKind::kObject && view_sphere) return sphere_poses(*view_sphere);
  if (kind != SceneKind::kTableTop) return {};
  return ring_poses(ring);
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const BuiltinSceneFile& file : builtin_scene_files()) names.emplace_back(file.name);
  return names;
}

std::string builtin_scene_text(std::string_view name) {
  for (const BuiltinSceneFile& file : builtin_scene_files()) {
    if (file.name == name) return std::string(file.text);
  }
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += cat(known.empty() ? "" : ", ", n);
  throw std::invalid_argument(cat("unknown built-in scene '", name, "' (built in: ", known, ")"));
}

Scene load_scene(const std::string& name_or_yaml_path) {
  return load_scene(name_or_yaml_path, ObjectProtocol{});
}

bool is_object_source(const std::string& name_or_path) {
  if (is_builtin_model(name_or_path)) return true;
  std::string ext = std::filesystem::path(name_or_path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl";
}

Scene load_scene(const std::string& name_or_yaml_path, const ObjectProtocol& objects) {
  if (is_object_source(name_or_yaml_path)) return single_object_scene(name_or_yaml_path, objects);
  for (const BuiltinSceneFile& file : builtin_scene_files()) {
    if (file.name == name_or_yaml_path) {
      Scene scene = parse_scene(std::string(file.text), cat("scene ", file.name), ".");
      scene.source = "built-in";
      return scene;
    }
  }
  const std::filesystem::path path(name_or_yaml_path);
  if (const std::string why = not_a_readable_file(path); !why.empty()) {
    if (why != "no such file") throw std::runtime_error(cat(path.string(), ": ", why));
    std::string known;
    for (const std::string& n : builtin_scene_names()) known += cat(known.empty() ? "" : ", ", n);
    throw std::runtime_error(cat("scene '", printable(name_or_yaml_path),
                                 "' is neither a built-in scene (", known, ") nor a file"));
  }
  return parse_scene(read_file(path), path.string(), path.parent_path());
}

}  // namespace vantage::sim
