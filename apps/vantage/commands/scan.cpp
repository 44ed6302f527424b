/// `vantage scan`: one simulated scan (or 360° sweep) of a scene, written as a point cloud.

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"

namespace vantage::cli {
namespace {

struct ScanOptions {
  std::string scene;
  std::string pose;
  int start = -1;
  int view = -1;
  std::string sensor;
  std::string out;
  std::string frame = "sensor";
  std::uint64_t seed = 1;
  bool sweep = false;
  int threads = 0;
  int repeat = 0;
};

Eigen::Isometry3d chosen_pose(const ScanOptions& o, const sim::Scene& scene) {
  if (!o.pose.empty()) return parse_pose(o.pose, "--pose");
  if (o.start >= 0) {
    if (static_cast<std::size_t>(o.start) >= scene.start_poses.size()) {
      throw std::invalid_argument(fmt::format("--start {} is out of range: {} has {} starts",
                                              o.start, scene.name, scene.start_poses.size()));
    }
    return scene.start_poses[static_cast<std::size_t>(o.start)];
  }
  const auto views = scene.candidate_poses();
  if (static_cast<std::size_t>(o.view) >= views.size()) {
    throw std::invalid_argument(fmt::format("--view {} is out of range: {} has {} candidate views",
                                            o.view, scene.name, views.size()));
  }
  return views[static_cast<std::size_t>(o.view)];
}

/// Whether `p` lies inside the scene's closed surfaces (a wall's box, an object): a level ray from
/// it crosses them an odd number of times, on most of four such rays (issue 53: a start inside a
/// wall was said as "hit nothing within range").
bool inside_geometry(const sim::World& world, const Eigen::Vector3d& p) {
  int odd = 0;
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0),
                                           Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)}) {
    Eigen::Vector3d origin = p;
    int crossings = 0;
    for (; crossings < 256; ++crossings) {
      const std::optional<double> hit = world.cast(origin, direction, kMaxWorldCoordinate);
      if (!hit) break;
      origin += direction * (*hit + 1e-6);
    }
    odd += crossings % 2;
  }
  return odd >= 3;
}

/// Writes the scan to --out, in the sensor's frame (with the believed pose as its VIEWPOINT) or
/// the world's; a scan that hit nothing is refused, saying so when the sensor is inside geometry.
void write_scan(const ScanOptions& o, const sim::World& world, const PointCloud& points,
                const Eigen::Isometry3d& T_true, const Eigen::Isometry3d& T_noisy) {
  if (points.empty()) {
    if (inside_geometry(world, T_true.translation())) {
      throw std::runtime_error(fmt::format(
          "the scan hit nothing within range: the sensor at {} lies inside the scene's geometry "
          "(a wall or an object), so every ray ends on its inside nearer than the sensor's "
          "min_range; {} not written (move the pose, or the scene's start, out of it)",
          describe_pose(T_true), o.out));
    }
    throw std::runtime_error(
        fmt::format("the scan hit nothing within range; {} not written", o.out));
  }
  // NOTE: points in the sensor frame carry the believed pose as their PCD VIEWPOINT, as a robot's
  // recording would (a manifest without poses plans from it); points in the world need none.
  if (o.frame == "world") {
    write_point_cloud(o.out, transform(T_true, points));
  } else {
    write_point_cloud(o.out, points, T_noisy);
  }
  fmt::print("wrote {} ({} frame)\n", o.out, o.frame);
}

void run(const ScanOptions& o) {
  if (o.frame != "sensor" && o.frame != "world") {
    throw UsageError(
        fmt::format("--frame must be sensor or world, got '{}'", printable(o.frame, 40)));
  }
  // NOTE: a sensor's name is the command line's; the scene is a file's.
  std::optional<sim::SensorConfig> replacement;
  if (!o.sensor.empty()) {
    try {
      replacement = sim::builtin_sensor(o.sensor);
    } catch (const std::invalid_argument& e) {
      throw UsageError(fmt::format("--sensor: {}", e.what()));
    }
  }
  // NOTE: the written format is the flag's, decided before the scan (a usage error, exit 2); the
  // file's folder is checked as every output's is.
  if (!o.out.empty()) {
    try {
      require_point_cloud_extension(o.out);
    } catch (const std::invalid_argument& e) {
      throw UsageError(fmt::format("--out: {}", e.what()));
    }
    check_output_file(o.out, "--out");
  }
  sim::Scene scene = sim::load_scene(o.scene);
  if (replacement) scene.sensor = *replacement;
  const Eigen::Isometry3d pose = chosen_pose(o, scene);
  const sim::World world(std::move(scene), sim::WorldConfig{o.threads});

  auto take = [&](std::uint64_t seed) {
    if (!o.sweep) {
      sim::SimulatedScan scan = world.scan(pose, seed);
      return std::tuple(std::move(scan.points_sensor), scan.T_world_sensor_true,
                        scan.T_world_sensor_noisy, scan.rays);
    }
    sim::SimulatedSweep sweep = world.sweep(pose, seed);
    std::size_t rays = 0;
    for (const auto& step : sweep.steps) rays += step.rays;
    return std::tuple(std::move(sweep.points_sensor), sweep.T_world_sensor_true,
                      sweep.T_world_sensor_noisy, rays);
  };
  auto [points, T_true, T_noisy, rays] = take(o.seed);
  const sim::SensorConfig& sensor = world.scene().sensor;
  fmt::print("{}: {} {} from {}: {} points of {} rays\n", world.scene().name, sensor.name,
             o.sweep ? fmt::format("sweep of {} steps", sensor.sweep_steps) : "scan",
             describe_pose(T_true), points.size(), rays);
  fmt::print("believed pose: {}\n", describe_pose(T_noisy));

  if (o.repeat > 0) {
    // Timing of the casting alone, the scene already built; the first scan above warmed up.
    const auto begin = std::chrono::steady_clock::now();
    for (int k = 0; k < o.repeat; ++k) take(o.seed + 1 + static_cast<std::uint64_t>(k));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
            .count() /
        o.repeat;
    fmt::print("time per {}: {:.1f} ms (mean of {}, {} rays, threads {})\n",
               o.sweep ? "sweep" : "scan", ms, o.repeat, rays,
               o.threads == 0 ? std::string("all") : std::to_string(o.threads));
  }

  if (!o.out.empty()) write_scan(o, world, points, T_true, T_noisy);
}

}  // namespace

void add_scan_command(CLI::App& app) {
  auto o = std::make_shared<ScanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scan", "One simulated scan of a scene, written as a .pcd or .ply point cloud");
  cmd->add_option("--scene,-s", o->scene, "a built-in scene name or a scene YAML file")->required();
  auto* pose = cmd->add_option("--pose", o->pose,
                               "sensor pose x,y,z,roll,pitch,yaw in the world (m, degrees)");
  auto* start = cmd->add_option("--start", o->start, "the scene's start pose number K instead")
                    ->check(whole_in(0, kMaxIndex));
  auto* view =
      cmd->add_option("--view", o->view, "the scene's candidate view number K instead (table top)")
          ->check(whole_in(0, kMaxIndex));
  pose->excludes(start)->excludes(view);
  start->excludes(view);
  cmd->add_option("--sensor", o->sensor, "replace the scene's sensor: hokuyo or kinect");
  cmd->add_option("--out,-o", o->out, "write the points to this .pcd or .ply file");
  cmd->add_option("--frame", o->frame,
                  "frame of the written points: sensor (a PCD records the believed pose as its "
                  "VIEWPOINT) or world (true pose)")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the range and pose noise")
      ->check(seed_value())
      ->capture_default_str();
  cmd->add_flag("--sweep", o->sweep, "a 360-degree sweep at the pose instead of one scan");
  add_threads_option(*cmd, o->threads, "threads (0 = all cores); the scan does not depend on it");
  cmd->add_option("--repeat", o->repeat, "also time this many more scans and print the mean")
      ->check(whole_in(0, kMaxIndex));
  cmd->callback([o, pose, start, view] {
    if (pose->count() == 0 && start->count() == 0 && view->count() == 0) {
      throw UsageError("give the sensor pose with --pose, --start K or --view K");
    }
    if (o->out.empty() && o->repeat == 0) {
      throw UsageError("give --out FILE.pcd|.ply (or --repeat N to time scans)");
    }
    run(*o);
  });
}

}  // namespace vantage::cli
