// The scene file: YAML (docs/scenes.md), read by io's one strict YAML reader into a Scene.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "vantage/io/yaml_reader.hpp"
#include "vantage/sim/detail/scene_shapes.hpp"
#include "vantage/sim/detail/scene_values.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

using namespace detail;  // the scene file's value readers (detail/scene_values.hpp)

struct Parser {
  const std::string& source;
  std::filesystem::path base_dir;
  Scene scene;

  void parse(const YamlField& root) {
    if (const auto kind = root.get("kind"); kind && kind->text() == "object") {
      scene = parse_object_file(root, base_dir);
      scene.source = source;
      return;
    }
    root.allow_keys({"name", "kind", "description", "units", "grid", "floor", "table", "walls",
                     "rooms", "doors", "objects", "sensor", "mount", "candidates", "start_poses",
                     "pose_noise", "robot", "arm"});
    scene.name = root.at("name").text();
    const YamlField kind = root.at("kind");
    if (kind.text() == "tabletop") {
      scene.kind = SceneKind::kTableTop;
    } else if (kind.text() == "office") {
      scene.kind = SceneKind::kOffice;
    } else {
      kind.fail(cat("must be tabletop, office or object, got '", kind.text(), "'"));
    }
    if (auto units = root.get("units")) check_units(*units);
    parse_grid(root.at("grid"));
    if (auto f = root.get("floor")) read_floor(*f, scene);
    if (auto f = root.get("table")) read_table(*f, scene);
    read_walls(root, scene);
    if (auto f = root.get("objects")) {
      const auto items = f->items();
      if (items.size() > kMaxSceneObjects) {
        f->fail(cat("holds ", items.size(), " objects, more than the ", kMaxSceneObjects,
                    " a scene may place"));
      }
      for (std::size_t i = 0; i < items.size(); ++i) read_object(items[i], i, base_dir, scene);
    }
    parse_sensor(root.at("sensor"));
    parse_mount(root.at("mount"));
    if (auto f = root.get("robot")) parse_robot(*f);
    check_floor_stops(root);
    parse_candidates(root.at("candidates"));
    parse_starts(root.at("start_poses"));
    if (auto f = root.get("pose_noise")) parse_pose_noise(*f);
    if (auto f = root.get("arm")) parse_arm(*f);
  }

  /// A table top's arm: where its base stands and how far it reaches (the hemisphere's rule).
  void parse_arm(const YamlField& f) {
    if (scene.kind != SceneKind::kTableTop) f.fail("an arm needs a tabletop scene");
    f.allow_keys({"base", "reach"});
    ArmReach arm;
    const YamlField base = f.at("base");
    arm.base = base.vec3();
    require_in_world(base, std::span<const double>(arm.base.data(), 3));
    arm.reach = length(f.at("reach"));
    scene.arm = arm;
  }

  void parse_grid(const YamlField& f) {
    f.allow_keys({"origin", "resolution", "dims"});
    scene.grid.origin = f.at("origin").vec3();
    scene.grid.resolution = f.at("resolution").positive();
    const YamlField dims = f.at("dims");
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

  void parse_sensor(const YamlField& f) {
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
      const YamlField type = f.at("type");
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

  void parse_mount(const YamlField& f) {
    f.allow_keys({"height", "target", "pitch_deg"});
    scene.mount.height = length(f.at("height"));
    const auto target = f.get("target");
    const auto pitch = f.get("pitch_deg");
    if (target.has_value() == pitch.has_value())
      f.fail("needs exactly one of 'target' or 'pitch_deg'");
    if (target) {
      scene.mount.aims_at_target = true;
      scene.mount.target = target->vec3();
      require_in_world(*target, std::span<const double>(scene.mount.target.data(), 3));
    } else {
      const double p = pitch->number();
      if (!(p > -90.0 && p < 90.0)) pitch->fail(cat("must lie in (-90, 90) degrees, got ", p));
      scene.mount.pitch = deg2rad(p);
    }
  }

  void parse_robot(const YamlField& f) {
    f.allow_keys({"footprint", "height", "stop_spacing"});
    scene.robot.footprint = positive_or(f, "footprint", scene.robot.footprint);
    scene.robot.height = positive_or(f, "height", scene.robot.height);
    scene.robot.stop_spacing = positive_or(f, "stop_spacing", scene.robot.stop_spacing);
    if (scene.robot.stop_spacing > scene.robot.footprint) {
      f.at("stop_spacing").fail("must not exceed the footprint (stops could straddle a wall)");
    }
    // NOTE: the ground truth sweeps from every reachable stop: a spacing finer than a cell sees
    // nothing more, and the stops' count is bounded before a sweep (issue 39: 1e-6 m passed here
    // and failed later as "out of memory").
    if (const auto spacing = f.get("stop_spacing")) {
      if (scene.robot.stop_spacing < scene.grid.resolution) {
        spacing->fail(cat("must be at least the grid's resolution (", scene.grid.resolution,
                          " m), got ", scene.robot.stop_spacing));
      }
    }
  }

  /// An office's floor stops, counted before any is made (kMaxFloorStops).
  void check_floor_stops(const YamlField& root) const {
    if (scene.kind != SceneKind::kOffice || scene.floor_area.isEmpty()) return;
    const Eigen::Vector2d sizes = scene.floor_area.sizes();
    // As the ground truth lays them out: at least one stop along each side.
    const double stops = std::max(1.0, std::floor(sizes.x() / scene.robot.stop_spacing)) *
                         std::max(1.0, std::floor(sizes.y() / scene.robot.stop_spacing));
    if (stops > static_cast<double>(kMaxFloorStops)) {
      const auto robot = root.get("robot");
      const std::string what =
          cat("the floor (", sizes.x(), " x ", sizes.y(), " m) at a spacing of ",
              scene.robot.stop_spacing, " m makes ", stops, " stops, more than the ",
              kMaxFloorStops, " the ground truth sweeps from: use a wider spacing");
      if (robot && robot->has("stop_spacing")) robot->at("stop_spacing").fail(what);
      root.fail_as("robot", what);
    }
  }

  void parse_candidates(const YamlField& f) {
    f.require_map();
    const YamlField generator = f.at("generator");
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
      ring.radius = length(f.at("radius"));
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

  void parse_starts(const YamlField& f) {
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
    for (const YamlField& item : items) {
      const std::vector<double> v = item.numbers(2, 3);
      if (scene.mount.aims_at_target && v.size() != 2) {
        item.fail("must be [x, y]: the mount aims at its target, so there is no yaw");
      }
      if (!scene.mount.aims_at_target && v.size() != 3) item.fail("must be [x, y, yaw_deg]");
      require_in_world(item, std::span(v).first(2));
      const Eigen::Vector2d xy(v[0], v[1]);
      if (!scene.floor_area.isEmpty() && !scene.floor_area.contains(xy)) {
        item.fail("lies outside the floor");
      }
      scene.start_poses.push_back(
          scene.mount.sensor_pose(v[0], v[1], v.size() == 3 ? deg2rad(v[2]) : 0.0));
    }
  }

  void parse_pose_noise(const YamlField& f) {
    f.allow_keys({"x", "y", "yaw_deg"});
    scene.pose_noise.x = non_negative_or(f, "x", 0.0);
    scene.pose_noise.y = non_negative_or(f, "y", 0.0);
    scene.pose_noise.yaw = deg2rad(non_negative_or(f, "yaw_deg", 0.0));
  }
};

}  // namespace

Scene parse_scene(const std::string& yaml_text, const std::string& source,
                  const std::filesystem::path& base_dir) {
  Parser parser{source, base_dir, {}};
  parser.scene.source = source;
  try {
    parser.parse(parse_yaml(yaml_text, source));
  } catch (const YamlError& e) {
    // NOTE: a bad scene stays a bad argument (std::invalid_argument, Python's ValueError), as
    // scene.hpp promises; the reader's YamlError is a std::runtime_error like other file errors.
    throw std::invalid_argument(e.what());
  }
  Scene& scene = parser.scene;
  if (scene.floor_area.isEmpty()) {
    scene.floor_area =
        Eigen::AlignedBox2d(scene.grid.origin.head<2>(), scene.grid.max_corner().head<2>());
  }
  return std::move(parser.scene);
}

}  // namespace vantage::sim
