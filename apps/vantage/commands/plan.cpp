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
#include "vantage/experiment/results.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/map_files.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/io/ply_export.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/views/frontier.hpp"
#include "vantage/views/hemisphere.hpp"
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
  std::string sensor_height;  // frontier candidates: H or MIN,MAX [m]; empty: any height
  int views = 0;              // 0: 10 ring positions / 50 sphere views
  std::string fov_deg = "57,43";
  std::string range = "0.5,3.5";
  bool sensor_given = false;  // --fov-deg or --range on the command line
  PlanningOptions planning;
  std::string pose;  // x,y,z,roll,pitch,yaw of the robot's sensor now
  std::string out;
  bool json_only = false;
  bool plots = true;
  int top = 10;
  std::uint64_t max_memory = 0;  // 0: what the machine has available
};

/// plan.json's format: 2 added version, units, the robot's pose, travel and yaw; 3 the sensor,
/// the clouds, units per objective and the estimated flag; 4 the search that decided, and the
/// candidates listed as Plan::ranking orders them.
constexpr int kPlanJsonVersion = 4;

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
  return fmt::format("{:.4f},{:.4f},{:.4f},{:.3f},{:.3f},{:.3f}", unsigned_zero(t.x(), 4),
                     unsigned_zero(t.y(), 4), unsigned_zero(t.z(), 4), unsigned_zero(rpy.x(), 3),
                     unsigned_zero(rpy.y(), 3), unsigned_zero(rpy.z(), 3));
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

/// --sensor-height: one height, or a range min,max [m].
std::optional<std::pair<double, double>> sensor_band(const PlanOptions& o) {
  if (o.sensor_height.empty()) return std::nullopt;
  const std::vector<double> v = parse_numbers(o.sensor_height, "--sensor-height");
  if (v.size() > 2) throw UsageError("--sensor-height takes a height or a range: h, or min,max");
  for (const double h : v) {
    if (!std::isfinite(h) || std::abs(h) > kMaxWorldCoordinate) {
      throw UsageError(
          fmt::format("--sensor-height: {} m is not a height within {} m", h, kMaxWorldCoordinate));
    }
  }
  const double lo = v.front(), hi = v.back();
  if (lo > hi) throw UsageError(fmt::format("--sensor-height: min {} exceeds max {}", lo, hi));
  return std::pair{lo, hi};
}

/// Frontier candidates with what was left out.
struct FrontierViews {
  std::vector<Eigen::Isometry3d> poses;
  std::size_t regions = 0;
  std::size_t dropped = 0;  ///< views whose place is not known free (unknown or occupied)
};

/// Four level views (yaw 0, 90, 180, 270 degrees) at the centroid of every frontier region; with
/// a sensor band, frontier cells are taken in the band (the layers holding min..max) and each
/// view is put at a height within it. A view whose place is not a known free cell is dropped:
/// a robot cannot stand in unknown or occupied space.
FrontierViews frontier_poses(const OccupancyGrid& grid,
                             const std::optional<std::pair<double, double>>& band) {
  FrontierConfig config;
  const double half = 0.5 * grid.spec().resolution;
  if (band) {
    config.min_z = band->first - half;
    config.max_z = band->second + half;
  }
  FrontierViews views;
  const std::vector<FrontierRegion> regions = frontier_regions(grid, config);
  views.regions = regions.size();
  for (const FrontierRegion& region : regions) {
    Eigen::Vector3d place = region.centroid;
    if (band) place.z() = std::clamp(place.z(), band->first, band->second);
    const std::optional<Index3> cell = grid.spec().find(place);
    if (!cell || grid.state(grid.spec().linear(*cell)) != CellState::kFree) {
      views.dropped += 4;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::AngleAxisd(k * std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ())
                          .toRotationMatrix();
      pose.translation() = place;
      views.poses.push_back(pose);
    }
  }
  if (views.poses.empty()) {
    throw std::runtime_error(
        regions.empty()
            ? std::string(band ? "the map has no frontier regions at --sensor-height to plan from"
                               : "the map has no frontier regions to plan from")
            : fmt::format("none of the {} frontier regions' centroids lies in a known free cell "
                          "(try --sensor-height)",
                          regions.size()));
  }
  return views;
}

std::vector<Eigen::Isometry3d> candidate_poses(const PlanOptions& o, const Eigen::AlignedBox3d& roi,
                                               CloudFrame frame, const OccupancyGrid& grid) {
  const Eigen::Vector3d center = roi.center();
  const double half_diagonal = 0.5 * roi.sizes().head<2>().norm();
  if (o.candidates == "ring") {
    RingConfig ring = default_ring(roi);  // the rule vt.ring_candidates shares
    if (o.radius > 0.0) ring.radius = o.radius;
    if (!std::isnan(o.height)) ring.height = o.height;
    if (o.views > 0) ring.positions = o.views;
    return ring_poses(ring);
  }
  if (o.candidates == "sphere") {
    SphereConfig sphere;
    sphere.center = center;
    sphere.radius = o.radius > 0.0 ? o.radius : std::max(1.0, 2.0 * half_diagonal);
    sphere.views = o.views > 0 ? o.views : 50;
    return sphere_poses(sphere);
  }
  if (o.candidates == "hemisphere") {
    // NOTE: an arm's views (issue 26): rings at 0.75, 1 and 1.25 times the ring's radius.
    HemisphereConfig hemisphere;
    hemisphere.center = center;
    const double radius = o.radius > 0.0 ? o.radius : default_ring(roi).radius;
    hemisphere.radii = {0.75 * radius, radius, 1.25 * radius};
    return hemisphere_poses(hemisphere);
  }
  if (o.candidates == "frontier") {
    const FrontierViews views = frontier_poses(grid, sensor_band(o));
    if (!o.json_only) {
      fmt::print("frontier: {} regions, {} views{}\n", views.regions, views.poses.size(),
                 views.dropped > 0
                     ? fmt::format(" ({} dropped: their place is not known free)", views.dropped)
                     : "");
    }
    return views.poses;
  }
  return read_candidate_poses(o.candidates, frame);  // run() checked that the file exists
}

/// The ICP column of a cloud's line.
std::string registration_note(const RecordedCloud& c, bool icp, bool first) {
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
  PlannerConfig planner = o.planning.planner_config();
  // NOTE: greedy's prediction on every candidate costs more than a swept decision itself.
  planner.greedy_reference =
      !sequence_of(planner).active() && resolve_search(planner) != DecisionSearch::kSwept;
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
  } else if (needs_pose(planner.method) && o.input.empty()) {
    throw UsageError(
        fmt::format("--method {} weighs travel and needs the robot's pose: give --pose "
                    "x,y,z,roll,pitch,yaw or a manifest (its last cloud's pose is used)",
                    to_string(planner.method)));
  }

  if (o.input.empty()) fov_from_options(o);  // throws for a bad --fov-deg or --range
  const bool named_candidates = o.candidates == "ring" || o.candidates == "sphere" ||
                                o.candidates == "hemisphere" || o.candidates == "frontier";
  if (!named_candidates) {
    std::error_code error;
    if (fs::is_directory(o.candidates, error)) {
      throw UsageError(fmt::format(
          "--candidates '{}' is a folder: give ring, sphere, hemisphere, frontier or a pose file "
          "(TUM format)",
          o.candidates));
    }
    if (!fs::exists(o.candidates, error)) {
      throw UsageError(fmt::format(
          "--candidates '{}' is neither ring, sphere, hemisphere, frontier nor an existing pose "
          "file",
          o.candidates));
    }
  }

  // NOTE: the views --views makes are counted before the map is built (issue 39: a million ring
  // positions, 3 M views, ran out of memory after minutes of mapping).
  if (o.views > 0 && (o.candidates == "ring" || o.candidates == "sphere")) {
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
  if (!o.input.empty()) manifest = read_manifest(o.input);
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
  const GridSpec& loaded = imported.grid.spec();
  if (!o.json_only) {
    fmt::print(
        "map: {} ({} {}, {} known voxels) into {} grid of {} x {} x {} cells at {} m from "
        "({:.4g}, {:.4g}, {:.4g})\n",
        o.map, to_string(imported.format), imported.tree_type, imported.known_voxels,
        manifest ? "the manifest's" : "its own", loaded.dims.x(), loaded.dims.y(), loaded.dims.z(),
        loaded.resolution, loaded.origin.x(), loaded.origin.y(), loaded.origin.z());
  }
  if (imported.cropped_voxels > 0) {
    // NOTE: a map from another grid keeps what lies inside the manifest's; what it drops is
    // said, never silent.
    warn(fmt::format(
        "{}: dropped {} of its {} known voxels, which lie outside the manifest's grid (its roi)",
        o.map, imported.cropped_voxels, imported.cropped_voxels + imported.known_voxels));
  }
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
               registration_note(c, mapper_config.register_scans, mapper->scans() == 1));
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
const auto estimated = [&](std::size_t i) { return plan.is_estimate(i); };
// The chosen view first (for random, the drawn one), then those evaluated in full by score, then
// the estimated ones: no estimate is listed above the choice it lost to.
const std::vector<std::size_t> ranking = plan.ranking();

const CellCounts counts = grid.counts();
const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(frame).transpose();
auto nbv = [&](std::size_t i) {
  Eigen::Isometry3d T_world_cloud = poses[i];
  T_world_cloud.linear() = poses[i].linear() * R_sensor_cloud;
  json j = {{"index", i},
            {"sensor", pose_json(poses[i])},
            {"yaw", unsigned_zero(yaw_deg(poses[i]), 9)},
            {"cloud_frame", pose_json(T_world_cloud)},
            {"predicted_gain", plan.gains[i].gain},
            {"predicted_cells", plan.gains[i].cells},
            {"greedy_gain", plan.greedy_gains.empty() ? json() : json(plan.greedy_gains[i])},
            {"score", plan.scores[i]}};
  if (robot) j["travel"] = candidates[i].travel;
  if (estimated(i)) j["estimated"] = true;
  return j;
};
const std::size_t clouds = manifest ? manifest->clouds.size() : 0;
json units_out = units_json(units);
units_out["position"] = "m";
units_out["yaw"] = "deg";
units_out["seconds"] = "s";
json out = {{"version", kPlanJsonVersion},
            {"vantage_version", VANTAGE_VERSION},
            {"units", units_out},
            {"robot", robot ? json{{"sensor", pose_json(*robot)}, {"from", robot_source}} : json()},
            {"next_best_view", nbv(plan.best)},
            {"method", to_string(planner.method)},
            {"alpha", planner.gain.alpha},
            {"objective", units.objective},
            {"evaluation", to_string(planner.gain.evaluation)},
            {"search", to_string(plan.search)},
            {"sensor", sensor_json(fov)},
            {"clouds", clouds},
            {"frames", {{"sensor", "x forward, y left, z up"}, {"cloud_frame", to_string(frame)}}},
            {"map",
             {{"grid",
               {{"origin", {spec.origin.x(), spec.origin.y(), spec.origin.z()}},
                {"resolution", spec.resolution},
                {"dims", {spec.dims.x(), spec.dims.y(), spec.dims.z()}}}},
              {"clouds", clouds},
              {"unobserved", counts.unobserved},
              {"free", counts.free},
              {"occupied", counts.occupied}}},
            {"candidates", json::array()},
            {"seconds",
             {{"map", map_seconds},
              {"plan", plan.seconds},
              {"reference", plan.reference_seconds},
              {"prediction", plan.prediction_seconds}}}};
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
// NOTE: the probabilistic method also predicts in cells (E, docs/model.md), the number its
// prediction error is measured in; greedy's gain already is a count of cells. The score column
// is what the method ranks by, in its unit, the same number as plan.json's score.
const bool show_cells = has_observability(planner.method);
const std::string gain_header = fmt::format("predicted gain [{}]", units.predicted_gain);
const std::string cells_header = "predicted seen [cells]";
const std::string score_header = fmt::format("score [{}]", units.score);
fmt::print("\n{:>4} {:>5} {:>26} {:>9} {:>{}}{} {:>19}{} {:>{}}\n", "rank", "view", "position [m]",
           "yaw [deg]", gain_header, gain_header.size() + 1,
           show_cells ? fmt::format(" {}", cells_header) : "", "greedy gain [cells]",
           robot ? fmt::format(" {:>10}", "travel [m]") : "", score_header, score_header.size());
const bool any_estimated =
    std::any_of(ranking.begin(), ranking.end(), [&](std::size_t i) { return estimated(i); });
for (std::size_t r = 0; r < ranking.size() && r < static_cast<std::size_t>(o.top); ++r) {
  const std::size_t i = ranking[r];
  const Eigen::Vector3d p = poses[i].translation();
  // NOTE: '~' marks a gain the search estimated instead of evaluating (plan.json: estimated).
  const char* mark = estimated(i) ? "~" : " ";
  // NOTE: a swept search predicts no greedy gain for the candidates ("-").
  const std::string greedy =
      plan.greedy_gains.empty() ? "-" : fmt::format("{:.1f}", plan.greedy_gains[i]);
  // NOTE: a decision by cells predicts no gain in bits for the views it did not choose ("-").
  const bool no_bits = plan.bits_of_chosen_only && i != plan.best;
  const std::string bits = no_bits ? "-" : fmt::format("{:.1f}", plan.gains[i].gain);
  fmt::print("{:>4} {:>5} {:>26} {:>9.1f} {}{:>{}}{} {:>19}{} {:>{}.3f}\n", r + 1, i,
             fmt::format("({:.3f}, {:.3f}, {:.3f})", unsigned_zero(p.x(), 3),
                         unsigned_zero(p.y(), 3), unsigned_zero(p.z(), 3)),
             unsigned_zero(yaw_deg(poses[i]), 1), no_bits ? " " : mark, bits, gain_header.size(),
             show_cells
                 ? fmt::format(" {}{:>{}.1f}", mark, plan.gains[i].cells, cells_header.size() - 1)
                 : "",
             greedy, robot ? fmt::format(" {:>10.3f}", candidates[i].travel) : "", plan.scores[i],
             score_header.size());
}
if (any_estimated) {
  fmt::print("{}\n", plan.search == DecisionSearch::kPruned
                         ? "~ not evaluated: the pruned search's upper bound on this view's gain "
                           "and score, below the chosen view's score"
                         : "~ not evaluated in full: the swept search's estimate of this view's "
                           "gain and score, listed after the views evaluated in full (its rays "
                           "weigh a cell by the part of its volume they sweep, so an estimate may "
                           "exceed the chosen view's exact score: the leaders were raced on "
                           "their exact cells)");
}
fmt::print(
    "\nnext best view: candidate {} ({} method{}, {} search), score {:.1f} {}, decided in "
    "{:.3f} s\n  at {}\n  as --pose: {}\n",
    plan.best, to_string(planner.method),
    has_observability(planner.method)
        ? fmt::format(", a = {}, ranked by {}", planner.gain.alpha, units.objective)
        : "",
    to_string(plan.search), plan.scores[plan.best], units.score, plan.seconds,
    describe_pose(poses[plan.best]), pose_argument(poses[plan.best]));
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
                  "ring, sphere, hemisphere (an arm's views: rings at several radii and elevations "
                  "looking at the ROI's centre), frontier (4 level views at each frontier "
                  "region's centroid), or a TUM-format file of candidate poses")
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
  cmd->add_option("--views", o->views, "ring positions (x3 yaw offsets) or sphere views")
      ->check(whole_in(1, kMaxIndex));
  cmd->add_option("--fov-deg", o->fov_deg, "h,v field of view without a manifest [deg]")
      ->capture_default_str();
  cmd->add_option("--range", o->range, "min,max range without a manifest [m]")
      ->capture_default_str();
  o->planning.method = "survival";
  o->planning.add_to(*cmd);
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
