// `vantage plan`'s map (plan.hpp): the input read (a manifest, or a recording alone), the grid
// checked against the budgets before it is allocated, an OctoMap imported, and the clouds mapped,
// each said in a line unless --json.

#include <fmt/core.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "commands/plan.hpp"
#include "shell.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::cli {
namespace {

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

/// --roi as a recording alone's region; none when not given. Throws UsageError.
std::optional<Eigen::AlignedBox3d> roi_option(const PlanOptions& o) {
  if (o.roi.empty()) return std::nullopt;
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
  return Eigen::AlignedBox3d(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
}

/// The manifest of a recording alone (issue 53): `plan FILE.bag --topic T`, its region and
/// resolution from --roi and --resolution or derived (manifest_for_recording), said in one line.
Manifest recording_alone(const PlanOptions& o) {
  RecordingAloneOptions read;
  read.read.topic = o.topic;
  if (o.every > 0) read.read.every = o.every;
  read.read.salvage = o.salvage;
  if (const auto roi = roi_option(o)) read.roi = *roi;
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

/// The manifest the input names: a recording alone (a .bag or .mcap file), a manifest or a data
/// folder, or none (--map alone). Throws UsageError for the options that do not fit it.
std::optional<Manifest> read_manifest_of(const PlanOptions& o) {
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
  if (alone) return recording_alone(o);
  if (o.input.empty()) return std::nullopt;
  ManifestReadOptions read;
  if (o.every > 0) read.every = o.every;
  if (!o.topic.empty()) read.topic = o.topic;
  read.salvage = o.salvage;
  return read_manifest(o.input, read);
}

/// Refuses a grid too large for memory, or one whose map cannot be written, and a decision the
/// work budget does not allow (its views known from the grid's box or the manifest's roi, all but
/// frontier views).
void check_grid(const PlanRun& run, const GridSpec& spec, const std::string& source) {
  const PlanOptions& o = run.o;
  check_memory({spec.num_cells(), grid_bytes_per_cell(o.planning.threads), kFixedRunBytes},
               o.max_memory,
               fmt::format("the grid of {} ({} x {} x {} cells)", source, spec.dims.x(),
                           spec.dims.y(), spec.dims.z()));
  require_octomap_range(spec, source);
  const auto box =
      run.manifest ? run.manifest->roi : Eigen::AlignedBox3d(spec.origin, spec.max_corner());
  if (const auto poses = planned_poses(o, box, run.frame)) {
    // NOTE: the least the decision can cost whatever the map (no cell unobserved); the map's
    // own share is weighed once it is built.
    check_decision_budget(estimate_decision(spec, *poses, run.fov, run.planner, /*unobserved=*/0.0),
                          work_budget(o.max_work, o.max_memory), spec.num_cells(),
                          o.planning.threads);
  }
}

/// The grid --map holds, cropped to the manifest's when there is one, said in a line.
OccupancyGrid imported_map(const PlanRun& run) {
  const PlanOptions& o = run.o;
  OctomapImportConfig settings;
  if (run.manifest) settings.grid = run.manifest->grid;
  settings.crop = run.manifest.has_value();
  // NOTE: a derived grid is checked before it is allocated (docs/fuzzing.md, the OctoMap
  // finding); a manifest's was checked before.
  if (!run.manifest) {
    settings.check_grid = [&](const GridSpec& spec) { check_grid(run, spec, o.map); };
  }
  OctomapImport imported = read_octomap(o.map, settings);
  const GridSpec& loaded = imported.grid.spec();
  if (!o.json_only) {
    fmt::print(
        "map: {} ({} {}, {} known voxels) into {} grid of {} x {} x {} cells at {} m from "
        "({:.4g}, {:.4g}, {:.4g})\n",
        o.map, to_string(imported.format), imported.tree_type, imported.known_voxels,
        run.manifest ? "the manifest's" : "its own", loaded.dims.x(), loaded.dims.y(),
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
  return std::move(imported.grid);
}

/// A cloud mapped: a warning when nothing of it was mapped, and its line unless --json.
void say_cloud(const PlanRun& run, const RecordedCloud& c, const Mapper& mapper,
               const MapperConfig& config) {
  const Manifest& manifest = *run.manifest;
  const MapperUpdate& u = c.update;
  const ManifestCloud& cloud = manifest.clouds[c.index];
  if (config.segment_table && u.table_views == 0 && u.thinned_points > 0) {
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
  if (run.o.json_only) return;
  fmt::print(
      "cloud {}/{}  {}  {} points{}  {} cells seen{}{}{}{}\n", c.index + 1, manifest.clouds.size(),
      cloud.file.filename().string(), u.points,
      c.non_finite_skipped > 0 ? fmt::format(" ({} non-finite skipped)", c.non_finite_skipped) : "",
      u.integration.left_unobserved.size(),
      cloud.pose_from_viewpoint ? "  (pose from its VIEWPOINT)" : "",
      c.table_pose ? "  (pose from the table)" : "",
      config.segment_table ? segmentation_note(c) : "",
      registration_note(c, config.register_scans, mapper.scans() == 1,
                        cloud.pose_from_registration));
  if (c.table_pose) {
    const perception::TablePose& t = *c.table_pose;
    fmt::print(
        "  pose from the table: the sensor {:.3f} m above the table's top (z = {} m), "
        "looking {:.1f} deg below level; the table's objects above the origin, x along the "
        "view\n  at {}\n  as --pose: {}\n",
        t.height_above_table, manifest.options.table_height,
        unsigned_zero(t.tilt * 180.0 / std::numbers::pi, 1), describe_pose(t.T_world_sensor),
        pose_argument(t.T_world_sensor));
  }
}

}  // namespace

void read_input(PlanRun& run) {
  const PlanOptions& o = run.o;
  run.manifest = read_manifest_of(o);
  if (run.manifest) {
    if (const auto& s = run.manifest->salvage) {
      // NOTE: one line, said whatever --json (plan.json records it too, "salvage").
      warn(
          fmt::format("{}: damaged; mapped the {} whole frame(s) before byte {} and dropped {}: {}",
                      run.manifest->recording->string(), s->frames, s->offset,
                      s->dropped ? fmt::format("the {} its index counts after them", *s->dropped)
                                 : std::string("the rest (its index is lost with it)"),
                      s->damage));
    }
  }
  run.fov = run.manifest ? run.manifest->fov : fov_from_options(o);
  run.frame = run.manifest ? run.manifest->frame : CloudFrame::kOptical;
  if (!run.manifest && !o.json_only) {
    fmt::print("sensor: {:.1f} x {:.1f} deg, {}-{} m{}\n", run.fov.h_fov * 180.0 / std::numbers::pi,
               run.fov.v_fov * 180.0 / std::numbers::pi, run.fov.min_range, run.fov.max_range,
               o.sensor_given ? " (--fov-deg, --range)"
                              : " (assumed: the --fov-deg and --range defaults, a Kinect's)");
  }
}

Mapper build_map(PlanRun& run) {
  const PlanOptions& o = run.o;
  MapperConfig config = run.manifest ? mapper_config_for(*run.manifest) : MapperConfig{};
  config.integration.num_threads = o.planning.threads;
  // NOTE: plan needs no object cloud; without it, memory stays bounded however many clouds come.
  config.keep_object_cloud = false;
  if (run.manifest) check_grid(run, run.manifest->grid, run.manifest->file.string());
  Mapper mapper =
      o.map.empty() ? Mapper(run.manifest->grid, config) : Mapper(imported_map(run), config);
  if (!o.map.empty() && run.manifest && config.register_scans && !o.json_only) {
    fmt::print(
        "note: {} holds no points, so ICP registers the manifest's clouds to each other "
        "only\n",
        o.map);
  }
  if (!run.manifest) return mapper;
  map_recorded(*run.manifest, mapper, [&](const RecordedCloud& c) {
    // NOTE: the pose the cloud was integrated at (ICP-corrected), wherever it came from.
    if (o.pose.empty()) {
      run.robot.pose = c.update.T_world_sensor;
      run.robot.source =
          c.table_pose ? "the last cloud's pose, from the table" : "the last cloud's pose";
    }
    say_cloud(run, c, mapper, config);
  });
  return mapper;
}

}  // namespace vantage::cli
