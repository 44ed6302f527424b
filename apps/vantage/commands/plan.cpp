/// `vantage plan`: real scans in, next view out. Maps a robot's clouds (a manifest, see
/// docs/manifest.md) and/or an existing OctoMap, scores candidate views, and answers with the
/// next best view as a ranked table, plan.json, the updated map (map.ot, lossless: the next
/// `plan --map` continues from it exactly) and a picture.

#include <fmt/chrono.h>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/gain/metrics.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/map_files.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/io/ply_export.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/views/frontier.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct PlanOptions {
  std::string input;  // manifest or folder
  std::string map;    // .bt / .ot to start from
  std::string candidates = "ring";
  double radius = 0.0;  // 0: from the ROI
  double height = std::numeric_limits<double>::quiet_NaN();
  int views = 0;  // 0: 10 ring positions / 50 sphere views
  std::string fov_deg = "57,43";
  std::string range = "0.5,3.5";
  PlanningOptions planning;
  std::string pose;  // x,y,z,roll,pitch,yaw of the robot's sensor now
  std::string out;
  bool json_only = false;
  bool plots = true;
  int top = 10;
  std::uint64_t max_memory = 0;  // 0: what the machine has available
};

/// plan.json's format: 2 added version, units, the robot's pose, travel and yaw.
constexpr int kPlanJsonVersion = 2;

/// What a plan's numbers count (docs/model.md: bits are not cells). The probabilistic method
/// predicts information (eq. 4, bits); greedy, random and latombe count cells (latombe discounted
/// by travel); yamauchi maximises minus the travel distance.
struct PlanUnits {
  std::string_view predicted_gain;
  std::string_view score;
};

PlanUnits units_of(PlannerMethod method) {
  // docs/model.md "The field's metrics": each in its own unit.
  if (is_volumetric_metric(gain_method_of(method))) return {"metric", "metric"};
  switch (method) {
    case PlannerMethod::kProbabilistic:
    case PlannerMethod::kSurvival:
      return {"bits", "bits"};
    case PlannerMethod::kYamauchi:
      return {"cells", "-m"};
    default:
      return {"cells", "cells"};
  }
}

bool needs_pose(PlannerMethod method) {
  return method == PlannerMethod::kLatombe || method == PlannerMethod::kYamauchi;
}

fs::path out_dir(const PlanOptions& o) {
  if (!o.out.empty()) return o.out;
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fs::path("results") / fmt::format("plan-{:%Y%m%d-%H%M%S}", fmt::localtime(now));
}

double yaw_deg(const Eigen::Isometry3d& T) {
  return roll_pitch_yaw(T.linear()).z() * 180.0 / std::numbers::pi;
}

/// The pose as `--pose` takes it: x,y,z,roll,pitch,yaw (m, deg).
std::string pose_argument(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.linear()) * (180.0 / std::numbers::pi);
  return fmt::format("{:.4f},{:.4f},{:.4f},{:.3f},{:.3f},{:.3f}", t.x(), t.y(), t.z(), rpy.x(),
                     rpy.y(), rpy.z());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

json pose_json(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{"position", {T.translation().x(), T.translation().y(), T.translation().z()}},
          {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

SensorFov fov_from_options(const PlanOptions& o) {
  const auto fov = parse_numbers(o.fov_deg, "--fov-deg");
  const auto range = parse_numbers(o.range, "--range");
  if (fov.size() != 2) throw UsageError("--fov-deg takes two numbers: h,v");
  if (range.size() != 2) throw UsageError("--range takes two numbers: min,max");
  SensorFov result{deg2rad(fov[0]), deg2rad(fov[1]), range[0], range[1]};
  try {
    result.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--fov-deg/--range: {}", e.what()));
  }
  return result;
}

/// Four level views (yaw 0, 90, 180, 270 degrees) at the centroid of every frontier region.
std::vector<Eigen::Isometry3d> frontier_poses(const OccupancyGrid& grid) {
  std::vector<Eigen::Isometry3d> poses;
  for (const FrontierRegion& region : frontier_regions(grid, FrontierConfig{})) {
    for (int k = 0; k < 4; ++k) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::AngleAxisd(k * std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ())
                          .toRotationMatrix();
      pose.translation() = region.centroid;
      poses.push_back(pose);
    }
  }
  if (poses.empty()) throw std::runtime_error("the map has no frontier regions to plan from");
  return poses;
}

std::vector<Eigen::Isometry3d> candidate_poses(const PlanOptions& o, const Eigen::AlignedBox3d& roi,
                                               CloudFrame frame, const OccupancyGrid& grid) {
  const Eigen::Vector3d center = roi.center();
  const double half_diagonal = 0.5 * roi.sizes().head<2>().norm();
  if (o.candidates == "ring") {
    RingConfig ring;
    ring.center = center;
    ring.radius = o.radius > 0.0 ? o.radius : std::max(1.0, 1.5 * half_diagonal);
    ring.height = std::isnan(o.height) ? roi.max().z() + 0.3 : o.height;
    ring.positions = o.views > 0 ? o.views : 10;
    return ring_poses(ring);
  }
  if (o.candidates == "sphere") {
    SphereConfig sphere;
    sphere.center = center;
    sphere.radius = o.radius > 0.0 ? o.radius : std::max(1.0, 2.0 * half_diagonal);
    sphere.views = o.views > 0 ? o.views : 50;
    return sphere_poses(sphere);
  }
  if (o.candidates == "frontier") return frontier_poses(grid);
  return read_candidate_poses(o.candidates, frame);  // run() checked that the file exists
}

void run(const PlanOptions& o) {
  if (o.input.empty() && o.map.empty()) {
    throw std::invalid_argument("give a manifest or data folder, or --map FILE.bt|.ot, or both");
  }
  // NOTE: everything the command line alone can refuse is refused before any mapping.
  if (o.planning.alpha_setting().automatic) {
    // NOTE: auto fits a to a run's own predictions and outcomes, scan after scan; one decision
    // from recorded clouds has none to fit to.
    throw std::invalid_argument(
        "--alpha auto fits a over an exploration's scans (explore, bench); plan takes a number");
  }
  PlannerConfig planner = o.planning.planner_config();
  planner.greedy_reference = true;
  // NOTE: the pruned search's choice is the exhaustive exact one's, proven; the candidates it
  // never evaluated are listed with their upper bounds, marked as estimates.
  planner.search = DecisionSearch::kPruned;
  const PlanUnits units = units_of(planner.method);
  const fs::path dir = out_dir(o);
  if (fs::exists(dir) && !fs::is_empty(dir)) {
    throw std::invalid_argument(fmt::format("--out {} exists and is not empty", dir.string()));
  }
  std::optional<Eigen::Isometry3d> robot;
  std::string robot_source;
  if (!o.pose.empty()) {
    robot = parse_pose(o.pose, "--pose");
    robot_source = "--pose";
  } else if (needs_pose(planner.method) && o.input.empty()) {
    throw std::invalid_argument(
        fmt::format("--method {} weighs travel and needs the robot's pose: give --pose "
                    "x,y,z,roll,pitch,yaw or a manifest (its last cloud's pose is used)",
                    to_string(planner.method)));
  }

  if (o.input.empty()) fov_from_options(o);  // throws for a bad --fov-deg or --range
  const bool named_candidates =
      o.candidates == "ring" || o.candidates == "sphere" || o.candidates == "frontier";
  if (!named_candidates && !fs::exists(o.candidates)) {
    throw std::invalid_argument(
        fmt::format("--candidates '{}' is neither ring, sphere, frontier nor an existing pose file",
                    o.candidates));
  }

  const auto start = std::chrono::steady_clock::now();
  std::optional<Manifest> manifest;
  if (!o.input.empty()) manifest = read_manifest(o.input);
  const SensorFov fov = manifest ? manifest->fov : fov_from_options(o);
  const CloudFrame frame = manifest ? manifest->frame : CloudFrame::kOptical;

  MapperConfig mapper_config = manifest ? mapper_config_for(*manifest) : MapperConfig{};
  mapper_config.integration.num_threads = o.planning.threads;
  // NOTE: plan needs no object cloud; without it, memory stays bounded however many clouds come.
  mapper_config.keep_object_cloud = false;

  // Refused before any work: a grid too large for memory, or one whose map cannot be written.
  auto check_grid = [&](const GridSpec& spec, const std::string& source) {
    check_memory({spec.num_cells(), grid_bytes_per_cell(o.planning.threads), kFixedRunBytes},
                 o.max_memory,
                 fmt::format("the grid of {} ({} x {} x {} cells)", source, spec.dims.x(),
                             spec.dims.y(), spec.dims.z()));
    require_octomap_range(spec, source);
  };
  if (manifest) check_grid(manifest->grid, manifest->file.string());

  std::optional<Mapper> mapper;
  if (!o.map.empty()) {
    OctomapImportConfig import;
    if (manifest) import.grid = manifest->grid;
    import.crop = manifest.has_value();
    // NOTE: a derived grid is checked before it is allocated (docs/fuzzing.md, the OctoMap
    // finding); a manifest's was checked above.
    if (!manifest) import.check_grid = [&](const GridSpec& spec) { check_grid(spec, o.map);
  };
  OctomapImport imported = read_octomap(o.map, import);
  mapper.emplace(std::move(imported.grid), mapper_config);
}
else {
  mapper.emplace(manifest->grid, mapper_config);
}
if (!o.map.empty() && manifest && mapper_config.register_scans && !o.json_only) {
  fmt::print(
      "note: {} holds no points, so ICP registers the manifest's clouds to each other "
      "only\n",
      o.map);
}
if (manifest) {
  map_recorded(*manifest, *mapper, [&](std::size_t i, const MapperUpdate& u) {
    // NOTE: the pose the cloud was integrated at (ICP-corrected), wherever it came from.
    if (o.pose.empty()) {
      robot = u.T_world_sensor;
      robot_source = "the last cloud's pose";
    }
    if (u.object_points > 0 && u.integration.points_inside == 0) {
      // NOTE: a warning, not an error: the frustum's free space was still mapped, and a later
      // cloud may map the region.
      warn(fmt::format(
          "{}: nothing was mapped from its points: none of the {} lies inside the roi (behind "
          "the sensor, or far from the roi? check the pose, frame and roi)",
          manifest->clouds[i].file.string(), u.object_points));
    }
    if (!o.json_only) {
      fmt::print("cloud {}/{}  {}  {} points  {} cells seen{}{}\n", i + 1, manifest->clouds.size(),
                 manifest->clouds[i].file.filename().string(), u.points,
                 u.integration.left_unobserved.size(),
                 manifest->clouds[i].pose_from_viewpoint ? "  (pose from its VIEWPOINT)" : "",
                 mapper_config.register_scans
                     ? (u.registered ? "  (ICP corrected)" : "  (ICP kept the pose)")
                     : "");
    }
  });
}
const double map_seconds = seconds_since(start);
const OccupancyGrid& grid = mapper->grid();
const GridSpec& spec = grid.spec();
const Eigen::AlignedBox3d roi =
    manifest ? manifest->roi : Eigen::AlignedBox3d(spec.origin, spec.max_corner());

if (needs_pose(planner.method) && !robot) {
  throw std::invalid_argument(
      fmt::format("--method {} needs the robot's pose: the manifest has no clouds; give --pose",
                  to_string(planner.method)));
}

const std::vector<Eigen::Isometry3d> poses = candidate_poses(o, roi, frame, grid);
std::vector<Candidate> candidates;
for (const Eigen::Isometry3d& pose : poses) {
  // NOTE: plan knows no obstacles between here and there: travel is the straight line.
  const double travel = robot ? (pose.translation() - robot->translation()).norm() : 0.0;
  candidates.push_back({Frustum(pose, fov), travel});
}
const Plan plan = plan_next_view(grid, candidates, planner, /*seed=*/1);

// Best first (for random, the drawn one), then by score; ties keep the candidates' order.
std::vector<std::size_t> ranking(candidates.size());
std::iota(ranking.begin(), ranking.end(), std::size_t{0});
std::stable_sort(ranking.begin(), ranking.end(),
                 [&](std::size_t a, std::size_t b) { return plan.scores[a] > plan.scores[b]; });
const auto best = std::find(ranking.begin(), ranking.end(), plan.best);
std::rotate(ranking.begin(), best, best + 1);

const CellCounts counts = grid.counts();
const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(frame).transpose();
auto nbv = [&](std::size_t i) {
  Eigen::Isometry3d T_world_cloud = poses[i];
  T_world_cloud.linear() = poses[i].linear() * R_sensor_cloud;
  json j = {{"index", i},
            {"sensor", pose_json(poses[i])},
            {"yaw", yaw_deg(poses[i])},
            {"cloud_frame", pose_json(T_world_cloud)},
            {"predicted_gain", plan.gains[i].gain},
            {"predicted_cells", plan.gains[i].cells},
            {"greedy_gain", plan.greedy_gains[i]},
            {"score", plan.scores[i]}};
  if (robot) j["travel"] = candidates[i].travel;
  return j;
};
json out = {{"version", kPlanJsonVersion},
            {"vantage_version", VANTAGE_VERSION},
            {"units",
             {{"position", "m"},
              {"yaw", "deg"},
              {"predicted_gain", units.predicted_gain},
              {"predicted_cells", "cells"},
              {"greedy_gain", "cells"},
              {"score", units.score},
              {"travel", "m"},
              {"seconds", "s"}}},
            {"robot", robot ? json{{"sensor", pose_json(*robot)}, {"from", robot_source}} : json()},
            {"next_best_view", nbv(plan.best)},
            {"method", to_string(planner.method)},
            {"alpha", planner.gain.alpha},
            {"objective", to_string(planner.objective)},
            {"evaluation", to_string(planner.gain.evaluation)},
            {"frames", {{"sensor", "x forward, y left, z up"}, {"cloud_frame", to_string(frame)}}},
            {"map",
             {{"grid",
               {{"origin", {spec.origin.x(), spec.origin.y(), spec.origin.z()}},
                {"resolution", spec.resolution},
                {"dims", {spec.dims.x(), spec.dims.y(), spec.dims.z()}}}},
              {"clouds", manifest ? manifest->clouds.size() : 0},
              {"unobserved", counts.unobserved},
              {"free", counts.free},
              {"occupied", counts.occupied}}},
            {"candidates", json::array()},
            {"seconds", {{"map", map_seconds}, {"plan", plan.seconds}}}};
for (const std::size_t i : ranking) out["candidates"].push_back(nbv(i));

write_folder_atomically(dir, [&](const fs::path& partial) {
  write_atomically(partial / "plan.json", out.dump(2) + "\n");
  write_map_files(partial, grid);
  write_cells_ply(partial / "map.ply", grid);
  if (o.plots) run_plot_script("plot_run.py", {partial.string()});
});

if (o.json_only) {
  fmt::print("{}\n", out.dump(2));
  return;
}
const bool show_score =
    planner.method == PlannerMethod::kLatombe || planner.method == PlannerMethod::kYamauchi;
// NOTE: the probabilistic method also predicts in cells (E, docs/model.md), the number its
// prediction error is measured in; greedy's gain already is a count of cells.
const bool show_cells = has_observability(planner.method);
const std::string gain_header = fmt::format("predicted gain [{}]", units.predicted_gain);
const std::string cells_header = "predicted seen [cells]";
const std::string score_header = fmt::format("score [{}]", units.score);
fmt::print("\n{:>4} {:>5} {:>26} {:>9} {:>{}}{} {:>19}{}{}\n", "rank", "view", "position [m]",
           "yaw [deg]", gain_header, gain_header.size(),
           show_cells ? fmt::format(" {}", cells_header) : "", "greedy gain [cells]",
           robot ? fmt::format(" {:>10}", "travel [m]") : "",
           show_score ? fmt::format(" {:>{}}", score_header, score_header.size()) : "");
for (std::size_t r = 0; r < ranking.size() && r < static_cast<std::size_t>(o.top); ++r) {
  const std::size_t i = ranking[r];
  const Eigen::Vector3d p = poses[i].translation();
  fmt::print("{:>4} {:>5} {:>26} {:>9.1f} {:>{}.1f}{} {:>19.1f}{}{}\n", r + 1, i,
             fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z()), yaw_deg(poses[i]),
             plan.gains[i].gain, gain_header.size(),
             show_cells ? fmt::format(" {:>{}.1f}", plan.gains[i].cells, cells_header.size()) : "",
             plan.greedy_gains[i], robot ? fmt::format(" {:>10.3f}", candidates[i].travel) : "",
             show_score ? fmt::format(" {:>{}.3f}", plan.scores[i], score_header.size()) : "");
}
fmt::print(
    "\nnext best view: candidate {} ({} method{}), decided in {:.3f} s\n"
    "  at {}\n  as --pose: {}\n",
    plan.best, to_string(planner.method),
    has_observability(planner.method) ? fmt::format(", a = {}", planner.gain.alpha) : "",
    plan.seconds, describe_pose(poses[plan.best]), pose_argument(poses[plan.best]));
if (robot) fmt::print("robot at {} ({})\n", describe_pose(*robot), robot_source);
fmt::print("map: {} unobserved, {} free, {} occupied cells\nresults: {}/plan.json, map.ot{}\n",
           counts.unobserved, counts.free, counts.occupied, dir.string(),
           o.plots ? ", map.png" : "");
}  // namespace

}  // namespace vantage::cli

void add_plan_command(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Real scans in, next view out: map recorded clouds and choose the next best view");
  cmd->add_option("input", o->input, "manifest YAML, or a folder holding manifest.yaml");
  cmd->add_option("--map", o->map, "start from this OctoMap (.bt or .ot)");
  cmd->add_option("--candidates,-c", o->candidates,
                  "ring, sphere, frontier (4 level views at each frontier region's "
                  "centroid), or a TUM-format file of candidate poses")
      ->capture_default_str();
  cmd->add_option("--radius", o->radius, "ring/sphere radius [m] (default: from the ROI)")
      ->check(number_in(0.0, kMaxWorldCoordinate, /*open_low=*/true));
  cmd->add_option("--height", o->height, "ring height [m] (default: 0.3 m above the ROI)")
      ->check(number_in(-kMaxWorldCoordinate, kMaxWorldCoordinate));
  cmd->add_option("--views", o->views, "ring positions (x3 yaw offsets) or sphere views")
      ->check(whole_in(1, kMaxIndex));
  cmd->add_option("--fov-deg", o->fov_deg, "h,v field of view without a manifest [deg]")
      ->capture_default_str();
  cmd->add_option("--range", o->range, "min,max range without a manifest [m]")
      ->capture_default_str();
  o->planning.method = "survival";
  o->planning.add_to(*cmd, /*search=*/false);
  cmd->add_option("--pose", o->pose,
                  "the robot's sensor pose now, x,y,z,roll,pitch,yaw [m, deg], for the travel of "
                  "latombe and yamauchi (default: the manifest's last cloud's pose)");
  cmd->add_option("--out,-o", o->out, "results folder (default: a fresh folder under results/)");
  cmd->add_flag("--json", o->json_only, "print only plan.json, for other programs");
  cmd->add_flag("!--no-plots", o->plots, "skip the picture (map.png)");
  add_memory_option(*cmd, o->max_memory);
  cmd->add_option("--top", o->top, "rows of the ranked table")
      ->check(whole_in(1, kMaxIndex))
      ->capture_default_str();
  cmd->footer(
      "Units: the probabilistic method's predicted gain is information in bits (eq. 4: an "
      "unobserved cell holds 1 bit, a view turning it known is credited less) and its predicted "
      "seen is the expected number of unobserved cells the view sees [cells]; greedy, random "
      "and latombe count cells (latombe's score: greedy gain x exp(-lambda x travel)); yamauchi "
      "scores minus the travel [m]. Travel is the straight line from --pose [m]. Writes "
      "plan.json, map.ot (lossless, for --map), map.bt (viewers), map.ply (occupied red, "
      "unobserved yellow) and map.png.");
  cmd->callback([o] { run(*o); });
}

}  // namespace vantage::cli
