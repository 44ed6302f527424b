// Bindings of the exploration loop a scan at a time (Exploration): the engine of Python's
// ExploreEnv (python/vantage/env.py), and a Python policy's trials in a sweep (run_bench).

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {
namespace {

/// What a run needs besides a trial: the settings of `vantage bench`'s (and explore's) defaults
/// with these changed. `method` is the planner's (ExploreEnv's reference); empty: greedy.
struct RunSettings {
  std::string method;
  std::string candidates;  ///< empty: the scene's own (a table top's ring, an object's sphere)
  int scans = 10;
  std::uint64_t seed = 1;
  int coverage_tolerance = -1;  ///< [cells]; -1: the scene kind's own (1, objects 0)
  int num_threads = 0;
};

/// The sweep `vantage bench` runs with the same options (its command's defaults otherwise).
BenchConfig bench_config(const RunSettings& s) {
  BenchConfig config;
  PlanningSettings planning;
  planning.method = s.method.empty() ? std::string(to_string(PlannerMethod::kGreedy)) : s.method;
  planning.threads = s.num_threads;
  try {
    config.exploration.planner = planning.planner_config();
  } catch (const SettingError& e) {
    throw std::invalid_argument(cat(e.setting(), ": ", e.what()));
  }
  config.exploration.mapper.integration.num_threads = s.num_threads;
  // NOTE: the command's --segmentation default: the scene's table segmentation, where it has one
  // (mapper_from_scene).
  config.exploration.mapper.segment_table = true;
  config.exploration.scans = s.scans;
  config.exploration.seed = s.seed;
  config.exploration.candidates = s.candidates;
  if (s.coverage_tolerance >= 0) config.exploration.coverage_tolerance = s.coverage_tolerance;
  config.exploration.budget = python_budget();
  config.methods = {config.exploration.planner.method};
  return config;
}

/// The scene a Python argument names: a Scene, a built-in name or a scene file.
sim::Scene scene_of(const py::object& scene) {
  if (!py::isinstance<py::str>(scene)) return scene.cast<sim::Scene>();
  const std::string name = scene.cast<std::string>();
  return with_file(name, false, [&] { return sim::load_scene(name); });
}

/// An object's run as `vantage explore --object` makes it: the arm's exact poses, and MA-SCVP's
/// tolerance unless told another.
void object_defaults(ExplorationConfig& config, const RunSettings& s) {
  config.pose_noise.reset();
  if (s.coverage_tolerance < 0) config.coverage_tolerance = 0;
}

/// What a planner may know after the scans so far (ExploreEnv's observation).
py::dict observation(const Exploration& run) {
  const ExplorationResult& result = run.result();
  const OccupancyGrid& grid = run.mapper().grid();
  const std::vector<bool>& taken = run.taken();
  py::array_t<bool> mask(static_cast<py::ssize_t>(taken.size()));
  for (std::size_t i = 0; i < taken.size(); ++i) mask.mutable_at(i) = taken[i];
  const std::vector<double> travel = run.travel();
  py::dict obs;
  obs["cells"] = state_array(grid);
  obs["log_odds"] = log_odds_array(grid);
  obs["pose"] = Eigen::Matrix4d(result.scans.back().T_world_sensor.matrix());
  obs["candidates"] = from_poses(result.candidates);
  obs["taken"] = mask;
  obs["travel"] = py::array_t<double>(static_cast<py::ssize_t>(travel.size()), travel.data());
  obs["scan"] = result.scans.size();
  return obs;
}

py::object optional(const std::optional<double>& value) {
  return value ? py::object(py::float_(*value)) : py::object(py::none());
}

/// The last scan's record as ExploreEnv's info: scans.csv's columns of it.
py::dict scan_info(const Exploration& run) {
  const ScanRecord& r = run.result().scans.back();
  py::dict info;
  info["scan"] = r.scan;
  info["view"] = r.view;
  info["surface_coverage"] = optional(r.surface_coverage);
  info["raw_surface_coverage"] = optional(r.raw_surface_coverage);
  info["coverage"] = r.coverage;
  info["unobserved"] = r.unobserved;
  info["actual_gain"] = r.actual_gain;
  info["travel_m"] = r.travel;
  info["plan_seconds"] = r.seconds.plan;
  info["pose_error_after_m"] = r.pose_error_after;
  if (run.done()) info["stop_reason"] = run.result().stop_reason;
  return info;
}

/// One episode's engine: the scene, its settings and yardstick truth (computed once), and the
/// run of the current episode.
class ExploreRun {
 public:
  ExploreRun(const py::object& scene, const RunSettings& settings, int start)
      : scene_(scene_of(scene)), bench_(bench_config(settings)) {
    if (scene_.kind == sim::SceneKind::kOffice) {
      throw std::invalid_argument(cat("scene '", scene_.name,
                                      "' is an office: ExploreEnv is for table tops and objects "
                                      "(an office's candidates are the planner's frontier stops)"));
    }
    if (scene_.kind == sim::SceneKind::kObject) {
      object_defaults(bench_.exploration, settings);
    }
    const int starts = static_cast<int>(scene_.start_poses.size());
    if (start < 0 || start >= starts) {
      throw std::invalid_argument(cat("start ", start, " is out of range: scene '", scene_.name,
                                      "' has ", starts, " start poses"));
    }
    const PlannerMethod method = bench_.exploration.planner.method;
    trial_ = {scene_.name,
              scene_.source,
              method,
              default_alpha_setting(method, kTableTopAlpha),
              natural_objective(method),
              start};
    config_ = trial_config(trial_, bench_, scene_);
    config_.validate();
    py::gil_scoped_release release;
    const std::vector<Eigen::Isometry3d> candidates = run_candidates(scene_, config_);
    check_surface_truth(scene_, candidates.size(), config_.budget);
    const sim::World world(scene_, sim::WorldConfig{config_.planner.gain.num_threads});
    truth_ = compute_surface_truth(world, candidates, config_.coverage_tolerance,
                                   config_.planner.gain.num_threads);
  }

  /// A new episode with the sweep seed `seed`: the first scan, from the start.
  void reset(std::uint64_t seed) {
    bench_.exploration.seed = seed;
    config_ = trial_config(trial_, bench_, scene_);
    run_.reset();
    check_grid_memory(scene_.grid, mapping_cost(config_.planner.gain.num_threads), "a run's grid");
    py::gil_scoped_release release;
    mapper_ = std::make_unique<Mapper>(scene_.grid, config_.mapper);
    run_ = std::make_unique<Exploration>(scene_, config_, *mapper_, &*truth_);
    run_->step();
  }

  void step(int view, double seconds) {
    running();
    py::gil_scoped_release release;
    run_->step(view, seconds);
  }

  py::dict propose() {
    running();
    ViewProposal p;
    {
      py::gil_scoped_release release;
      p = run_->propose();
    }
    const std::size_t n = run_->result().candidates.size();
    py::array_t<double> gains(static_cast<py::ssize_t>(n));
    for (std::size_t i = 0; i < n; ++i) gains.mutable_at(i) = std::nan("");
    for (const CandidateRecord& c : p.considered) {
      gains.mutable_at(static_cast<std::size_t>(c.view)) = c.predicted_gain;
    }
    py::dict out;
    out["method"] = std::string(to_string(config_.planner.method));
    out["view"] = p.view;
    out["gains"] = gains;
    out["seconds"] = p.seconds;
    return out;
  }

  const Exploration& running() const {
    if (!run_) throw std::runtime_error("no episode yet: call reset() first");
    return *run_;
  }

  const sim::Scene& scene() const { return scene_; }
  const ExplorationConfig& config() const { return config_; }
  const SurfaceTruth& truth() const { return *truth_; }

 private:
  sim::Scene scene_;
  BenchConfig bench_;
  TrialSpec trial_;
  ExplorationConfig config_;
  std::optional<SurfaceTruth> truth_;
  std::unique_ptr<Mapper> mapper_;
  std::unique_ptr<Exploration> run_;  // NOTE: after mapper_, which it refers to
};

/// Cell indices (linear, x fastest, as the grid's) as a uint32 array.
py::array_t<std::uint32_t> cell_array(const std::vector<std::uint32_t>& cells) {
  return py::array_t<std::uint32_t>(static_cast<py::ssize_t>(cells.size()), cells.data());
}

/// The yardstick's truth of the run's scene and candidates (ExploreEnv.truth).
py::dict truth_dict(const SurfaceTruth& truth) {
  py::list views, starts;
  for (const auto& hits : truth.candidate_hits) views.append(cell_array(hits));
  for (const auto& hits : truth.start_hits) starts.append(cell_array(hits));
  py::dict out;
  out["surface"] = cell_array(truth.surface);
  out["visible"] = cell_array(truth.visible);
  out["views"] = views;
  out["starts"] = starts;
  out["tolerance_cells"] = truth.tolerance.cells;
  out["tolerance_m"] = truth.tolerance.metres;
  return out;
}

/// A Python policy's choice: the index it returned, refused unless an integer (not a bool).
int policy_view(const py::object& value, const std::string& name) {
  const auto refuse = [&](const char* why) {
    return std::invalid_argument(
        cat("policy '", name, "' returned ", py::repr(value).cast<std::string>(), ", ", why));
  };
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) {
    throw refuse("not a candidate's index (an integer)");
  }
  const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0 || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
    throw refuse("out of range");
  }
  return static_cast<int>(v);
}

/// One line of a Python exception: its type and message.
std::string one_line(py::error_already_set& e) {
  std::string text = cat(py::str(e.type().attr("__name__")).cast<std::string>(), ": ",
                         py::str(e.value()).cast<std::string>());
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

/// Runs `policy` (obs -> candidate index) through the sweep in `out`, as vantage bench runs a
/// method. Returns the number of trials run now.
std::size_t bench_policy(const py::function& policy, const std::string& name,
                         const std::vector<std::string>& scenes, int trials,
                         const std::filesystem::path& out, const RunSettings& settings,
                         int generated, int objects, std::uint64_t generated_seed) {
  BenchConfig config = bench_config(settings);
  config.scenes = scenes;
  config.generated = generated;
  config.pile.objects = objects < 0 ? sim::PileConfig{}.objects : objects;  // -1: the default
  config.pile.seed = generated_seed;
  config.trials = trials;
  config.methods.clear();
  config.jobs = 1;  // NOTE: the policy is called from this thread only, one trial at a time
  // NOTE: a sweep of objects (meshes or built-in models) runs as `vantage bench objects` does.
  if (!scenes.empty() && std::all_of(scenes.begin(), scenes.end(), sim::is_object_source)) {
    object_defaults(config.exploration, settings);
  }
  config.policies.push_back({name, [&policy, name](const Exploration& run) {
                               py::gil_scoped_acquire gil;
                               py::dict obs = observation(run);
                               const auto start = std::chrono::steady_clock::now();
                               py::object choice;
                               try {
                                 choice = policy(obs);
                               } catch (py::error_already_set& e) {
                                 throw std::runtime_error(
                                     cat("policy '", name, "' raised ", one_line(e)));
                               }
                               const double seconds = seconds_since(start);
                               return ViewChoice{policy_view(choice, name), seconds};
                             }});
  config.validate();
  py::gil_scoped_release release;
  return run_bench(out, config);
}

}  // namespace

void bind_env(py::module_& m) {
  py::class_<ExploreRun>(m, "_ExploreRun",
                         "The engine of ExploreEnv (vantage.env): one table-top exploration "
                         "run, a scan at a time.")
      .def(py::init([](const py::object& scene, const std::string& candidates, int scans, int start,
                       const std::optional<std::string>& method, int coverage_tolerance,
                       int num_threads) {
             RunSettings s;
             s.method = method.value_or("");
             s.candidates = candidates;
             s.scans = scans;
             s.coverage_tolerance = coverage_tolerance;
             s.num_threads = num_threads;
             return std::make_unique<ExploreRun>(scene, s, start);
           }),
           py::arg("scene"), py::arg("candidates"), py::arg("scans"), py::arg("start"),
           py::arg("method"), py::arg("coverage_tolerance"), py::arg("num_threads"))
      .def("reset", &ExploreRun::reset, py::arg("seed"))
      .def("step", &ExploreRun::step, py::arg("view"), py::arg("seconds"))
      .def("propose", &ExploreRun::propose)
      .def("observation", [](const ExploreRun& r) { return observation(r.running()); })
      .def("info", [](const ExploreRun& r) { return scan_info(r.running()); })
      .def_property_readonly("done", [](const ExploreRun& r) { return r.running().done(); })
      .def_property_readonly("scene", &ExploreRun::scene)
      .def_property_readonly("fov", [](const ExploreRun& r) { return r.scene().fov(); })
      .def_property_readonly("grid", [](const ExploreRun& r) { return r.scene().grid; })
      .def_property_readonly("scans", [](const ExploreRun& r) { return r.config().scans; })
      .def_property_readonly(
          "candidates",
          [](const ExploreRun& r) { return from_poses(run_candidates(r.scene(), r.config())); })
      .def_property_readonly(
          "method",
          [](const ExploreRun& r) { return std::string(to_string(r.config().planner.method)); })
      .def_property_readonly("run_seed", [](const ExploreRun& r) { return r.config().seed; })
      .def_property_readonly("truth", [](const ExploreRun& r) { return truth_dict(r.truth()); });

  m.def(
      "_bench_policy",
      [](const py::function& policy, const std::string& name,
         const std::vector<std::string>& scenes, int trials, const std::string& out, int scans,
         const std::string& candidates, std::uint64_t seed, int coverage_tolerance, int num_threads,
         int generated, int objects, std::uint64_t generated_seed) {
        RunSettings s;
        s.candidates = candidates;
        s.scans = scans;
        s.seed = seed;
        s.coverage_tolerance = coverage_tolerance;
        s.num_threads = num_threads;
        return bench_policy(policy, name, scenes, trials, out, s, generated, objects,
                            generated_seed);
      },
      py::arg("policy"), py::arg("name"), py::arg("scenes"), py::arg("trials"), py::arg("out"),
      py::arg("scans"), py::arg("candidates"), py::arg("seed"), py::arg("coverage_tolerance"),
      py::arg("num_threads"), py::arg("generated"), py::arg("objects"), py::arg("generated_seed"),
      "The engine of vantage.bench_policy.");
}

}  // namespace vantage::python
