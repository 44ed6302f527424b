#include "vantage/sim/detail/scene_values.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "vantage/sim/builtin_models.hpp"
#include "vantage/sim/furniture.hpp"
#include "vantage/sim/geometry.hpp"
#include "vantage/sim/mesh_io.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim::detail {

double number_or(const YamlField& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->number() : fallback;
}
double positive_or(const YamlField& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->positive() : fallback;
}
double non_negative_or(const YamlField& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->non_negative() : fallback;
}

/// Refuses coordinates beyond kMaxWorldCoordinate (docs/robustness.md): a scene that reaches
/// them would be refused by the simulated world mid-run.
void require_in_world(const YamlField& f, std::span<const double> v) {
  for (const double x : v) {
    if (!(std::abs(x) <= kMaxWorldCoordinate)) {
      f.fail(cat("coordinate ", x, " m lies beyond ", kMaxWorldCoordinate, " m of the origin"));
    }
  }
}

/// A length: a number in (0, kMaxWorldCoordinate] m.
double length(const YamlField& f) {
  const double value = f.positive();
  if (value > kMaxWorldCoordinate) {
    f.fail(cat("must be at most ", kMaxWorldCoordinate, " m, got ", value));
  }
  return value;
}

/// [x, y, z], each a length.
Eigen::Vector3d lengths(const YamlField& f) {
  const Eigen::Vector3d v = f.positive_vec3();
  for (int i = 0; i < 3; ++i) {
    if (v[i] > kMaxWorldCoordinate) {
      f[static_cast<std::size_t>(i)].fail(
          cat("must be at most ", kMaxWorldCoordinate, " m, got ", v[i]));
    }
  }
  return v;
}

Eigen::Isometry3d parse_pose(const YamlField& f) {
  const std::vector<double> v = f.numbers(3, 6);
  require_in_world(f, std::span(v).first(std::min<std::size_t>(v.size(), 3)));
  if (v.size() != 3 && v.size() != 6) {
    f.fail("must be [x, y, z] or [x, y, z, roll_deg, pitch_deg, yaw_deg]");
  }
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (v.size() == 6) {
    for (std::size_t i = 3; i < 6; ++i) {
      if (!(std::abs(v[i]) <= kMaxAngleDegrees)) {
        f.fail(cat(std::array{"roll", "pitch", "yaw"}[i - 3], " ", v[i], " deg lies outside [-",
                   kMaxAngleDegrees, ", ", kMaxAngleDegrees, "]"));
      }
    }
    rpy = {deg2rad(v[3]), deg2rad(v[4]), deg2rad(v[5])};
  }
  return pose_from_xyz_rpy({v[0], v[1], v[2]}, rpy);
}

Shape read_mesh_shape(const YamlField& f, const std::string& label,
                      const std::filesystem::path& base_dir) {
  const auto model = f.get("model");
  const auto file = f.get("file");
  if (model.has_value() == file.has_value())
    f.fail("a mesh needs exactly one of 'model' or 'file'");
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (auto s = f.get("scale")) {
    scale = s->is_sequence() ? s->positive_vec3() : Eigen::Vector3d::Constant(s->positive());
  } else if (model) {
    f.fail("missing key 'scale' (a built-in model's largest size, in metres)");
  }
  TriangleMesh mesh;
  std::string name;
  if (model) {
    name = model->text();
    try {
      mesh = load_builtin_model(name);
    } catch (const std::exception& e) {
      model->fail(e.what());
    }
  } else {
    std::filesystem::path path = file->text();
    if (path.is_relative()) path = base_dir / path;
    name = path.filename().string();
    try {
      mesh = load_mesh(path);
    } catch (const std::exception& e) {
      file->fail(e.what());
    }
  }
  Shape s = mesh_shape(cat(label, " (", name, ")"), "mesh",
                       transformed(mesh, Eigen::Isometry3d::Identity(), scale));
  return s;
}

void check_units(const YamlField& f) {
  f.allow_keys({"length", "angle"});
  if (auto l = f.get("length"); l && l->text() != "m") l->fail("only metres ('m') are supported");
  if (auto a = f.get("angle"); a && a->text() != "deg") {
    a->fail("only degrees ('deg') are supported in scene files");
  }
}

}  // namespace vantage::sim::detail
