/// `vantage plan`: real scans in, next view out. Maps a robot's clouds (a manifest, see
/// docs/manifest.md) and/or an existing OctoMap, scores candidate views, and answers with the
/// next best view as a ranked table, plan.json, the updated map (map.ot, lossless: the next
/// `plan --map` continues from it exactly) and a picture.

#include "commands/plan.hpp"

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
#include "vantage/experiment/results.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/map_files.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/io/ply_export.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/views/candidate_sets.hpp"
#include "vantage/views/frontier.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path out_dir(const PlanOptions& o) {
  if (!o.out.empty()) return o.out;
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fs::path("results") / fmt::format("plan-{:%Y%m%d-%H%M%S}", fmt::localtime(now));
}

/// The ICP column of a cloud's line.
std::string registration_note(const RecordedCloud& c, bool icp, bool first, bool unposed) {
  if (unposed) return "  (pose from registration to the map so far)";
  if (!icp) return "";
  if (c.update.registered) return "  (ICP corrected)";
  // NOTE: the first cloud of a map defines its frame; there is nothing to register it against.
  if (first) return "  (first cloud: nothing to register against)";
  return "  (ICP kept the pose)";
}

/// The segmentation column of a cloud's line: whether the table was found, what it removed.
std::string segmentation_note(const RecordedCloud& c) {
  const MapperUpdate& u = c.update;
  if (u.table_views == 0) return "  table: none found";
  return fmt::format("  table: found, {} of {} points removed", u.thinned_points - u.object_points,
                     u.thinned_points);
}

/// The manifest of a recording alone (issue 53): `plan FILE.bag --topic T`, its region and
/// resolution from --roi and --resolution or derived (manifest_for_recording), said in one line.
Manifest recording_alone(const PlanOptions& o) {
  RecordingAloneOptions read;
  read.read.topic = o.topic;
  if (o.every > 0) read.read.every = o.every;
  read.read.salvage = o.salvage;
  if (!o.roi.empty()) {
    const std::vector<double> v = parse_numbers(o.roi, "--roi");
    if (v.size() != 6) throw UsageError("--roi takes six numbers: xmin,ymin,zmin,xmax,ymax,zmax");
    for (int a = 0; a < 3; ++a) {
      if (!(v[a] < v[a + 3]) || std::abs(v[a]) > kMaxWorldCoordinate ||
          std::abs(v[a + 3]) > kMaxWorldCoordinate) {
        throw UsageError(fmt::format(
            "--roi: each min must lie below its max, within {} m of 0 (got {} and {} on axis {})",
            kMaxWorldCoordinate, v[a], v[a + 3], "xyz"[a]));
      }
    }
    read.roi =
        Eigen::AlignedBox3d(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
  }
  if (o.resolution > 0.0) read.resolution = o.resolution;
  Manifest m = manifest_for_recording(o.input, read);
  if (!o.json_only) {
    const Eigen::Vector3d a = m.roi.min(), b = m.roi.max();
    fmt::print(
        "recording alone: sensor {:.1f} x {:.1f} deg, {}-{} m ({}, frame {}); roi ({:.4g}, "
        "{:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g}) m ({}); resolution {} m ({}); a manifest "
        "says more (docs/manifest.md)\n",
        m.fov.h_fov * 180.0 / std::numbers::pi, m.fov.v_fov * 180.0 / std::numbers::pi,
        m.fov.min_range, m.fov.max_range,
        m.intrinsics ? "from CameraInfo, its range the points'" : "from the points",
        to_string(m.frame), a.x(), a.y(), a.z(), b.x(), b.y(), b.z(),
        o.roi.empty() ? "the frames' extent" : "--roi", m.grid.resolution,
        o.resolution > 0.0 ? "--resolution" : "for the sensor's range");
  }
  return m;
}

void run(const PlanOptions& o) {
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
  const GainUnits units = gain_units(planner);
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
  std::optional<Eigen::Isometry3d> robot;
  std::string robot_source;
  if (!o.pose.empty()) {
    robot = parse_pose(o.pose, "--pose");
    robot_source = "--pose";
  } else if (uses_travel(planner.method) && o.input.empty()) {
    throw UsageError(
        fmt::format("--method {} weighs travel and needs the robot's pose: give --pose "
                    "x,y,z,roll,pitch,yaw or a manifest (its last cloud's pose is used)",
                    to_string(planner.method)));
  }

  if (o.input.empty()) fov_from_options(o);  // throws for a bad --fov-deg or --range
  const bool named_candidates = !names_pose_file(o);
  if (named_candidates && find_candidate_set(o.candidates).needs_robot) {
    throw UsageError(fmt::format(
        "--candidates {}: an office robot's stops, which explore builds as it drives; plan from a "
        "map with frontier",
        o.candidates));
  }
  if (!named_candidates) {
    // NOTE: a folder or a missing file is bad input, exit 1, as --map's (issue 53).
    std::error_code error;
    if (fs::is_directory(o.candidates, error)) {
      throw std::runtime_error(
          fmt::format("--candidates '{}' is a folder: give one of {} or a pose file (TUM format)",
                      o.candidates, candidate_set_names()));
    }
    if (!fs::exists(o.candidates, error)) {
      throw std::runtime_error(
          fmt::format("--candidates '{}' is neither one of {} nor an existing pose file",
                      o.candidates, candidate_set_names()));
    }
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
  const auto start = std::chrono::steady_clock::now();
  std::optional<Manifest> manifest;
  if ((o.every > 0 || !o.topic.empty()) && o.input.empty()) {
    throw UsageError(
        "--every and --topic choose frames of a TUM folder or a recording: give its manifest");
  }
  // NOTE: a recording alone plans without a manifest (issue 53): its sensor, region and
  // resolution derived, or the region and resolution from the command line.
  const std::string input_ext = lower_extension(o.input);
  const bool alone = input_ext == ".bag" || input_ext == ".mcap";
  if ((!o.roi.empty() || o.resolution > 0.0) && !alone) {
    throw UsageError(
        "--roi and --resolution set a recording's region and cells when it comes alone (FILE.bag "
        "or FILE.mcap); a manifest gives its own (roi, resolution)");
  }
  if (alone && o.topic.empty()) {
    throw UsageError(fmt::format(
        "a recording alone needs --topic: its sensor_msgs/PointCloud2 or depth sensor_msgs/Image "
        "topic (vantage plan {} --topic /camera/depth/points)",
        o.input));
  }
  if (alone) manifest = recording_alone(o);
  if (!o.input.empty() && !alone) {
    ManifestReadOptions read;
    if (o.every > 0) read.every = o.every;
    if (!o.topic.empty()) read.topic = o.topic;
    read.salvage = o.salvage;
    manifest = read_manifest(o.input, read);
  }
  if (manifest) {
    if (const auto& s = manifest->salvage) {
      // NOTE: one line, said whatever --json (plan.json records it too, "salvage").
      warn(
          fmt::format("{}: damaged; mapped the {} whole frame(s) before byte {} and dropped {}: {}",
                      manifest->recording->string(), s->frames, s->offset,
                      s->dropped ? fmt::format("the {} its index counts after them", *s->dropped)
                                 : std::string("the rest (its index is lost with it)"),
                      s->damage));
    }
  }
  const SensorFov fov = manifest ? manifest->fov : fov_from_options(o);
  const CloudFrame frame = manifest ? manifest->frame : CloudFrame::kOptical;
  if (!manifest && !o.json_only) {
    fmt::print("sensor: {:.1f} x {:.1f} deg, {}-{} m{}\n", fov.h_fov * 180.0 / std::numbers::pi,
               fov.v_fov * 180.0 / std::numbers::pi, fov.min_range, fov.max_range,
               o.sensor_given ? " (--fov-deg, --range)"
                              : " (assumed: the --fov-deg and --range defaults, a Kinect's)");
  }

  MapperConfig mapper_config = manifest ? mapper_config_for(*manifest) : MapperConfig{};
  mapper_config.integration.num_threads = o.planning.threads;
  // NOTE: plan needs no object cloud; without it, memory stays bounded however many clouds come.
  mapper_config.keep_object_cloud = false;

  // Refused before any work: a grid too large for memory, or one whose map cannot be written,
  // and a decision the work budget does not allow (its views known from the grid's box or the
  // manifest's roi, all but frontier views).
  const WorkBudget budget = work_budget(o.max_work, o.max_memory);
  auto check_grid = [&](const GridSpec& spec, const std::string& source) {
    check_memory({spec.num_cells(), grid_bytes_per_cell(o.planning.threads), kFixedRunBytes},
                 o.max_memory,
                 fmt::format("the grid of {} ({} x {} x {} cells)", source, spec.dims.x(),
                             spec.dims.y(), spec.dims.z()));
    require_octomap_range(spec, source);
    const auto box = manifest ? manifest->roi : Eigen::AlignedBox3d(spec.origin, spec.max_corner());
    if (const auto poses = planned_poses(o, box, frame)) {
      // NOTE: the least the decision can cost whatever the map (no cell unobserved); the map's
      // own share is weighed once it is built.
      check_decision_budget(estimate_decision(spec, *poses, fov, planner, /*unobserved=*/0.0),
                            budget, spec.num_cells(), o.planning.threads);
    }
  };
  if (manifest) check_grid(manifest->grid, manifest->file.string());

  std::optional<Mapper> mapper;
  if (!o.map.empty()) {
    OctomapImportConfig settings;
    if (manifest) settings.grid = manifest->grid;
    settings.crop = manifest.has_value();
    // NOTE: a derived grid is checked before it is allocated (docs/fuzzing.md, the OctoMap
    // finding); a manifest's was checked above.
    if (!manifest) {
      settings.check_grid = [&](const GridSpec& spec) { check_grid(spec, o.map); };
    }
    OctomapImport imported = read_octomap(o.map, settings);
    const GridSpec& loaded = imported.grid.spec();
    if (!o.json_only) {
      fmt::print(
          "map: {} ({} {}, {} known voxels) into {} grid of {} x {} x {} cells at {} m from "
          "({:.4g}, {:.4g}, {:.4g})\n",
          o.map, to_string(imported.format), imported.tree_type, imported.known_voxels,
          manifest ? "the manifest's" : "its own", loaded.dims.x(), loaded.dims.y(),
          loaded.dims.z(), loaded.resolution, loaded.origin.x(), loaded.origin.y(),
          loaded.origin.z());
    }
    if (imported.cropped_voxels > 0) {
      // NOTE: a map from another grid keeps what lies inside the manifest's; what it drops is
      // said, never silent.
      warn(fmt::format(
          "{}: dropped {} of its {} known voxels, which lie outside the manifest's grid (its roi)",
          o.map, imported.cropped_voxels, imported.cropped_voxels + imported.known_voxels));
    }
    mapper.emplace(std::move(imported.grid), mapper_config);
  } else {
    mapper.emplace(manifest->grid, mapper_config);
  }
  if (!o.map.empty() && manifest && mapper_config.register_scans && !o.json_only) {
    fmt::print(
        "note: {} holds no points, so ICP registers the manifest's clouds to each other "
        "only\n",
        o.map);
  }
  if (manifest) {
    map_recorded(*manifest, *mapper, [&](const RecordedCloud& c) {
      const std::size_t i = c.index;
      const MapperUpdate& u = c.update;
      const ManifestCloud& cloud = manifest->clouds[i];
      // NOTE: the pose the cloud was integrated at (ICP-corrected), wherever it came from.
      if (o.pose.empty()) {
        robot = u.T_world_sensor;
        robot_source =
            c.table_pose ? "the last cloud's pose, from the table" : "the last cloud's pose";
      }
      if (mapper_config.segment_table && u.table_views == 0 && u.thinned_points > 0) {
        warn(fmt::format(
            "{}: table segmentation found no table, so nothing was mapped from its {} points "
            "(check the pose's up axis, or set options.table_segmentation: false)",
            cloud.file.string(), u.points));
      } else if (u.object_points > 0 && u.integration.points_inside == 0) {
        // NOTE: a warning, not an error: the frustum's free space was still mapped, and a later
        // cloud may map the region.
        warn(fmt::format(
            "{}: nothing was mapped from its points: none of the {} lies inside the roi (behind "
            "the sensor, or far from the roi? check the pose, frame and roi)",
            cloud.file.string(), u.object_points));
      }
      if (o.json_only) return;
      fmt::print("cloud {}/{}  {}  {} points{}  {} cells seen{}{}{}{}\n", i + 1,
                 manifest->clouds.size(), cloud.file.filename().string(), u.points,
                 c.non_finite_skipped > 0
                     ? fmt::format(" ({} non-finite skipped)", c.non_finite_skipped)
                     : "",
                 u.integration.left_unobserved.size(),
                 cloud.pose_from_viewpoint ? "  (pose from its VIEWPOINT)" : "",
                 c.table_pose ? "  (pose from the table)" : "",
                 mapper_config.segment_table ? segmentation_note(c) : "",
                 registration_note(c, mapper_config.register_scans, mapper->scans() == 1,
                                   cloud.pose_from_registration));
      if (c.table_pose) {
        const perception::TablePose& t = *c.table_pose;
        fmt::print(
            "  pose from the table: the sensor {:.3f} m above the table's top (z = {} m), "
            "looking {:.1f} deg below level; the table's objects above the origin, x along the "
            "view\n  at {}\n  as --pose: {}\n",
            t.height_above_table, manifest->options.table_height,
            unsigned_zero(t.tilt * 180.0 / std::numbers::pi, 1), describe_pose(t.T_world_sensor),
            pose_argument(t.T_world_sensor));
      }
    });
  }
  const double map_seconds = seconds_since(start);
  const OccupancyGrid& grid = mapper->grid();
  const GridSpec& spec = grid.spec();
  const Eigen::AlignedBox3d roi =
      manifest ? manifest->roi : Eigen::AlignedBox3d(spec.origin, spec.max_corner());

  if (uses_travel(planner.method) && !robot) {
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
  const DecisionCost cost = estimate_decision(spec, candidates, planner, unobserved_share(grid));
  check_decision_budget(cost, budget, spec.num_cells(), o.planning.threads);
  const Plan plan = plan_next_view(grid, candidates, planner, /*seed=*/1);
  report_plan({o, plan, planner, units, candidates, poses, robot, robot_source, grid, frame, fov,
               manifest ? manifest->clouds.size() : 0, map_seconds, dir, cost.seconds(),
               manifest && manifest->salvage ? &*manifest->salvage : nullptr});
}

}  // namespace

void add_plan_command(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Real scans in, next view out: map recorded clouds and choose the next best view");
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
