// Bindings of mapping as `vantage plan` maps: the Mapper scan by scan, a manifest read and its
// clouds mapped, point cloud files.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {

namespace {

MapperUpdate add_scan(Mapper& mapper, const DoubleArray& points_sensor,
                      const Eigen::Matrix4d& T_world_sensor, const SensorFov& fov) {
  const PointCloud points = to_cloud(points_sensor, "points_sensor");
  const Eigen::Isometry3d pose = to_pose(T_world_sensor, "T_world_sensor");
  py::gil_scoped_release release;
  return mapper.add_scan(points, pose, fov);
}

/// Mapper(start, integration=..., table_segmentation=..., icp=..., num_threads=...), where
/// `start` is a GridSpec (a fresh grid) or an OccupancyGrid (continued).
template <typename Start>
void def_mapper_init(py::class_<Mapper>& mapper, const char* start, const char* doc) {
  mapper.def(py::init([](const Start& from, const std::string& integration, bool table_segmentation,
                         bool icp, int num_threads) {
               if constexpr (std::is_same_v<Start, GridSpec>) {
                 check_grid_memory(from, mapping_cost(num_threads), "a Mapper's grid");
               } else {
                 check_grid_memory(from.spec(), mapping_cost(num_threads), "a Mapper's grid");
               }
               return Mapper(
                   from, recorded_mapper_config(integration, table_segmentation, icp, num_threads));
             }),
             py::arg(start), py::arg("integration") = "paper",
             py::arg("table_segmentation") = false, py::arg("icp") = false,
             py::arg("num_threads") = 0, doc);
}

/// A manifest as read_manifest returns it to Python.
py::dict manifest_dict(const Manifest& manifest) {
  py::list clouds;
  for (const ManifestCloud& c : manifest.clouds) {
    py::dict cloud;
    cloud["file"] = c.file;
    cloud["T_world_cloud"] = Eigen::Matrix4d(c.T_world_cloud.matrix());
    cloud["T_world_sensor"] = Eigen::Matrix4d(c.T_world_sensor.matrix());
    cloud["stamp"] = c.stamp;
    // NOTE: where a cloud without a given pose gets one (issue 38): "table", "registration".
    cloud["pose_from"] = c.pose_from_table          ? "table"
                         : c.pose_from_registration ? "registration"
                         : c.pose_from_viewpoint    ? "viewpoint"
                                                    : "given";
    clouds.append(cloud);
  }
  py::dict out;
  out["file"] = manifest.file;
  out["clouds"] = clouds;
  out["frame"] = std::string(to_string(manifest.frame));
  out["fov"] = manifest.fov;
  out["roi"] =
      py::make_tuple(Eigen::Vector3d(manifest.roi.min()), Eigen::Vector3d(manifest.roi.max()));
  out["grid"] = manifest.grid;
  out["table_segmentation"] = manifest.options.table_segmentation;
  out["icp"] = manifest.options.icp;
  out["integration"] = std::string(to_string(manifest.options.integration));
  out["skip_non_finite"] = manifest.options.skip_non_finite;
  if (const auto& s = manifest.salvage) {
    py::dict salvage;
    salvage["damage"] = s->damage;
    salvage["byte"] = s->offset;
    salvage["frames_kept"] = s->frames;
    salvage["frames_dropped"] = s->dropped;
    out["salvage"] = salvage;
  }
  return out;
}

/// MapperUpdate and Mapper.
void def_mapper_classes(py::module_& m) {
  py::class_<MapperUpdate>(m, "MapperUpdate", "What adding one scan to a Mapper did.")
      .def_property_readonly(
          "T_world_sensor",
          [](const MapperUpdate& u) { return Eigen::Matrix4d(u.T_world_sensor.matrix()); },
          "The pose the scan was integrated at (after ICP, when it ran).")
      .def_readonly("registered", &MapperUpdate::registered,
                    "Registration ran and its correction passed the check against the prior.")
      .def_property_readonly(
          "registration",
          [](const MapperUpdate& u) { return std::string(perception::to_string(u.registration)); },
          "Registration's outcome: accepted, or why the believed pose was kept (empty_map, "
          "too_few_matches, outside_prior, uncertain, worse_than_prior).")
      .def_readonly("points", &MapperUpdate::points, "Points in the scan.")
      .def_readonly("object_points", &MapperUpdate::object_points,
                    "Points integrated (after table segmentation).")
      .def_readonly("integration", &MapperUpdate::integration, "The IntegrationResult.")
      .def_property_readonly(
          "reregistered",
          [](const MapperUpdate& u) {
            std::vector<std::pair<std::size_t, Eigen::Matrix4d>> out;
            for (const MapperUpdate::Reregistered& r : u.reregistered) {
              out.emplace_back(r.scan, r.T_world_sensor.matrix());
            }
            return out;
          },
          "Earlier scans that had fallen back and passed on a second try against the reference "
          "this scan grew, as (0-based scan index, 4x4 pose); the map was rebuilt with them.");

  py::class_<Mapper> mapper_class(
      m, "Mapper",
      "Builds a map scan by scan as `vantage plan` does: optional ICP "
      "against the points so far (§4.2), optional table segmentation (§5.1), "
      "integration.");
  def_mapper_init<GridSpec>(mapper_class, "spec",
                            "A mapper over a fresh grid; the switches are a manifest's options.");
  def_mapper_init<OccupancyGrid>(
      mapper_class, "grid",
      "A mapper that continues a copy of an existing map (one read from OctoMap).");
  mapper_class
      .def("add_scan", &add_scan, py::arg("points_sensor"), py::arg("T_world_sensor"),
           py::arg("fov"),
           "Adds an N x 3 array of points in the sensor frame (x forward, y left, z up) taken "
           "from the 4 x 4 pose. ValueError for a non-finite point or a pose that is not rigid; "
           "the map is unchanged then.")
      .def_property_readonly(
          "grid", [](const Mapper& mp) { return mp.grid(); }, "A copy of the map so far.")
      .def_property_readonly("scans", &Mapper::scans, "Scans added.")
      .def_property_readonly(
          "object_cloud", [](const Mapper& mp) { return from_cloud(mp.object_cloud()); },
          "The points that went into the grid, in the world [m].");
}

}  // namespace

MapperConfig recorded_mapper_config(const std::string& integration, bool table_segmentation,
                                    bool icp, int num_threads) {
  Manifest manifest;
  manifest.options.integration = parse_integration_mode(integration);
  manifest.options.table_segmentation = table_segmentation;
  manifest.options.icp = icp;
  MapperConfig config = mapper_config_for(manifest);
  config.integration.num_threads = num_threads;
  config.validate();
  return config;
}

void bind_mapping(py::module_& m) {
  def_mapper_classes(m);
  m.def(
      "read_manifest",
      [](const std::filesystem::path& path, std::optional<int> every,
         std::optional<std::string> topic, bool salvage) {
        return manifest_dict(with_file(path, false, [&] {
          return read_manifest(path, {.every = every, .topic = topic, .salvage = salvage});
        }));
      },
      py::arg("path"), py::arg("every") = py::none(), py::arg("topic") = py::none(),
      py::arg("salvage") = false,
      "Reads a manifest (a YAML file or a folder holding manifest.yaml, docs/manifest.md) into a "
      "dict: clouds (file, T_world_cloud, T_world_sensor, stamp, pose_from), frame, fov, roi, "
      "grid and the options. `every` and `topic` choose the frames of its TUM folder or "
      "recording, as `vantage plan --every --topic` do; `salvage` takes the whole frames before "
      "a damaged recording's damage, as `--salvage` does (the dict's salvage says what was "
      "dropped).");
  m.def(
      "map_recorded",
      [](const std::filesystem::path& path, int num_threads, std::optional<int> every,
         std::optional<std::string> topic, bool salvage) {
        const Manifest manifest = with_file(path, false, [&] {
          return read_manifest(path, {.every = every, .topic = topic, .salvage = salvage});
        });
        MapperConfig config = mapper_config_for(manifest);
        config.integration.num_threads = num_threads;
        check_grid_memory(manifest.grid, mapping_cost(num_threads),
                          cat("the grid of ", path.string()));
        Mapper mapper(manifest.grid, config);
        py::gil_scoped_release release;
        map_recorded(manifest, mapper);
        return mapper.grid();
      },
      py::arg("path"), py::arg("num_threads") = 0, py::arg("every") = py::none(),
      py::arg("topic") = py::none(), py::arg("salvage") = false,
      "Maps a manifest's clouds (files, a TUM folder or a recording) exactly as `vantage plan` "
      "does, a cloud without a pose after the first by registration; returns the grid.");
  m.def(
      "read_point_cloud",
      [](const std::filesystem::path& path, bool skip_non_finite) {
        return from_cloud(
            with_file(path, false, [&] { return read_point_cloud(path, {skip_non_finite}); }));
      },
      py::arg("path"), py::arg("skip_non_finite") = false,
      "The x, y, z of every point of a .pcd or .ply file as an N x 3 array [m].");
  m.def(
      "write_point_cloud",
      [](const std::filesystem::path& path, const DoubleArray& points) {
        const PointCloud cloud = to_cloud(points, "points");
        with_file(path, true, [&] { write_point_cloud(path, cloud); });
      },
      py::arg("path"), py::arg("points"),
      "Writes an N x 3 array as binary .pcd or .ply (float32 x, y, z), atomically.");
}

}  // namespace vantage::python
