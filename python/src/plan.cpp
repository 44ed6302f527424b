// Bindings of the next-best-view decision: Plan, plan_next_view, and plan (real scans in, next
// view out, as `vantage plan` takes them).

#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/io/manifest.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/text.hpp"

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

/// Plan, the decision and everything behind it.
void def_plan_class(py::module_& m) {
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
}

}  // namespace

void bind_plan(py::module_& m) {
  def_plan_class(m);
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

  m.def("plan", &plan_recorded, py::arg("clouds"), py::arg("poses"), py::arg("fov"),
        py::arg("spec"), py::arg("candidates"), py::arg("frame") = "x_forward",
        py::arg("table_segmentation") = false, py::arg("icp") = false,
        py::arg("integration") = "paper", py::arg("config") = std::nullopt, py::arg("seed") = 1,
        "Real scans in, next view out, as `vantage plan` does: maps the clouds (N x 3 arrays in "
        "the cloud frame `frame`, 'x_forward' or 'optical') at their 4 x 4 poses T_world_cloud "
        "into a fresh grid of `spec`, then scores the candidate sensor poses (x forward), the "
        "robot at the last cloud's sensor pose; `config` None: `vantage plan`'s default, "
        "latombe+surface. Returns (grid, plan).");
}

}  // namespace vantage::python
