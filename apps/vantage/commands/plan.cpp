/// `vantage plan`: real scans in, next view out. Maps a robot's clouds (a manifest, see
/// docs/manifest.md) and/or an existing OctoMap, scores candidate views, and answers with the
/// next best view as a ranked table, plan.json, the updated map (map.ot, lossless: the next
/// `plan --map` continues from it exactly) and a picture.

#include "commands/plan.hpp"

#include <fmt/chrono.h>
#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/views/candidate_sets.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;

fs::path out_dir(const PlanOptions& o) {
  if (!o.out.empty()) return o.out;
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fs::path("results") / fmt::format("plan-{:%Y%m%d-%H%M%S}", fmt::localtime(now));
}

/// The decision's settings from the options, refused first what the command line alone can
/// refuse.
PlannerConfig planner_of(const PlanOptions& o) {
  if (o.input.empty() && o.map.empty()) {
    throw UsageError("give a manifest or data folder, or --map FILE.bt|.ot, or both");
  }
  // NOTE: everything the command line alone can refuse is refused before any mapping.
  if (o.planning.alpha_setting().automatic) {
    // NOTE: auto fits a to a run's own predictions and outcomes, scan after scan; one decision
    // from recorded clouds has none to fit to.
    throw UsageError(
        "--alpha auto fits a over an exploration's scans (explore, bench); plan takes a number");
  }
  if (o.planning.method == "greedy-oracle") {
    // NOTE: plan --help lists explore's and bench's methods too; the oracle's is not "unknown".
    throw UsageError(
        "--method greedy-oracle needs the world's truth, which only a simulated table top has "
        "(explore, bench); plan maps real scans: give a planner method");
  }
  // NOTE: the default planner weighs travel from the robot's pose: --pose, or a manifest's last
  // cloud's.
  PlanningOptions planning = o.planning;
  planning.task = o.candidates == "frontier" ? ViewTask::kExploration : ViewTask::kObjects;
  planning.knows_pose = !o.pose.empty() || !o.input.empty();
  PlannerConfig planner = planning.planner_config();
  planner.predict_chosen = o.predict;
  request_plan_reference(planner);
  return planner;
}

/// The results folder, refused when it holds anything; --sensor-height and --map's format
/// checked.
fs::path checked_out_dir(const PlanOptions& o) {
  if (!o.sensor_height.empty() && o.candidates != "frontier") {
    throw UsageError("--sensor-height places frontier candidates: give --candidates frontier");
  }
  (void)sensor_band(o);  // throws for a bad --sensor-height
  const fs::path dir = out_dir(o);
  if (fs::exists(dir) && !fs::is_empty(dir)) {
    throw std::invalid_argument(fmt::format("--out {} exists and is not empty", dir.string()));
  }
  if (!o.map.empty()) {
    try {
      (void)octomap_format_of(o.map);  // the flag's format, decided before any file is read
    } catch (const std::invalid_argument& e) {
      throw UsageError(fmt::format("--map: {}", e.what()));
    }
  }
  return dir;
}

/// --pose, or none; a method that weighs travel without --pose needs a manifest's clouds.
RobotPose robot_of(const PlanOptions& o, const PlannerConfig& planner) {
  if (!o.pose.empty()) return {parse_pose(o.pose, "--pose"), "--pose"};
  if (uses_travel(planner.method) && o.input.empty()) {
    throw UsageError(
        fmt::format("--method {} weighs travel and needs the robot's pose: give --pose "
                    "x,y,z,roll,pitch,yaw or a manifest (its last cloud's pose is used)",
                    to_string(planner.method)));
  }
  return {};
}

/// Refuses a sensor without a manifest, candidates and views --candidates and --views cannot
/// make, before the map is built.
void check_candidate_options(const PlanOptions& o) {
  if (o.input.empty()) fov_from_options(o);  // throws for a bad --fov-deg or --range
  const bool named_candidates = !names_pose_file(o);
  if (named_candidates && find_candidate_set(o.candidates).needs_robot) {
    throw UsageError(fmt::format(
        "--candidates {}: an office robot's stops, which explore builds as it drives; plan from a "
        "map with frontier",
        o.candidates));
  }
  std::error_code error;
  // NOTE: a folder or a missing file is bad input, exit 1, as --map's (issue 53).
  if (!named_candidates && fs::is_directory(o.candidates, error)) {
    throw std::runtime_error(
        fmt::format("--candidates '{}' is a folder: give one of {} or a pose file (TUM format)",
                    o.candidates, candidate_set_names()));
  }
  if (!named_candidates && !fs::exists(o.candidates, error)) {
    throw std::runtime_error(
        fmt::format("--candidates '{}' is neither one of {} nor an existing pose file",
                    o.candidates, candidate_set_names()));
  }
  // NOTE: the views --views makes are counted before the map is built (issue 39: a million ring
  // positions, 3 M views, ran out of memory after minutes of mapping).
  if (o.views > 0 &&
      (o.candidates == "ring" || o.candidates == "sphere" || o.candidates == "view-sphere")) {
    const std::uint64_t views = static_cast<std::uint64_t>(o.views) *
                                (o.candidates == "ring" ? RingConfig{}.yaw_offsets.size() : 1);
    if (views > kMaxCandidateViews) {
      throw UsageError(
          fmt::format("--views {} makes {} candidate views, more than the {} a "
                      "decision scores (docs/robustness.md, \"Limits\")",
                      o.views, views, kMaxCandidateViews));
    }
  }
  // NOTE: a pose file is opened as every input is, before the map is built: a FIFO, a device or
  // a file past its kind's size is refused here, not after the mapping.
  if (!named_candidates) {
    if (const std::string why = input_file_problem(o.candidates, InputKind::kPoses); !why.empty()) {
      throw std::runtime_error(fmt::format("--candidates {}: {}", o.candidates, why));
    }
  }
}

/// Chooses among the candidates on the map, within the work budget, and reports the plan.
void decide(const PlanRun& run, const OccupancyGrid& grid, double map_seconds) {
  const PlanOptions& o = run.o;
  const GridSpec& spec = grid.spec();
  const Eigen::AlignedBox3d roi =
      run.manifest ? run.manifest->roi : Eigen::AlignedBox3d(spec.origin, spec.max_corner());
  const std::optional<Eigen::Isometry3d>& robot = run.robot.pose;
  if (uses_travel(run.planner.method) && !robot) {
    throw std::invalid_argument(
        fmt::format("--method {} needs the robot's pose: the manifest has no clouds; give --pose",
                    to_string(run.planner.method)));
  }
  const std::vector<Eigen::Isometry3d> poses = candidate_poses(o, roi, run.frame, grid);
  std::vector<Candidate> candidates;
  for (const Eigen::Isometry3d& pose : poses) {
    // NOTE: plan knows no obstacles between here and there: travel is the straight line.
    const double travel = robot ? (pose.translation() - robot->translation()).norm() : 0.0;
    candidates.push_back({Frustum(pose, run.fov), travel});
  }
  const DecisionCost cost =
      estimate_decision(spec, candidates, run.planner, unobserved_share(grid));
  check_decision_budget(cost, work_budget(o.max_work, o.max_memory), spec.num_cells(),
                        o.planning.threads);
  const Plan plan = plan_next_view(grid, candidates, run.planner, /*seed=*/1);
  const GainUnits units = gain_units(run.planner);
  report_plan({o, plan, run.planner, units, candidates, poses, robot, run.robot.source, grid,
               run.frame, run.fov, run.manifest ? run.manifest->clouds.size() : 0, map_seconds,
               run.dir, cost.seconds(),
               run.manifest && run.manifest->salvage ? &*run.manifest->salvage : nullptr});
}

/// The command's steps: the command line checked, the input read and mapped, the decision.
void run(const PlanOptions& o) {
  PlanRun job{o, planner_of(o)};
  job.dir = checked_out_dir(o);
  job.robot = robot_of(o, job.planner);
  check_candidate_options(o);
  const auto start = std::chrono::steady_clock::now();
  read_input(job);
  const Mapper mapper = build_map(job);
  decide(job, mapper.grid(), seconds_since(start));
}

/// The options that say what to map: the input, a recording's frames and region, --map.
void add_input_options(CLI::App* cmd, PlanOptions* o) {
  cmd->add_option("input", o->input,
                  "manifest YAML, a folder holding manifest.yaml, or a recording alone (a ROS 1 "
                  "bag, an MCAP file) with --topic");
  cmd->add_option("--roi", o->roi,
                  "of a recording alone: the region xmin,ymin,zmin,xmax,ymax,zmax [m] (default: "
                  "the frames' extent)");
  cmd->add_option("--resolution", o->resolution,
                  "of a recording alone: the cells' edge [m] (default: a 200th of the sensor's "
                  "range, 0.01 m for a Kinect's)")
      ->check(number_in(0.0, kMaxWorldCoordinate, /*open_low=*/true));
  cmd->add_option("--map", o->map, "start from this OctoMap (.bt or .ot)");
  cmd->add_option("--every", o->every,
                  "of a TUM RGB-D folder's depth frames or a recording's (the manifest's tum or "
                  "recording), the first and every n-th after it")
      ->check(CLI::Range(1, 1'000'000));
  cmd->add_option("--topic", o->topic,
                  "the sensor_msgs/PointCloud2 or depth sensor_msgs/Image topic of a recording "
                  "alone, or of the manifest's recording (a ROS 1 bag or an MCAP file), in place "
                  "of its recording.topic");
  cmd->add_flag("--salvage", o->salvage,
                "of a damaged recording (cut short, a CRC or an index that does not match), map "
                "the whole frames before the damage, say how many it dropped and record it in "
                "plan.json (salvage), rather than refuse it");
}

}  // namespace

void add_plan_command(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Real scans in, next view out: map recorded clouds and choose the next best view");
  add_input_options(cmd, o.get());
  std::string sets;
  for (const CandidateSetRow& row : candidate_sets()) {
    if (!row.needs_list && !row.needs_robot) {
      sets += fmt::format("{} ({}), ", row.name, row.help);
    }
  }
  cmd->add_option("--candidates,-c", o->candidates,
                  sets + "or a TUM-format file of candidate poses")
      ->capture_default_str();
  cmd->add_option("--radius", o->radius,
                  "ring/sphere radius, the hemisphere's middle one [m] (default: from the ROI)")
      ->check(number_in(0.0, kMaxWorldCoordinate, /*open_low=*/true));
  cmd->add_option("--height", o->height, "ring height [m] (default: 0.3 m above the ROI)")
      ->check(number_in(-kMaxWorldCoordinate, kMaxWorldCoordinate));
  cmd->add_option("--sensor-height", o->sensor_height,
                  "frontier candidates: the robot's sensor height [m], h or a range min,max (a "
                  "ground robot's); frontier cells are taken in that band and each view placed "
                  "in it (default: any height)");
  cmd->add_option("--views", o->views,
                  "ring positions (x3 yaw offsets), sphere or view-sphere views")
      ->check(whole_in(1, kMaxIndex));
  cmd->add_option("--fov-deg", o->fov_deg, "h,v field of view without a manifest [deg]")
      ->capture_default_str();
  cmd->add_option("--range", o->range, "min,max range without a manifest [m]")
      ->capture_default_str();
  o->planning.add_to(*cmd);
  cmd->add_option("--pose", o->pose,
                  "the robot's sensor pose now, x,y,z,roll,pitch,yaw [m, deg], for the travel of "
                  "latombe and yamauchi (default: the manifest's last cloud's pose)");
  cmd->add_option("--out,-o", o->out, "results folder (default: a fresh folder under results/)");
  cmd->add_flag("--json", o->json_only, "print only plan.json, for other programs");
  cmd->add_flag("!--no-prediction", o->predict,
                "decide only: skip the chosen view's full prediction in bits, which follows the "
                "decision (plan.json: seconds.prediction) and on a large grid takes longer than "
                "it; its predicted_gain is then null, its cells the search's own");
  cmd->add_flag("!--no-plots", o->plots, "skip the picture (map.png)");
  add_memory_option(*cmd, o->max_memory);
  add_work_option(*cmd, o->max_work);
  cmd->add_option("--top", o->top, "rows of the ranked table")
      ->check(whole_in(1, kMaxIndex))
      ->capture_default_str();
  cmd->footer(
      "Units: the probabilistic method's predicted gain is information in bits (eq. 4: an "
      "unobserved cell holds 1 bit, a view turning it known is credited less) and its predicted "
      "seen is the expected number of unobserved cells the view sees [cells]; greedy, random "
      "and latombe count cells (latombe's score: greedy gain x exp(-lambda x travel)); yamauchi "
      "scores minus the travel [m]. The score column is what the method ranks by, in its unit "
      "(the survival reading: cells, --objective bits|cells); '~' marks an estimated gain, '-' a "
      "gain in bits that a decision by cells did not predict (plan.json: 0). Travel is the "
      "straight line from --pose [m]. Writes "
      "plan.json, map.ot (lossless, for --map), map.bt (viewers), map.ply (occupied red, "
      "unobserved yellow) and map.png.");
  cmd->callback([o, cmd] {
    o->sensor_given = cmd->count("--fov-deg") > 0 || cmd->count("--range") > 0;
    run(*o);
  });
}

}  // namespace vantage::cli
