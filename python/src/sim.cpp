// Bindings of the simulator: scenes (built in or from YAML), their sensors and Embree scans.

#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {

namespace {

sim::Scene load(const std::string& name_or_path) {
  // NOTE: a missing scene file is an OSError; a name that is neither built in nor a file stays
  // the ValueError the library raises.
  return with_file(name_or_path, false, [&] { return sim::load_scene(name_or_path); });
}

py::array_t<double> scan(const sim::World& world, const Eigen::Matrix4d& T_world_sensor,
                         std::uint64_t seed, const std::string& frame) {
  if (frame != "sensor" && frame != "world") {
    throw std::invalid_argument(cat("frame must be 'sensor' or 'world', got '", frame, "'"));
  }
  const Eigen::Isometry3d pose = to_pose(T_world_sensor, "T_world_sensor");
  PointCloud points;
  {
    py::gil_scoped_release release;
    sim::SimulatedScan s = world.scan(pose, seed);
    points = frame == "world" ? transform(s.T_world_sensor_true, s.points_sensor)
                              : std::move(s.points_sensor);
  }
  return from_cloud(points);
}

/// World: a scene ready to scan.
void def_world(py::module_& m) {
  py::class_<sim::World>(m, "World",
                         "A scene loaded into Embree, ready to scan with the scene's sensor.")
      .def(py::init([](const py::object& scene, const std::string& sensor, int num_threads) {
             sim::Scene s = py::isinstance<py::str>(scene) ? load(scene.cast<std::string>())
                                                           : scene.cast<sim::Scene>();
             if (!sensor.empty()) s.sensor = sim::builtin_sensor(sensor);
             sim::WorldConfig config{num_threads};
             config.validate();
             return std::make_unique<sim::World>(std::move(s), config);
           }),
           py::arg("scene"), py::arg("sensor") = "", py::arg("num_threads") = 0,
           "A Scene, or a scene's name or file; `sensor` replaces the scene's ('hokuyo' or "
           "'kinect'); num_threads 0 = all cores (scans do not depend on it).")
      .def_property_readonly("scene", &sim::World::scene, "The Scene.")
      .def("scan", &scan, py::arg("T_world_sensor"), py::arg("seed") = 1,
           py::arg("frame") = "sensor",
           "One scan from the 4 x 4 sensor pose: an N x 3 array of the points hit, in the sensor "
           "frame (x forward, y left, z up) or with frame='world' in the world [m]. Range noise "
           "(and the scene's pose noise, see noisy_pose) are drawn from `seed`.")
      .def(
          "noisy_pose",
          [](const sim::World& w, const Eigen::Matrix4d& T_world_sensor, std::uint64_t seed) {
            return Eigen::Matrix4d(
                w.noisy_pose(to_pose(T_world_sensor, "T_world_sensor"), seed).matrix());
          },
          py::arg("T_world_sensor"), py::arg("seed") = 1,
          "The pose a robot believes after the scene's pose noise for `seed` (the true pose "
          "when the scene has none).");
}

}  // namespace

void bind_sim(py::module_& m) {
  m.def("builtin_scene_names", &sim::builtin_scene_names, "Names of the built-in scenes.");
  m.def(
      "object_scene",
      [](const std::string& mesh, double object_radius, double view_radius, int views,
         double resolution, const std::string& sensor) {
        sim::ObjectProtocol protocol;
        protocol.object_radius = object_radius;
        protocol.view_radius = view_radius;
        protocol.views = views;
        protocol.resolution = resolution;
        protocol.sensor = sensor;
        return with_file(mesh, false, [&] { return sim::single_object_scene(mesh, protocol); });
      },
      py::arg("mesh"), py::arg("object_radius") = sim::ObjectProtocol{}.object_radius,
      py::arg("view_radius") = sim::ObjectProtocol{}.view_radius,
      py::arg("views") = sim::ObjectProtocol{}.views,
      py::arg("resolution") = sim::ObjectProtocol{}.resolution,
      py::arg("sensor") = sim::ObjectProtocol{}.sensor,
      "A single object on its view sphere, the field's protocol (docs/objects.md): `mesh` a file "
      "(.ply, .obj, .off, .stl) or a built-in model, centred on its bounding sphere scaled to "
      "`object_radius`, floating; `views` candidates spread over the sphere at `view_radius` "
      "from its centre, which are also its start poses [m]. Scene('bunny.ply') is the same "
      "with the defaults.");
  m.def("builtin_sensor_names", &sim::builtin_sensor_names,
        "Names of the built-in sensors ('hokuyo', 'kinect').");
  m.def(
      "pose_from_xyz_rpy",
      [](const DoubleArray& xyz, const DoubleArray& rpy) {
        return Eigen::Matrix4d(
            sim::pose_from_xyz_rpy(to_vector3(xyz, "xyz"), to_vector3(rpy, "rpy")).matrix());
      },
      py::arg("xyz"), py::arg("rpy"),
      "4 x 4 pose from a position [m] and roll, pitch, yaw [rad]: R = Rz(yaw) Ry(pitch) Rx(roll).");

  py::class_<sim::Scene>(m, "Scene",
                         "A simulated experiment's world: geometry, grid, sensor, start poses and "
                         "candidate views (docs/scenes.md).")
      .def(py::init(&load), py::arg("name_or_path"),
           "A built-in scene by name (builtin_scene_names()) or a scene YAML file. ValueError "
           "naming the file, line and key for a bad scene; OSError for a missing file.")
      .def_readonly("name", &sim::Scene::name, "The scene's name.")
      .def_readonly("source", &sim::Scene::source, "'built-in' or the YAML file's path.")
      .def_property_readonly(
          "kind", [](const sim::Scene& s) { return std::string(sim::to_string(s.kind)); },
          "'tabletop' or 'office'.")
      .def_readonly("grid", &sim::Scene::grid, "The GridSpec of the map.")
      .def_property_readonly("fov", &sim::Scene::fov, "The sensor's SensorFov.")
      .def_property_readonly(
          "sensor", [](const sim::Scene& s) { return s.sensor.name; }, "The sensor's name.")
      .def_property_readonly(
          "start_poses", [](const sim::Scene& s) { return from_poses(s.start_poses); },
          "Sensor poses the experiments start from, K x 4 x 4.")
      .def(
          "candidate_poses", [](const sim::Scene& s) { return from_poses(s.candidate_poses()); },
          "Table top: the ring's candidate sensor poses, K x 4 x 4; office: none.")
      .def("__repr__", [](const sim::Scene& s) {
        return cat("Scene('", s.name, "', kind=", sim::to_string(s.kind),
                   ", sensor=", s.sensor.name, ")");
      });

  def_world(m);
}

}  // namespace vantage::python
