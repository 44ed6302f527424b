/// `vantage plan`: real scans in, next view out. Maps a robot's clouds (a manifest, see
/// docs/manifest.md) and/or an existing OctoMap, scores candidate views, and answers with the
/// next best view as a ranked table, plan.json and the updated map.

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
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/octomap_io.hpp"
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
  std::string out;
  bool json_only = false;
  int top = 10;
};

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
  if (fov.size() != 2) throw std::invalid_argument("--fov-deg takes two numbers: h,v");
  if (range.size() != 2) throw std::invalid_argument("--range takes two numbers: min,max");
  SensorFov result{deg2rad(fov[0]), deg2rad(fov[1]), range[0], range[1]};
  result.validate();
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
  if (!fs::exists(o.candidates)) {
    throw std::invalid_argument(
        fmt::format("--candidates '{}' is neither ring, sphere, frontier nor an existing pose file",
                    o.candidates));
  }
  return read_candidate_poses(o.candidates, frame);
}

void run(const PlanOptions& o) {
  if (o.input.empty() && o.map.empty()) {
    throw std::invalid_argument("give a manifest or data folder, or --map FILE.bt|.ot, or both");
  }
  const auto start = std::chrono::steady_clock::now();
  std::optional<Manifest> manifest;
  if (!o.input.empty()) manifest = read_manifest(o.input);
  const SensorFov fov = manifest ? manifest->fov : fov_from_options(o);
  const CloudFrame frame = manifest ? manifest->frame : CloudFrame::kOptical;

  PlannerConfig planner = o.planning.planner_config();
  planner.greedy_reference = true;
  MapperConfig mapper_config = manifest ? mapper_config_for(*manifest) : MapperConfig{};
  mapper_config.integration.num_threads = o.planning.threads;

  std::optional<Mapper> mapper;
  if (!o.map.empty()) {
    OctomapImportConfig import;
    if (manifest) import.grid = manifest->grid;
    import.crop = manifest.has_value();
    mapper.emplace(read_octomap(o.map, import).grid, mapper_config);
  } else {
    mapper.emplace(manifest->grid, mapper_config);
  }
  if (manifest) {
    map_recorded(*manifest, *mapper, [&](std::size_t i, const MapperUpdate& u) {
      if (!o.json_only) {
        fmt::print("cloud {}/{}  {}  {} points  {} cells seen{}\n", i + 1, manifest->clouds.size(),
                   manifest->clouds[i].file.filename().string(), u.points,
                   u.integration.left_unobserved.size(),
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

  const std::vector<Eigen::Isometry3d> poses = candidate_poses(o, roi, frame, grid);
  std::vector<Candidate> candidates;
  for (const Eigen::Isometry3d& pose : poses) candidates.push_back({Frustum(pose, fov)});
  const Plan plan = plan_next_view(grid, candidates, planner, /*seed=*/1);

  std::vector<std::size_t> ranking(candidates.size());
  std::iota(ranking.begin(), ranking.end(), std::size_t{0});
  std::stable_sort(ranking.begin(), ranking.end(),
                   [&](std::size_t a, std::size_t b) { return plan.scores[a] > plan.scores[b]; });
  std::swap(*std::find(ranking.begin(), ranking.end(), plan.best), ranking.front());

  const CellCounts counts = grid.counts();
  const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(frame).transpose();
  auto nbv = [&](std::size_t i) {
    Eigen::Isometry3d T_world_cloud = poses[i];
    T_world_cloud.linear() = poses[i].linear() * R_sensor_cloud;
    json j = {{"index", i},
              {"sensor", pose_json(poses[i])},
              {"cloud_frame", pose_json(T_world_cloud)},
              {"predicted_gain", plan.gains[i].gain},
              {"greedy_gain", plan.greedy_gains[i]},
              {"score", plan.scores[i]}};
    return j;
  };
  json out = {
      {"next_best_view", nbv(plan.best)},
      {"method", to_string(planner.method)},
      {"alpha", planner.gain.alpha},
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

  const fs::path dir =
      !o.out.empty()
          ? fs::path(o.out)
          : fs::path("results") / fmt::format("plan-{:%Y%m%d-%H%M%S}",
                                              fmt::localtime(std::chrono::system_clock::to_time_t(
                                                  std::chrono::system_clock::now())));
  if (fs::exists(dir) && !fs::is_empty(dir)) {
    throw std::invalid_argument(fmt::format("--out {} exists and is not empty", dir.string()));
  }
  write_folder_atomically(dir, [&](const fs::path& partial) {
    write_atomically(partial / "plan.json", out.dump(2) + "\n");
    write_octomap(partial / "map.bt", grid);
  });

  if (o.json_only) {
    fmt::print("{}\n", out.dump(2));
    return;
  }
  fmt::print("\n{:>4} {:>5} {:>30} {:>14} {:>12}\n", "rank", "view", "position [m]",
             "predicted gain", "greedy gain");
  for (std::size_t r = 0; r < ranking.size() && r < static_cast<std::size_t>(o.top); ++r) {
    const std::size_t i = ranking[r];
    const Eigen::Vector3d p = poses[i].translation();
    fmt::print("{:>4} {:>5} {:>30} {:>14.1f} {:>12.1f}\n", r + 1, i,
               fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z()), plan.gains[i].gain,
               plan.greedy_gains[i]);
  }
  fmt::print(
      "\nnext best view: candidate {} ({} method{}), decided in {:.3f} s\n"
      "map: {} unobserved, {} free, {} occupied cells\nresults: {}/plan.json, map.bt\n",
      plan.best, to_string(planner.method),
      planner.method == PlannerMethod::kProbabilistic ? fmt::format(", a = {}", planner.gain.alpha)
                                                      : "",
      plan.seconds, counts.unobserved, counts.free, counts.occupied, dir.string());
}

}  // namespace

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
  cmd->add_option("--radius", o->radius, "ring/sphere radius [m] (default: from the ROI)");
  cmd->add_option("--height", o->height, "ring height [m] (default: 0.3 m above the ROI)");
  cmd->add_option("--views", o->views, "ring positions (x3 yaw offsets) or sphere views");
  cmd->add_option("--fov-deg", o->fov_deg, "h,v field of view without a manifest [deg]")
      ->capture_default_str();
  cmd->add_option("--range", o->range, "min,max range without a manifest [m]")
      ->capture_default_str();
  o->planning.add_to(*cmd);
  cmd->add_option("--out,-o", o->out, "results folder (default: a fresh folder under results/)");
  cmd->add_flag("--json", o->json_only, "print only plan.json, for other programs");
  cmd->add_option("--top", o->top, "rows of the ranked table")->capture_default_str();
  cmd->callback([o] { run(*o); });
}

}  // namespace vantage::cli
