#include "vantage/sim/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "vantage/sim/builtin_scenes.hpp"
#include "vantage/sim/mesh_io.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

/// A YAML node with the key path and file it came from, so that every error names them.
class Field {
 public:
  Field(YAML::Node node, std::string path, const std::string& source)
      : node_(std::move(node)), path_(std::move(path)), source_(&source) {}

  const std::string& path() const { return path_; }

  [[noreturn]] void fail(std::string_view message) const {
    const YAML::Mark mark = node_.Mark();
    const std::string where = mark.line >= 0 ? cat(*source_, ":", mark.line + 1) : cat(*source_);
    throw std::invalid_argument(cat(where, ": ", path_.empty() ? "scene" : path_, ": ", message));
  }

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }

  void require_map() const {
    if (!node_.IsMap()) fail("must be a map of keys");
  }

  /// Fails on a key that is not one of `allowed` (a typo), naming it and the allowed ones.
  void allow_keys(std::initializer_list<std::string_view> allowed) const {
    require_map();
    for (const auto& item : node_) {
      const std::string key = item.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (const std::string_view a : allowed) list += cat(list.empty() ? "" : ", ", a);
        Field(item.first, child_path(key), *source_)
            .fail(cat("unknown key '", key, "' (expected one of: ", list, ")"));
      }
    }
  }

  bool has(std::string_view key) const { return node_.IsMap() && node_[std::string(key)]; }

  std::optional<Field> get(std::string_view key) const {
    require_map();
    YAML::Node child = node_[std::string(key)];
    if (!child || child.IsNull()) return std::nullopt;
    return Field(child, child_path(key), *source_);
  }

  Field at(std::string_view key) const {
    if (auto child = get(key)) return *child;
    fail(cat("missing key '", key, "'"));
  }

  std::size_t size() const { return node_.size(); }
  Field operator[](std::size_t i) const {
    return Field(node_[i], cat(path_, "[", i, "]"), *source_);
  }

  std::vector<Field> items() const {
    if (!node_.IsSequence()) fail("must be a list");
    std::vector<Field> out;
    for (std::size_t i = 0; i < node_.size(); ++i) out.push_back((*this)[i]);
    return out;
  }

  std::string text() const {
    if (!node_.IsScalar()) fail("must be a single value");
    return node_.Scalar();
  }

  double number() const {
    if (!node_.IsScalar()) fail("must be a number");
    const std::string& s = node_.Scalar();
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != s.size() || !std::isfinite(value)) {
      fail(cat("must be a finite number, got '", s, "'"));
    }
    return value;
  }
  double positive() const {
    const double v = number();
    if (!(v > 0.0)) fail(cat("must be positive, got ", v));
    return v;
  }
  double non_negative() const {
    const double v = number();
    if (!(v >= 0.0)) fail(cat("must be >= 0, got ", v));
    return v;
  }
  int integer(int min, int max) const {
    const double v = number();
    if (v != std::floor(v) || v < min || v > max) {
      fail(cat("must be a whole number in [", min, ", ", max, "], got ", v));
    }
    return static_cast<int>(v);
  }
  std::vector<double> numbers(std::size_t min_count, std::size_t max_count) const {
    if (!node_.IsSequence() || node_.size() < min_count || node_.size() > max_count) {
      fail(min_count == max_count
               ? cat("must be a list of ", min_count, " numbers")
               : cat("must be a list of ", min_count, " to ", max_count, " numbers"));
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < node_.size(); ++i) out.push_back((*this)[i].number());
    return out;
  }
  Eigen::Vector2d vec2() const {
    const auto v = numbers(2, 2);
    return {v[0], v[1]};
  }
  Eigen::Vector3d vec3() const {
    const auto v = numbers(3, 3);
    return {v[0], v[1], v[2]};
  }
  Eigen::Vector3d positive_vec3() const {
    const Eigen::Vector3d v = vec3();
    for (int i = 0; i < 3; ++i) {
      if (!(v[i] > 0.0))
        (*this)[static_cast<std::size_t>(i)].fail(cat("must be positive, got ", v[i]));
    }
    return v;
  }
  Eigen::Vector2d positive_vec2() const {
    const Eigen::Vector2d v = vec2();
    for (int i = 0; i < 2; ++i) {
      if (!(v[i] > 0.0))
        (*this)[static_cast<std::size_t>(i)].fail(cat("must be positive, got ", v[i]));
    }
    return v;
  }

 private:
  std::string child_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : cat(path_, ".", key);
  }

  YAML::Node node_;
  std::string path_;
  const std::string* source_;
};

double number_or(const Field& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->number() : fallback;
}
double positive_or(const Field& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->positive() : fallback;
}
double non_negative_or(const Field& map, std::string_view key, double fallback) {
  const auto f = map.get(key);
  return f ? f->non_negative() : fallback;
}

/// [x, y, z] or [x, y, z, roll, pitch, yaw] with angles in degrees.
Eigen::Isometry3d parse_pose(const Field& f) {
  const std::vector<double> v = f.numbers(3, 6);
  if (v.size() != 3 && v.size() != 6) {
    f.fail("must be [x, y, z] or [x, y, z, roll_deg, pitch_deg, yaw_deg]");
  }
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (v.size() == 6) rpy = {deg2rad(v[3]), deg2rad(v[4]), deg2rad(v[5])};
  return pose_from_xyz_rpy({v[0], v[1], v[2]}, rpy);
}

constexpr int kCylinderSegments = 48;

Shape mesh_shape(std::string name, std::string kind, TriangleMesh mesh) {
  Shape s;
  s.name = std::move(name);
  s.kind = std::move(kind);
  s.mesh_world = std::move(mesh);
  return s;
}

/// Pieces of a box, placed in a furniture item's local frame (origin on the floor, at the centre
/// of its footprint).
void add_box(TriangleMesh& into, const Eigen::Vector3d& size, const Eigen::Vector3d& base) {
  append(into, transformed(make_box(size), Eigen::Isometry3d(Eigen::Translation3d(base))));
}

/// A desk or table: a top and four legs.
TriangleMesh make_desk(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double top = std::min(0.03, size.z() / 4),
               leg = std::min({0.05, size.x() / 4, size.y() / 4});
  add_box(m, {size.x(), size.y(), top}, {0, 0, size.z() - top});
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(m, {leg, leg, size.z() - top},
              {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
    }
  }
  return m;
}

/// A chair: four legs, a seat at half its height, and a back on its +y side.
TriangleMesh make_chair(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double seat_z = size.z() / 2, seat = 0.04,
               leg = std::min({0.04, size.x() / 4, size.y() / 4});
  add_box(m, {size.x(), size.y(), seat}, {0, 0, seat_z - seat});
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(m, {leg, leg, seat_z - seat},
              {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
    }
  }
  add_box(m, {size.x(), leg, size.z() - seat_z}, {0, (size.y() - leg) / 2, seat_z});
  return m;
}

/// A bookshelf open to -y: sides, back, bottom, top and a board every ~0.35 m.
TriangleMesh make_shelf(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double t = std::min({0.02, size.x() / 6, size.y() / 6, size.z() / 6});
  add_box(m, {t, size.y(), size.z()}, {-(size.x() - t) / 2, 0, 0});
  add_box(m, {t, size.y(), size.z()}, {(size.x() - t) / 2, 0, 0});
  add_box(m, {size.x() - 2 * t, t, size.z()}, {0, (size.y() - t) / 2, 0});
  const int boards = std::max(2, static_cast<int>(std::lround(size.z() / 0.35)) + 1);
  for (int k = 0; k < boards; ++k) {
    const double z = (size.z() - t) * k / (boards - 1);
    add_box(m, {size.x() - 2 * t, size.y() - t, t}, {0, -t / 2, z});
  }
  return m;
}

struct WallSegment {
  Eigen::Vector2d a, b;
  std::string name;
};

/// Cuts door gaps out of wall centre lines and turns the pieces into boxes.
void build_walls(const std::vector<WallSegment>& segments, double height, double thickness,
                 const std::vector<std::pair<Field, std::pair<Eigen::Vector2d, double>>>& doors,
                 std::vector<Shape>& shapes) {
  std::vector<int> door_used(doors.size(), 0);
  for (const WallSegment& wall : segments) {
    const Eigen::Vector2d axis = wall.b - wall.a;
    const double length = axis.norm();
    const Eigen::Vector2d dir = axis / length;
    // Pieces as [s0, s1] along the centre line; the outer ends reach half a thickness further so
    // that walls meeting at a corner close it.
    std::vector<std::pair<double, double>> pieces = {{-thickness / 2, length + thickness / 2}};
    for (std::size_t d = 0; d < doors.size(); ++d) {
      const auto& [at, width] = doors[d].second;
      const Eigen::Vector2d rel = at - wall.a;
      const double s = rel.dot(dir);
      const double off = std::abs(rel.x() * dir.y() - rel.y() * dir.x());
      if (off > thickness || s < 0.0 || s > length) continue;
      door_used[d] = 1;
      std::vector<std::pair<double, double>> cut;
      for (const auto& [s0, s1] : pieces) {
        if (s - width / 2 > s0) cut.emplace_back(s0, std::min(s1, s - width / 2));
        if (s + width / 2 < s1) cut.emplace_back(std::max(s0, s + width / 2), s1);
      }
      pieces = cut;
    }
    const double yaw = std::atan2(dir.y(), dir.x());
    for (const auto& [s0, s1] : pieces) {
      if (s1 - s0 < 1e-6) continue;
      const Eigen::Vector2d mid = wall.a + dir * (s0 + s1) / 2;
      const Eigen::Isometry3d T = pose_from_xyz_rpy({mid.x(), mid.y(), 0.0}, {0, 0, yaw});
      shapes.push_back(
          mesh_shape(wall.name, "wall", transformed(make_box({s1 - s0, thickness, height}), T)));
    }
  }
  for (std::size_t d = 0; d < doors.size(); ++d) {
    if (door_used[d] == 0)
      doors[d].first.fail("cuts no wall (it must lie on a wall's centre line)");
  }
}

struct Parser {
  const std::string& source;
  std::filesystem::path base_dir;
  Scene scene;

  void parse(const Field& root) {
    root.allow_keys({"name", "kind", "description", "units", "grid", "floor", "table", "walls",
                     "rooms", "doors", "objects", "sensor", "mount", "candidates", "start_poses",
                     "pose_noise", "robot"});
    scene.name = root.at("name").text();
    const Field kind = root.at("kind");
    if (kind.text() == "tabletop") {
      scene.kind = SceneKind::kTableTop;
    } else if (kind.text() == "office") {
      scene.kind = SceneKind::kOffice;
    } else {
      kind.fail(cat("must be tabletop or office, got '", kind.text(), "'"));
    }
    if (auto units = root.get("units")) parse_units(*units);
    parse_grid(root.at("grid"));
    if (auto f = root.get("floor")) parse_floor(*f);
    if (auto f = root.get("table")) parse_table(*f);
    parse_walls(root);
    if (auto f = root.get("objects")) {
      const auto items = f->items();
      for (std::size_t i = 0; i < items.size(); ++i) parse_object(items[i], i);
    }
    parse_sensor(root.at("sensor"));
    parse_mount(root.at("mount"));
    if (auto f = root.get("robot")) parse_robot(*f);
    parse_candidates(root.at("candidates"));
    parse_starts(root.at("start_poses"));
    if (auto f = root.get("pose_noise")) parse_pose_noise(*f);
  }

  void parse_units(const Field& f) {
    f.allow_keys({"length", "angle"});
    if (auto l = f.get("length"); l && l->text() != "m") l->fail("only metres ('m') are supported");
    if (auto a = f.get("angle"); a && a->text() != "deg") {
      a->fail("only degrees ('deg') are supported in scene files");
    }
  }

  void parse_grid(const Field& f) {
    f.allow_keys({"origin", "resolution", "dims"});
    scene.grid.origin = f.at("origin").vec3();
    scene.grid.resolution = f.at("resolution").positive();
    const Field dims = f.at("dims");
    dims.numbers(3, 3);
    for (std::size_t i = 0; i < 3; ++i) {
      scene.grid.dims[static_cast<int>(i)] = dims[i].integer(1, 1 << 20);
    }
    try {
      scene.grid.validate();
    } catch (const std::invalid_argument& e) {
      f.fail(e.what());
    }
  }

  void parse_floor(const Field& f) {
    f.allow_keys({"size", "center", "thickness"});
    const Eigen::Vector2d size = f.at("size").positive_vec2();
    const Eigen::Vector2d center =
        f.has("center") ? f.at("center").vec2() : Eigen::Vector2d::Zero();
    const double thickness = positive_or(f, "thickness", 0.05);
    const Eigen::Isometry3d T(Eigen::Translation3d(center.x(), center.y(), -thickness));
    scene.shapes.push_back(
        mesh_shape("floor", "floor", transformed(make_box({size.x(), size.y(), thickness}), T)));
    scene.floor_area = Eigen::AlignedBox2d(center - size / 2, center + size / 2);
  }

  void parse_table(const Field& f) {
    f.allow_keys({"size", "height", "center", "top_thickness", "leg_width"});
    const Eigen::Vector2d size = f.at("size").positive_vec2();
    const double height = f.at("height").positive();
    const Eigen::Vector2d center =
        f.has("center") ? f.at("center").vec2() : Eigen::Vector2d::Zero();
    const double top = positive_or(f, "top_thickness", 0.03);
    const double leg = positive_or(f, "leg_width", 0.05);
    if (top >= height) f.at("top_thickness").fail("must be less than the table's height");
    if (2 * leg >= size.minCoeff()) f.at("leg_width").fail("must be less than half the table");
    TriangleMesh m;
    add_box(m, {size.x(), size.y(), top}, {0, 0, height - top});
    for (const double sx : {-1.0, 1.0}) {
      for (const double sy : {-1.0, 1.0}) {
        add_box(m, {leg, leg, height - top},
                {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
      }
    }
    const Eigen::Isometry3d T(Eigen::Translation3d(center.x(), center.y(), 0.0));
    scene.shapes.push_back(mesh_shape("table", "table", transformed(m, T)));
  }

  void parse_walls(const Field& root) {
    std::vector<WallSegment> segments;
    double height = 0.0, thickness = 0.0;
    const auto walls = root.get("walls");
    const auto rooms = root.get("rooms");
    const auto doors_field = root.get("doors");
    if (!walls && !rooms) {
      if (doors_field) doors_field->fail("doors need walls or rooms");
      return;
    }
    if (!walls) root.fail("rooms need a 'walls' map with height and thickness");
    walls->allow_keys({"height", "thickness", "segments"});
    height = walls->at("height").positive();
    thickness = walls->at("thickness").positive();
    if (auto segs = walls->get("segments")) {
      const auto items = segs->items();
      for (std::size_t i = 0; i < items.size(); ++i) {
        const std::vector<double> v = items[i].numbers(4, 4);
        WallSegment w{{v[0], v[1]}, {v[2], v[3]}, cat("walls.segments[", i, "]")};
        if ((w.b - w.a).norm() < 1e-6) items[i].fail("has zero length");
        segments.push_back(w);
      }
    }
    if (rooms) {
      const auto items = rooms->items();
      for (std::size_t i = 0; i < items.size(); ++i) {
        const Field& r = items[i];
        r.allow_keys({"name", "min", "max"});
        Room room;
        room.name = r.has("name") ? r.at("name").text() : cat("room ", i);
        const Eigen::Vector2d lo = r.at("min").vec2(), hi = r.at("max").vec2();
        if (!(hi.x() > lo.x() && hi.y() > lo.y())) r.at("max").fail("must exceed min in x and y");
        room.area = Eigen::AlignedBox2d(lo, hi);
        const std::string name = cat("rooms[", i, "] (", room.name, ")");
        const Eigen::Vector2d c1(hi.x(), lo.y()), c3(lo.x(), hi.y());
        segments.push_back({lo, c1, name});
        segments.push_back({c1, hi, name});
        segments.push_back({hi, c3, name});
        segments.push_back({c3, lo, name});
        scene.rooms.push_back(room);
      }
    }
    std::vector<std::pair<Field, std::pair<Eigen::Vector2d, double>>> doors;
    if (doors_field) {
      for (const Field& d : doors_field->items()) {
        d.allow_keys({"at", "width"});
        doors.push_back({d, {d.at("at").vec2(), d.at("width").positive()}});
      }
    }
    build_walls(segments, height, thickness, doors, scene.shapes);
  }

  void parse_object(const Field& f, std::size_t index) {
    f.require_map();
    const Field type_field = f.at("type");
    const std::string type = type_field.text();
    const std::string label = cat("objects[", index, "]");
    std::vector<Shape> made;
    if (type == "box" || type == "cabinet") {
      f.allow_keys({"type", "size", "pose", "repeat"});
      made.push_back(mesh_shape(label, type, make_box(f.at("size").positive_vec3())));
    } else if (type == "desk" || type == "table") {
      f.allow_keys({"type", "size", "pose", "repeat"});
      made.push_back(mesh_shape(label, type, make_desk(f.at("size").positive_vec3())));
    } else if (type == "chair") {
      f.allow_keys({"type", "size", "pose", "repeat"});
      made.push_back(mesh_shape(label, type, make_chair(f.at("size").positive_vec3())));
    } else if (type == "shelf") {
      f.allow_keys({"type", "size", "pose", "repeat"});
      made.push_back(mesh_shape(label, type, make_shelf(f.at("size").positive_vec3())));
    } else if (type == "cylinder") {
      f.allow_keys({"type", "radius", "height", "segments", "pose", "repeat"});
      const int segments =
          f.has("segments") ? f.at("segments").integer(3, 4096) : kCylinderSegments;
      made.push_back(mesh_shape(
          label, type,
          make_cylinder(f.at("radius").positive(), f.at("height").positive(), segments)));
    } else if (type == "sphere") {
      f.allow_keys({"type", "radius", "pose", "repeat"});
      Shape s;
      s.name = label;
      s.kind = type;
      s.sphere = Sphere{Eigen::Vector3d::Zero(), f.at("radius").positive()};
      made.push_back(s);
    } else if (type == "mesh") {
      f.allow_keys({"type", "model", "file", "scale", "pose", "repeat"});
      made.push_back(parse_mesh(f, label));
    } else {
      type_field.fail(cat("unknown object type '", type,
                          "' (expected box, cylinder, sphere, mesh, desk, table, chair, shelf or "
                          "cabinet)"));
    }
    const Eigen::Isometry3d pose = parse_pose(f.at("pose"));
    std::vector<Eigen::Vector2d> offsets = {Eigen::Vector2d::Zero()};
    if (auto r = f.get("repeat")) {
      r->allow_keys({"count", "step"});
      const Field count = r->at("count");
      count.numbers(2, 2);
      const int nx = count[0].integer(1, 1000), ny = count[1].integer(1, 1000);
      const Eigen::Vector2d step = r->at("step").vec2();
      offsets.clear();
      for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) offsets.emplace_back(step.x() * i, step.y() * j);
      }
    }
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const Eigen::Isometry3d T = Eigen::Translation3d(offsets[k].x(), offsets[k].y(), 0.0) * pose;
      Shape s = made.front();
      if (offsets.size() > 1) s.name = cat(label, "#", k);
      if (s.sphere) {
        s.sphere->center = T.translation();
      } else {
        s.mesh_world = transformed(s.mesh_world, T);
      }
      scene.shapes.push_back(std::move(s));
    }
  }

  Shape parse_mesh(const Field& f, const std::string& label) {
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

  void parse_sensor(const Field& f) {
    if (f.is_scalar()) {
      try {
        scene.sensor = builtin_sensor(f.text());
      } catch (const std::invalid_argument& e) {
        f.fail(e.what());
      }
      return;
    }
    f.allow_keys({"preset", "name", "type", "h_fov_deg", "v_fov_deg", "min_range", "max_range",
                  "width", "height", "angular_resolution_deg", "tilt_resolution_deg", "noise",
                  "sweep_steps"});
    SensorConfig& s = scene.sensor;
    if (auto p = f.get("preset")) {
      try {
        s = builtin_sensor(p->text());
      } catch (const std::invalid_argument& e) {
        p->fail(e.what());
      }
    } else {
      const Field type = f.at("type");
      try {
        s.type = parse_sensor_type(type.text());
      } catch (const std::invalid_argument& e) {
        type.fail(e.what());
      }
      s.name = to_string(s.type);
    }
    if (auto v = f.get("name")) s.name = v->text();
    if (auto v = f.get("type")) {
      try {
        s.type = parse_sensor_type(v->text());
      } catch (const std::invalid_argument& e) {
        v->fail(e.what());
      }
    }
    if (auto v = f.get("h_fov_deg")) s.fov.h_fov = deg2rad(v->positive());
    if (auto v = f.get("v_fov_deg")) s.fov.v_fov = deg2rad(v->positive());
    if (auto v = f.get("min_range")) s.fov.min_range = v->non_negative();
    if (auto v = f.get("max_range")) s.fov.max_range = v->positive();
    if (auto v = f.get("width")) s.width = v->integer(1, 16384);
    if (auto v = f.get("height")) s.height = v->integer(1, 16384);
    if (auto v = f.get("angular_resolution_deg")) s.angular_resolution = deg2rad(v->positive());
    if (auto v = f.get("tilt_resolution_deg")) s.tilt_resolution = deg2rad(v->positive());
    if (auto v = f.get("sweep_steps")) s.sweep_steps = v->integer(1, 3600);
    if (auto n = f.get("noise")) {
      n->allow_keys({"sigma", "sigma_quadratic", "reference_range"});
      s.noise.sigma = non_negative_or(*n, "sigma", 0.0);
      s.noise.sigma_quadratic = non_negative_or(*n, "sigma_quadratic", 0.0);
      s.noise.reference_range = non_negative_or(*n, "reference_range", 0.0);
    }
    try {
      s.validate();
    } catch (const std::invalid_argument& e) {
      f.fail(e.what());
    }
  }

  void parse_mount(const Field& f) {
    f.allow_keys({"height", "target", "pitch_deg"});
    scene.mount.height = f.at("height").positive();
    const auto target = f.get("target");
    const auto pitch = f.get("pitch_deg");
    if (target.has_value() == pitch.has_value())
      f.fail("needs exactly one of 'target' or 'pitch_deg'");
    if (target) {
      scene.mount.aims_at_target = true;
      scene.mount.target = target->vec3();
    } else {
      const double p = pitch->number();
      if (!(p > -90.0 && p < 90.0)) pitch->fail(cat("must lie in (-90, 90) degrees, got ", p));
      scene.mount.pitch = deg2rad(p);
    }
  }

  void parse_robot(const Field& f) {
    f.allow_keys({"footprint", "height", "stop_spacing"});
    scene.robot.footprint = positive_or(f, "footprint", scene.robot.footprint);
    scene.robot.height = positive_or(f, "height", scene.robot.height);
    scene.robot.stop_spacing = positive_or(f, "stop_spacing", scene.robot.stop_spacing);
    if (scene.robot.stop_spacing > scene.robot.footprint) {
      f.at("stop_spacing").fail("must not exceed the footprint (stops could straddle a wall)");
    }
  }

  void parse_candidates(const Field& f) {
    f.require_map();
    const Field generator = f.at("generator");
    const std::string g = generator.text();
    if (scene.kind == SceneKind::kTableTop) {
      if (g != "ring")
        generator.fail(cat("a tabletop scene's generator must be ring, got '", g, "'"));
      if (!scene.mount.aims_at_target) {
        f.fail("the ring needs a mount with a 'target' (the point every view looks at)");
      }
      f.allow_keys({"generator", "radius", "positions", "start_angle_deg", "yaw_offsets_deg"});
      RingConfig& ring = scene.ring;
      ring.center = scene.mount.target;
      ring.height = scene.mount.height;
      ring.radius = f.at("radius").positive();
      ring.positions = f.at("positions").integer(1, 10000);
      ring.start_angle = deg2rad(number_or(f, "start_angle_deg", 0.0));
      if (auto y = f.get("yaw_offsets_deg")) {
        ring.yaw_offsets.clear();
        for (const double d : y->numbers(1, 1000)) ring.yaw_offsets.push_back(deg2rad(d));
      }
      try {
        ring.validate();
      } catch (const std::invalid_argument& e) {
        f.fail(e.what());
      }
    } else {
      if (g != "frontier") {
        generator.fail(cat("an office scene's generator must be frontier, got '", g, "'"));
      }
      f.allow_keys({"generator"});
    }
  }

  void parse_starts(const Field& f) {
    if (f.is_scalar()) {
      if (f.text() != "ring") f.fail("must be 'ring' or a list of [x, y] or [x, y, yaw_deg] stops");
      if (scene.kind != SceneKind::kTableTop) f.fail("'ring' starts need a tabletop scene");
      const RingConfig& ring = scene.ring;
      for (int k = 0; k < ring.positions; ++k) {
        const double bearing = ring.start_angle + 2.0 * std::numbers::pi * k / ring.positions;
        scene.start_poses.push_back(
            scene.mount.sensor_pose(ring.center.x() + ring.radius * std::cos(bearing),
                                    ring.center.y() + ring.radius * std::sin(bearing)));
      }
      return;
    }
    const auto items = f.items();
    if (items.empty()) f.fail("needs at least one start");
    for (const Field& item : items) {
      const std::vector<double> v = item.numbers(2, 3);
      if (scene.mount.aims_at_target && v.size() != 2) {
        item.fail("must be [x, y]: the mount aims at its target, so there is no yaw");
      }
      if (!scene.mount.aims_at_target && v.size() != 3) item.fail("must be [x, y, yaw_deg]");
      const Eigen::Vector2d xy(v[0], v[1]);
      if (!scene.floor_area.isEmpty() && !scene.floor_area.contains(xy)) {
        item.fail("lies outside the floor");
      }
      scene.start_poses.push_back(
          scene.mount.sensor_pose(v[0], v[1], v.size() == 3 ? deg2rad(v[2]) : 0.0));
    }
  }

  void parse_pose_noise(const Field& f) {
    f.allow_keys({"x", "y", "yaw_deg"});
    scene.pose_noise.x = non_negative_or(f, "x", 0.0);
    scene.pose_noise.y = non_negative_or(f, "y", 0.0);
    scene.pose_noise.yaw = deg2rad(non_negative_or(f, "yaw_deg", 0.0));
  }
};

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(cat("scene file ", path.string(), " cannot be opened"));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string_view to_string(SceneKind kind) {
  return kind == SceneKind::kTableTop ? "tabletop" : "office";
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

Scene parse_scene(const std::string& yaml_text, const std::string& source,
                  const std::filesystem::path& base_dir) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(cat(source, ":", e.mark.line + 1, ": not valid YAML: ", e.msg));
  }
  if (!root.IsMap())
    throw std::invalid_argument(cat(source, ": a scene file must be a map of keys"));
  Parser parser{source, base_dir, {}};
  parser.scene.source = source;
  parser.parse(Field(root, "", source));
  Scene& scene = parser.scene;
  if (scene.floor_area.isEmpty()) {
    scene.floor_area =
        Eigen::AlignedBox2d(scene.grid.origin.head<2>(), scene.grid.max_corner().head<2>());
  }
  return std::move(parser.scene);
}

Scene load_scene(const std::string& name_or_yaml_path) {
  for (const BuiltinSceneFile& file : builtin_scene_files()) {
    if (file.name == name_or_yaml_path) {
      Scene scene = parse_scene(std::string(file.text), cat("scene ", file.name), ".");
      scene.source = "built-in";
      return scene;
    }
  }
  const std::filesystem::path path(name_or_yaml_path);
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    std::string known;
    for (const std::string& n : builtin_scene_names()) known += cat(known.empty() ? "" : ", ", n);
    throw std::runtime_error(cat("scene '", name_or_yaml_path, "' is neither a built-in scene (",
                                 known, ") nor a file"));
  }
  return parse_scene(read_file(path), path.string(), path.parent_path());
}

}  // namespace vantage::sim
