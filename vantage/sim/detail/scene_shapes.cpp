// The scene file's shapes (scene_shapes.hpp): the floor, the table, walls and rooms with their
// doors, and the objects, each placed and repeated.

#include "vantage/sim/detail/scene_shapes.hpp"

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vantage/sim/detail/scene_values.hpp"
#include "vantage/sim/furniture.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim::detail {
namespace {

constexpr int kCylinderSegments = 48;

}  // namespace

void read_floor(const YamlField& f, Scene& scene) {
  f.allow_keys({"size", "center", "thickness"});
  const Eigen::Vector2d size = f.at("size").positive_vec2();
  const Eigen::Vector2d center = f.has("center") ? f.at("center").vec2() : Eigen::Vector2d::Zero();
  const double thickness = positive_or(f, "thickness", 0.05);
  const Eigen::Isometry3d T(Eigen::Translation3d(center.x(), center.y(), -thickness));
  scene.shapes.push_back(
      mesh_shape("floor", "floor", transformed(make_box({size.x(), size.y(), thickness}), T)));
  scene.floor_area = Eigen::AlignedBox2d(center - size / 2, center + size / 2);
}

void read_table(const YamlField& f, Scene& scene) {
  f.allow_keys({"size", "height", "center", "top_thickness", "leg_width"});
  const Eigen::Vector2d size = f.at("size").positive_vec2();
  const double height = length(f.at("height"));
  const Eigen::Vector2d center = f.has("center") ? f.at("center").vec2() : Eigen::Vector2d::Zero();
  const double top = positive_or(f, "top_thickness", 0.03);
  const double leg = positive_or(f, "leg_width", 0.05);
  if (top >= height) f.at("top_thickness").fail("must be less than the table's height");
  if (2 * leg >= size.minCoeff()) f.at("leg_width").fail("must be less than half the table");
  const Eigen::Isometry3d T(Eigen::Translation3d(center.x(), center.y(), 0.0));
  scene.shapes.push_back(
      mesh_shape("table", "table", transformed(make_table(size, height, top, leg), T)));
}

void read_walls(const YamlField& root, Scene& scene) {
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
  height = length(walls->at("height"));
  thickness = length(walls->at("thickness"));
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
      const YamlField& r = items[i];
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
  std::vector<YamlField> door_fields;
  std::vector<Door> doors;
  if (doors_field) {
    for (const YamlField& d : doors_field->items()) {
      d.allow_keys({"at", "width"});
      door_fields.push_back(d);
      doors.push_back({d.at("at").vec2(), length(d.at("width"))});
    }
  }
  const std::vector<bool> used = build_walls(segments, height, thickness, doors, scene.shapes);
  for (std::size_t d = 0; d < doors.size(); ++d) {
    if (!used[d]) door_fields[d].fail("cuts no wall (it must lie on a wall's centre line)");
  }
}

void read_object(const YamlField& f, std::size_t index, const std::filesystem::path& base_dir,
                 Scene& scene) {
  f.require_map();
  const YamlField type_field = f.at("type");
  const std::string type = type_field.text();
  const std::string label = cat("objects[", index, "]");
  std::vector<Shape> made;
  if (type == "box" || type == "cabinet") {
    f.allow_keys({"type", "size", "pose", "repeat"});
    made.push_back(mesh_shape(label, type, make_box(lengths(f.at("size")))));
  } else if (type == "desk" || type == "table") {
    f.allow_keys({"type", "size", "pose", "repeat"});
    made.push_back(mesh_shape(label, type, make_desk(lengths(f.at("size")))));
  } else if (type == "chair") {
    f.allow_keys({"type", "size", "pose", "repeat"});
    made.push_back(mesh_shape(label, type, make_chair(lengths(f.at("size")))));
  } else if (type == "shelf") {
    f.allow_keys({"type", "size", "pose", "repeat"});
    made.push_back(mesh_shape(label, type, make_shelf(lengths(f.at("size")))));
  } else if (type == "cylinder") {
    f.allow_keys({"type", "radius", "height", "segments", "pose", "repeat"});
    const int segments = f.has("segments") ? f.at("segments").integer(3, 4096) : kCylinderSegments;
    made.push_back(mesh_shape(
        label, type, make_cylinder(length(f.at("radius")), length(f.at("height")), segments)));
  } else if (type == "sphere") {
    f.allow_keys({"type", "radius", "pose", "repeat"});
    Shape s;
    s.name = label;
    s.kind = type;
    s.sphere = Sphere{Eigen::Vector3d::Zero(), length(f.at("radius"))};
    made.push_back(s);
  } else if (type == "mesh") {
    f.allow_keys({"type", "model", "file", "scale", "pose", "repeat"});
    made.push_back(read_mesh_shape(f, label, base_dir));
  } else {
    type_field.fail(cat("unknown object type '", type,
                        "' (expected box, cylinder, sphere, mesh, desk, table, chair, shelf or "
                        "cabinet)"));
  }
  const Eigen::Isometry3d pose = parse_pose(f.at("pose"));
  std::vector<Eigen::Vector2d> offsets = {Eigen::Vector2d::Zero()};
  if (auto r = f.get("repeat")) {
    r->allow_keys({"count", "step"});
    const YamlField count = r->at("count");
    count.numbers(2, 2);
    const int nx = count[0].integer(1, 1000), ny = count[1].integer(1, 1000);
    const Eigen::Vector2d step = r->at("step").vec2();
    offsets.clear();
    const std::size_t placed = scene.shapes.size() + static_cast<std::size_t>(nx) * ny;
    if (placed > kMaxSceneObjects) {
      count.fail(cat("places ", nx * ny, " copies, which makes more than the ", kMaxSceneObjects,
                     " objects a scene may place"));
    }
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

}  // namespace vantage::sim::detail
