// Bindings of planning: candidate poses, the next-best-view decision, the mapping pipeline and
// recorded data (clouds and poses, as `vantage plan` takes them).

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <bit>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_sets.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::python {

namespace {

/// A Plan and the candidates ranked as `vantage plan` ranks them.
struct RankedPlan {
  Plan plan;
  std::vector<std::size_t> ranking;  // Plan::ranking: the chosen first, estimates last
};

RankedPlan decide(const OccupancyGrid& grid, const DoubleArray& candidates, const SensorFov& fov,
                  const std::optional<PlannerConfig>& given, std::uint64_t seed,
                  const std::optional<Eigen::Isometry3d>& robot) {
  const PlannerConfig config = given.value_or(default_planner_config(robot.has_value()));
  config.validate();
  if (uses_travel(config.method) && !robot) {
    throw std::invalid_argument(cat("method ", to_string(config.method),
                                    " weighs travel and needs the robot's pose: give robot "
                                    "(its sensor's 4 x 4 T_world_sensor)"));
  }
  std::vector<Candidate> views;
  // NOTE: as `vantage plan`: travel is the straight line from the robot.
  for (const Frustum& view : to_views(candidates, fov, "candidates")) {
    const double travel = robot ? (view.origin() - robot->translation()).norm() : 0.0;
    views.push_back({view, travel});
  }
  check_decision_on(grid, views, config, python_budget());  // before any of it is computed
  RankedPlan out;
  {
    py::gil_scoped_release release;
    out.plan = plan_next_view(grid, views, config, seed);
  }
  out.ranking = out.plan.ranking();
  return out;
}

/// The mapping settings `vantage plan` derives from a manifest with these options.
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

/// Maps clouds given in `frame` at poses T_world_cloud into a fresh grid, as map_recorded maps a
/// manifest's clouds, then plans: the path `vantage plan` takes, with arrays for files.
py::tuple plan_recorded(const std::vector<DoubleArray>& clouds, const DoubleArray& poses,
                        const SensorFov& fov, const GridSpec& spec, const DoubleArray& candidates,
                        const std::string& frame, bool table_segmentation, bool icp,
                        const std::string& integration, std::optional<PlannerConfig> given,
                        std::uint64_t seed) {
  const CloudFrame cloud_frame = parse_cloud_frame(frame);
  const std::vector<Eigen::Isometry3d> T_world_cloud = to_poses(poses, "poses");
  if (T_world_cloud.size() != clouds.size()) {
    throw std::invalid_argument(cat("got ", clouds.size(), " clouds but ", T_world_cloud.size(),
                                    " poses; give one pose per cloud"));
  }
  if (clouds.empty()) throw std::invalid_argument("give at least one cloud");
  PlannerConfig config = given.value_or(default_planner_config(true));
  request_plan_reference(config);  // as `vantage plan`
  check_grid_memory(spec, mapping_cost(config.gain.num_threads), "the plan's grid");
  Mapper mapper(
      spec, recorded_mapper_config(integration, table_segmentation, icp, config.gain.num_threads));
  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
  T_cloud_sensor.linear() = R_cloud_sensor(cloud_frame);
  const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(cloud_frame).transpose();
  Eigen::Isometry3d robot = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    const std::string name = cat("clouds[", i, "]");
    PointCloud points = to_cloud(clouds[i], name.c_str());
    for (Eigen::Vector3d& p : points) p = R_sensor_cloud * p;
    try {
      py::gil_scoped_release release;
      robot = mapper.add_scan(points, T_world_cloud[i] * T_cloud_sensor, fov).T_world_sensor;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(cat(name, ": ", e.what()));
    }
  }
  // NOTE: as `vantage plan`, the robot stands where the last cloud was taken (after ICP).
  return py::make_tuple(mapper.grid(), decide(mapper.grid(), candidates, fov, config, seed, robot));
}

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

}  // namespace

void bind_plan(py::module_& m) {
  m.def(
      "look_at",
      [](const DoubleArray& eye, const DoubleArray& target) {
        return Eigen::Matrix4d(
            look_at(to_vector3(eye, "eye"), to_vector3(target, "target")).matrix());
      },
      py::arg("eye"), py::arg("target"),
      "4 x 4 pose of a sensor at `eye` looking at `target`, its z axis as close to world +z as "
      "the direction allows [m].");
  m.def(
      "ring_poses",
      [](const DoubleArray& center, double radius, double height, int positions, double start_angle,
         const std::vector<double>& yaw_offsets) {
        RingConfig ring;
        ring.center = to_vector3(center, "center");
        ring.radius = radius;
        ring.height = height;
        ring.positions = positions;
        ring.start_angle = start_angle;
        ring.yaw_offsets = yaw_offsets;
        ring.validate();
        return from_poses(ring_poses(ring));
      },
      py::arg("center"), py::arg("radius"), py::arg("height"), py::arg("positions") = 10,
      py::arg("start_angle") = 0.0, py::arg("yaw_offsets") = RingConfig{}.yaw_offsets,
      "Candidate views on a horizontal circle around `center` (§5.1): `positions` sensor "
      "positions at `height`, each looking at the centre turned by every yaw offset [m, rad]. "
      "Returns a K x 4 x 4 array, view (k, j) at index k * len(yaw_offsets) + j.");
  m.def(
      "ring_candidates",
      [](const py::object& region, std::optional<double> radius, std::optional<double> height,
         std::optional<int> positions) {
        Eigen::AlignedBox3d roi;
        if (py::isinstance<GridSpec>(region)) {
          const auto& spec = region.cast<const GridSpec&>();
          roi = Eigen::AlignedBox3d(spec.origin, spec.max_corner());
        } else {
          const auto corners = region.cast<std::pair<DoubleArray, DoubleArray>>();
          roi = Eigen::AlignedBox3d(to_vector3(corners.first, "roi[0]"),
                                    to_vector3(corners.second, "roi[1]"));
          if (!roi.min().allFinite() || !roi.max().allFinite() ||
              (roi.min().array() > roi.max().array()).any()) {
            throw std::invalid_argument("roi must be (min corner, max corner), min <= max");
          }
        }
        RingConfig ring = default_ring(roi);
        if (radius) ring.radius = *radius;
        if (height) ring.height = *height;
        if (positions) ring.positions = *positions;
        ring.validate();
        return from_poses(ring_poses(ring));
      },
      py::arg("region"), py::arg("radius") = std::nullopt, py::arg("height") = std::nullopt,
      py::arg("positions") = std::nullopt,
      "The candidates `vantage plan` scores by default (--candidates ring): a ring around "
      "`region`, a GridSpec (its box, as for `plan --map`) or a (min, max) region of interest "
      "(a manifest's roi) [m]; radius 1.5 half-diagonals of its footprint (at least 1 m), 0.3 m "
      "above its top, 10 positions, yaw offsets -15, 0, 15 degrees; radius, height and "
      "positions as `plan --radius --height --views` override them. K x 4 x 4.");
  m.def(
      "candidate_sets",
      [] {
        std::vector<std::pair<std::string, std::string>> sets;
        for (const CandidateSetRow& row : candidate_sets()) {
          sets.emplace_back(std::string(row.name), std::string(row.help));
        }
        return sets;
      },
      "The candidate sets by name, with a line each: the registry `vantage plan --candidates`, "
      "`explore` and `bench` read (views/candidate_sets.hpp).");
  m.def(
      "candidate_views",
      [](const std::string& name, const DoubleArray& roi_min, const DoubleArray& roi_max,
         double radius, int views, std::optional<DoubleArray> poses) {
        CandidateSite site;
        site.region =
            Eigen::AlignedBox3d(to_vector3(roi_min, "roi_min"), to_vector3(roi_max, "roi_max"));
        if (!site.region.min().allFinite() || !site.region.max().allFinite() ||
            (site.region.min().array() > site.region.max().array()).any()) {
          throw std::invalid_argument("roi must be (min corner, max corner), min <= max");
        }
        site.target = site.region.center();
        CandidateParams params;
        params.radius = radius;
        params.views = views;
        if (poses) params.listed = to_poses(*poses, "poses");
        const CandidateSetRow& row = find_candidate_set(name);
        if (row.needs_robot) {
          throw std::invalid_argument(
              cat("candidate set '", name, "' is an office robot's: explore an office with it"));
        }
        if (row.needs_map) {
          throw std::invalid_argument(
              cat("candidate set '", name, "' is found in a map: plan with it (vt.plan)"));
        }
        return from_poses(row.build(site, params).poses);
      },
      py::arg("name"), py::arg("roi_min"), py::arg("roi_max"), py::arg("radius") = 0.0,
      py::arg("views") = 0, py::arg("poses") = std::nullopt,
      "The views of the candidate set `name` (candidate_sets()) around a region of interest, "
      "as `vantage plan --candidates NAME` places them: radius and views 0 for the set's own "
      "[m]; 'file' takes `poses` (K x 4 x 4). K x 4 x 4.");
  m.def(
      "sphere_poses",
      [](const DoubleArray& center, double radius, int views) {
        SphereConfig sphere;
        sphere.center = to_vector3(center, "center");
        sphere.radius = radius;
        sphere.views = views;
        sphere.validate();
        return from_poses(sphere_poses(sphere));
      },
      py::arg("center"), py::arg("radius"), py::arg("views") = 50,
      "Candidate views spread over a sphere around `center`, each looking at it [m]; K x 4 x 4.");
  m.def(
      "grid_for_roi",
      [](const DoubleArray& roi_min, const DoubleArray& roi_max, double resolution) {
        return grid_for_roi(
            Eigen::AlignedBox3d(to_vector3(roi_min, "roi_min"), to_vector3(roi_max, "roi_max")),
            resolution);
      },
      py::arg("roi_min"), py::arg("roi_max"), py::arg("resolution"),
      "The grid `vantage plan` maps a region of interest into: whole cells on the lattice "
      "through the world origin (OctoMap's) that hold the box [m].");

  py::class_<RankedPlan>(m, "Plan", "The decision and everything behind it.")
      .def_property_readonly(
          "best", [](const RankedPlan& p) { return p.plan.best; }, "Index of the chosen view.")
      .def_property_readonly(
          "gains", [](const RankedPlan& p) { return p.plan.gains; },
          "Each candidate's predicted gain under the method's model (list of ViewGain).")
      .def_property_readonly(
          "greedy_gains", [](const RankedPlan& p) { return p.plan.greedy_gains; },
          "Each candidate's greedy gain [bits] (when requested or used; else empty).")
      .def_property_readonly(
          "scores", [](const RankedPlan& p) { return p.plan.scores; }, "What was maximised.")
      .def_readonly("ranking", &RankedPlan::ranking,
                    "Candidate indices, the chosen one first, then those evaluated in full by "
                    "score, then the estimated ones by score (the order of `vantage plan`'s table "
                    "and JSON).")
      .def_property_readonly(
          "search", [](const RankedPlan& p) { return std::string(to_string(p.plan.search)); },
          "The search that decided: swept, pruned or exhaustive.")
      .def_property_readonly(
          "estimated",
          [](const RankedPlan& p) {
            std::vector<bool> out(p.plan.scores.size());
            for (std::size_t c = 0; c < out.size(); ++c) out[c] = p.plan.is_estimate(c);
            return out;
          },
          "Per candidate: whether its gains and score are the search's estimate or upper bound, "
          "not a full evaluation.")
      .def_property_readonly(
          "seconds", [](const RankedPlan& p) { return p.plan.seconds; },
          "Wall time of the decision [s].")
      .def("__repr__", [](const RankedPlan& p) {
        const std::size_t best = p.plan.best;
        std::string out = cat("Plan(best=", best, ", candidates=", p.plan.scores.size());
        if (best < p.plan.scores.size()) out += cat(", score=", p.plan.scores[best]);
        if (best < p.plan.gains.size()) {
          out += cat(", gain=", p.plan.gains[best].gain, ", cells=", p.plan.gains[best].cells);
        }
        if (best < p.plan.greedy_gains.size()) out += cat(", greedy=", p.plan.greedy_gains[best]);
        return out + cat(", seconds=", p.plan.seconds, ")");
      });

  m.def(
      "plan_next_view",
      [](const OccupancyGrid& grid, const DoubleArray& candidates, const SensorFov& fov,
         const std::optional<PlannerConfig>& config, std::uint64_t seed,
         const std::optional<Eigen::Matrix4d>& robot) {
        return decide(grid, candidates, fov, config, seed,
                      robot ? std::optional(to_pose(*robot, "robot")) : std::nullopt);
      },
      py::arg("grid"), py::arg("candidates"), py::arg("fov"), py::arg("config") = std::nullopt,
      py::arg("seed") = 1, py::arg("robot") = std::nullopt,
      "Scores K x 4 x 4 candidate sensor poses seen with `fov` on the grid and chooses one "
      "(ties to the lower index, 'random' uses `seed`). `robot`: the robot's sensor pose now, "
      "4 x 4 T_world_sensor, whence each candidate's travel, the straight line [m]. `config` "
      "None: `vantage plan`'s default, latombe+surface, or surface without `robot`. Returns a "
      "Plan.");

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

  m.def("plan", &plan_recorded, py::arg("clouds"), py::arg("poses"), py::arg("fov"),
        py::arg("spec"), py::arg("candidates"), py::arg("frame") = "x_forward",
        py::arg("table_segmentation") = false, py::arg("icp") = false,
        py::arg("integration") = "paper", py::arg("config") = std::nullopt, py::arg("seed") = 1,
        "Real scans in, next view out, as `vantage plan` does: maps the clouds (N x 3 arrays in "
        "the cloud frame `frame`, 'x_forward' or 'optical') at their 4 x 4 poses T_world_cloud "
        "into a fresh grid of `spec`, then scores the candidate sensor poses (x forward), the "
        "robot at the last cloud's sensor pose; `config` None: `vantage plan`'s default, "
        "latombe+surface. Returns (grid, plan).");
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
