/// `vantage scene`: a scene's summary, its ground truth, and a top view drawn by
/// scripts/plot_scene.py from the JSON this command writes.

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/sim/ground_truth.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::cli {
namespace {

struct SceneOptions {
  std::string scene;
  std::string out;
  std::string json;
  bool ground_truth = false;
  int threads = 0;
  std::uint64_t max_memory = 0;  // 0: what the machine has available
};

nlohmann::json xy(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

nlohmann::json view_json(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d f = T.linear().col(0);
  return {{"x", T.translation().x()},
          {"y", T.translation().y()},
          {"z", T.translation().z()},
          {"yaw", std::atan2(f.y(), f.x())}};
}

/// Everything the top view shows, in the world frame [m, rad].
nlohmann::json scene_json(const sim::Scene& scene) {
  nlohmann::json j;
  j["name"] = scene.name;
  j["kind"] = std::string(sim::to_string(scene.kind));
  const GridSpec& g = scene.grid;
  j["grid"] = {{"min", {g.origin.x(), g.origin.y(), g.origin.z()}},
               {"max", {g.max_corner().x(), g.max_corner().y(), g.max_corner().z()}},
               {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
               {"resolution", g.resolution}};
  j["floor"] = {xy(scene.floor_area.min()), xy(scene.floor_area.max())};
  j["rooms"] = nlohmann::json::array();
  for (const sim::Room& room : scene.rooms) {
    j["rooms"].push_back(
        {{"name", room.name}, {"min", xy(room.area.min())}, {"max", xy(room.area.max())}});
  }
  j["shapes"] = nlohmann::json::array();
  for (const sim::Shape& shape : scene.shapes) {
    nlohmann::json outline = nlohmann::json::array();
    for (const Eigen::Vector2d& p : sim::top_outline(shape)) outline.push_back(xy(p));
    const Eigen::AlignedBox3d box = shape.bounds();
    j["shapes"].push_back({{"name", shape.name},
                           {"kind", shape.kind},
                           {"zmin", box.min().z()},
                           {"zmax", box.max().z()},
                           {"outline", outline}});
  }
  j["starts"] = nlohmann::json::array();
  for (const Eigen::Isometry3d& T : scene.start_poses) j["starts"].push_back(view_json(T));
  j["candidates"] = nlohmann::json::array();
  for (const Eigen::Isometry3d& T : scene.candidate_poses()) {
    j["candidates"].push_back(view_json(T));
  }
  j["sensor"] = {{"name", scene.sensor.name},
                 {"h_fov", scene.sensor.fov.h_fov},
                 {"max_range", scene.sensor.fov.max_range}};
  return j;
}

void run(const SceneOptions& o) {
  // NOTE: outputs that cannot be made are refused before the ground truth's work.
  if (!o.out.empty()) check_picture_format(o.out, "--out");
  if (!o.out.empty()) check_output_file(o.out, "--out", {o.scene});
  if (!o.json.empty()) check_output_file(o.json, "--json", {o.scene});
  const sim::Scene scene = sim::load_scene(o.scene);
  const GridSpec& g = scene.grid;
  fmt::print("{} ({}, {})\n", scene.name, sim::to_string(scene.kind), scene.source);
  fmt::print("grid: {} x {} x {} cells of {:.6g} m from ({:.6g}, {:.6g}, {:.6g}) m\n", g.dims.x(),
             g.dims.y(), g.dims.z(), g.resolution, g.origin.x(), g.origin.y(), g.origin.z());
  fmt::print("shapes: {}; sensor: {}; starts: {}; candidate views: {}\n", scene.shapes.size(),
             scene.sensor.name, scene.start_poses.size(), scene.candidate_poses().size());

  if (o.ground_truth) {
    check_memory({g.num_cells(), kGroundTruthBytesPerCell, kFixedRunBytes}, o.max_memory,
                 fmt::format("the ground truth of scene {} ({} x {} x {} cells)", scene.name,
                             g.dims.x(), g.dims.y(), g.dims.z()));
    const auto begin = std::chrono::steady_clock::now();
    const sim::World world(scene, sim::WorldConfig{o.threads});
    const sim::GroundTruth gt = sim::compute_ground_truth(world, o.threads);
    const double seconds = seconds_since(begin);
    fmt::print(
        "ground truth: {} occupied cells, {} surface cells, {} observable from {} viewpoints "
        "({:.1f} s)\n",
        gt.occupied_count, gt.surface.size(), gt.observable.size(), gt.viewpoints, seconds);
  }

  const std::string data = scene_json(scene).dump(1);
  if (!o.json.empty()) write_atomically(o.json, data);
  if (o.out.empty()) return;
  const TemporaryFile drawing(".json");
  write_atomically(drawing.path(), data);
  run_plot_script("plot_scene.py", {drawing.path().string(), o.out});
  fmt::print("picture: {}\n", o.out);
}

struct GenerateOptions {
  int objects = sim::PileConfig{}.objects;
  std::uint64_t seed = sim::PileConfig{}.seed;
  std::string out;
};

void generate(const GenerateOptions& o) {
  check_output_file(o.out, "--out");
  sim::PileConfig config;
  config.objects = o.objects;
  config.seed = o.seed;
  const sim::Pile pile = from_options([&] { return sim::generate_pile(config); });
  const std::string text = sim::pile_scene_yaml(pile);
  write_atomically(o.out, text);
  std::size_t stacked = 0;
  for (const sim::PileObject& object : pile.objects) stacked += object.stands_on >= 0;
  fmt::print("{}: {} objects ({} set on another) into {}\n", pile.name, pile.objects.size(),
             stacked, o.out);
}

}  // namespace

void add_scene_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scene", "A scene's summary and top view: objects, start positions and candidate views");
  cmd->add_option("scene", o->scene, "a built-in scene name or a scene YAML file");
  cmd->add_option("--out,-o", o->out, "draw the top view into this PNG");
  cmd->add_option("--json", o->json, "also write the drawing's data to this JSON file");
  cmd->add_flag("--ground-truth", o->ground_truth,
                "also count the truly occupied, surface and observable cells");
  add_threads_option(*cmd, o->threads, "threads (0 = all cores)");
  add_memory_option(*cmd, o->max_memory);
  auto g = std::make_shared<GenerateOptions>();
  CLI::App* gen = cmd->add_subcommand(
      "generate",
      "Write the scene file of a seeded pile of the scanned models and primitives on the paper's "
      "table (docs/scenes.md, \"Generated piles\")");
  gen->add_option("--objects", g->objects, "objects in the pile")
      ->check(whole_in(1, sim::kMaxPileObjects))
      ->capture_default_str();
  gen->add_option("--seed", g->seed, "the same seed writes the same file")
      ->check(seed_value())
      ->capture_default_str();
  gen->add_option("--out,-o", g->out, "the scene file to write (YAML)")->required();
  gen->callback([g] { generate(*g); });
  cmd->callback([o, cmd] {
    if (cmd->got_subcommand("generate")) return;
    if (o->scene.empty()) throw UsageError("scene: give a built-in scene name or a YAML file");
    run(*o);
  });
}

}  // namespace vantage::cli
