// `vantage plan`'s report (plan.hpp): plan.json, written with the maps as one folder, and the
// ranked table.

#include <fmt/core.h>

#include <algorithm>
#include <numbers>

#include "commands/plan.hpp"
#include "shell.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/map_files.hpp"
#include "vantage/io/ply_export.hpp"
#include "vantage/planner/search.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// plan.json's format: 2 added version, units, the robot's pose, travel and yaw; 3 the sensor,
/// the clouds, units per objective and the estimated flag; 4 the search that decided, and the
/// candidates listed as Plan::ranking orders them.
constexpr int kPlanJsonVersion = 4;

double yaw_deg(const Eigen::Isometry3d& T) {
  return roll_pitch_yaw(T.linear()).z() * 180.0 / std::numbers::pi;
}

json pose_json(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{"position", {T.translation().x(), T.translation().y(), T.translation().z()}},
          {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

}  // namespace

std::string pose_argument(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.linear()) * (180.0 / std::numbers::pi);
  return fmt::format("{:.4f},{:.4f},{:.4f},{:.3f},{:.3f},{:.3f}", unsigned_zero(t.x(), 4),
                     unsigned_zero(t.y(), 4), unsigned_zero(t.z(), 4), unsigned_zero(rpy.x(), 3),
                     unsigned_zero(rpy.y(), 3), unsigned_zero(rpy.z(), 3));
}

namespace {

/// A candidate as plan.json lists it: its sensor and cloud-frame poses, predictions and score.
json candidate_json(const PlanReport& report, std::size_t i) {
  const Plan& plan = report.plan;
  const std::vector<Eigen::Isometry3d>& poses = report.poses;
  const Eigen::Matrix3d R_sensor_cloud = R_cloud_sensor(report.frame).transpose();
  Eigen::Isometry3d T_world_cloud = poses[i];
  T_world_cloud.linear() = poses[i].linear() * R_sensor_cloud;
  json j = {{"index", i},
            {"sensor", pose_json(poses[i])},
            {"yaw", unsigned_zero(yaw_deg(poses[i]), 9)},
            {"cloud_frame", pose_json(T_world_cloud)},
            {"predicted_gain", plan.bits_predicted ? json(plan.gains[i].gain) : json()},
            {"predicted_cells", plan.gains[i].cells},
            {"greedy_gain", plan.greedy_gains.empty() ? json() : json(plan.greedy_gains[i])},
            {"score", plan.scores[i]}};
  if (report.robot) j["travel"] = report.candidates[i].travel;
  if (plan.is_estimate(i)) j["estimated"] = true;
  return j;
}

/// plan.json: the decision, its settings, the map, every candidate in Plan::ranking's order,
/// the times, and what a damaged recording lost.
json plan_json(const PlanReport& report) {
  const Plan& plan = report.plan;
  const PlannerConfig& planner = report.planner;
  const GainUnits& units = report.units;
  const std::optional<Eigen::Isometry3d>& robot = report.robot;
  const GridSpec& spec = report.grid.spec();
  const CellCounts counts = report.grid.counts();
  json units_out = units_json(units);
  units_out["position"] = "m";
  units_out["yaw"] = "deg";
  units_out["seconds"] = "s";
  json out = {
      {"version", kPlanJsonVersion},
      {"vantage_version", VANTAGE_VERSION},
      {"units", units_out},
      {"robot",
       robot ? json{{"sensor", pose_json(*robot)}, {"from", report.robot_source}} : json()},
      {"next_best_view", candidate_json(report, plan.best)},
      {"method", to_string(planner.method)},
      {"alpha", planner.gain.alpha},
      {"objective", units.objective},
      {"evaluation", to_string(planner.gain.evaluation)},
      {"search", to_string(plan.search)},
      {"sensor", sensor_json(report.fov)},
      {"clouds", report.clouds},
      {"frames", {{"sensor", "x forward, y left, z up"}, {"cloud_frame", to_string(report.frame)}}},
      {"map",
       {{"grid",
         {{"origin", {spec.origin.x(), spec.origin.y(), spec.origin.z()}},
          {"resolution", spec.resolution},
          {"dims", {spec.dims.x(), spec.dims.y(), spec.dims.z()}}}},
        {"clouds", report.clouds},
        {"unobserved", counts.unobserved},
        {"free", counts.free},
        {"occupied", counts.occupied}}},
      {"candidates", json::array()},
      {"seconds",
       {{"map", report.map_seconds},
        {"plan", plan.seconds},
        {"reference", plan.reference_seconds},
        {"prediction", plan.prediction_seconds},
        {"estimate", report.estimated_seconds}}}};
  // The chosen view first (for random, the drawn one), then those evaluated in full by score,
  // then the estimated ones: no estimate is listed above the choice it lost to.
  for (const std::size_t i : plan.ranking()) out["candidates"].push_back(candidate_json(report, i));
  if (const RecordingSalvage* s = report.salvage) {
    out["salvage"] = {{"damage", s->damage},
                      {"byte", s->offset},
                      {"frames_kept", s->frames},
                      {"frames_dropped", s->dropped ? json(*s->dropped) : json()}};
  }
  return out;
}

/// What the table's '~' means for the search that decided.
void print_estimate_note(const Plan& plan, const PlannerConfig& planner) {
  // NOTE: a metric whose value sums cell credits is raced cell by cell from the start, its
  // estimates those of the race's samples (docs/decision.md, "A metric raced cell by cell").
  const bool cell_race = method_traits(planner.method.gain).cells != nullptr;
  fmt::print("{}\n",
             plan.search == DecisionSearch::kPruned
                 ? "~ not evaluated: the pruned search's upper bound on this view's gain "
                   "and score, below the chosen view's score"
             : cell_race
                 ? "~ not evaluated in full: the swept search's estimate of this view's "
                   "gain and score on the sample of cells its race stopped at, listed after "
                   "the views evaluated in full"
                 : "~ not evaluated in full: the swept search's estimate of this view's "
                   "gain and score, listed after the views evaluated in full (its rays "
                   "weigh a cell by the part of its volume they sweep, so an estimate may "
                   "exceed the chosen view's exact score: the leaders were raced on "
                   "their exact cells), or, for a view its travel put out of the first "
                   "round before its rays were cast, the bound: its frustum's cells");
}

/// The table of the --top candidates in Plan::ranking's order, '~' marking an estimate, with a
/// line that says what the estimates are.
void print_table(const PlanReport& report) {
  const Plan& plan = report.plan;
  const PlannerConfig& planner = report.planner;
  const GainUnits& units = report.units;
  const std::vector<Eigen::Isometry3d>& poses = report.poses;
  const bool robot = report.robot.has_value();
  const auto estimated = [&](std::size_t i) { return plan.is_estimate(i); };
  const std::vector<std::size_t> ranking = plan.ranking();
  // NOTE: the probabilistic method also predicts in cells (E, docs/model.md), the number its
  // prediction error is measured in; greedy's gain already is a count of cells. The score column
  // is what the method ranks by, in its unit, the same number as plan.json's score.
  const bool show_cells = has_observability(planner.method);
  const std::string gain_header = fmt::format("predicted gain [{}]", units.predicted_gain);
  const std::string cells_header = "predicted seen [cells]";
  const std::string score_header = fmt::format("score [{}]", units.score);
  fmt::print("\n{:>4} {:>5} {:>26} {:>9} {:>{}}{} {:>19}{} {:>{}}\n", "rank", "view",
             "position [m]", "yaw [deg]", gain_header, gain_header.size() + 1,
             show_cells ? fmt::format(" {}", cells_header) : "", "greedy gain [cells]",
             robot ? fmt::format(" {:>10}", "travel [m]") : "", score_header, score_header.size());
  const bool any_estimated =
      std::any_of(ranking.begin(), ranking.end(), [&](std::size_t i) { return estimated(i); });
  for (std::size_t r = 0; r < ranking.size() && r < static_cast<std::size_t>(report.o.top); ++r) {
    const std::size_t i = ranking[r];
    const Eigen::Vector3d p = poses[i].translation();
    // NOTE: '~' marks a gain the search estimated instead of evaluating (plan.json: estimated).
    const char* mark = estimated(i) ? "~" : " ";
    // NOTE: a swept search predicts no greedy gain for the candidates ("-").
    const std::string greedy =
        plan.greedy_gains.empty() ? "-" : fmt::format("{:.1f}", plan.greedy_gains[i]);
    // NOTE: a decision by cells predicts no gain in bits for the views it did not choose ("-").
    const bool no_bits = (plan.bits_of_chosen_only && i != plan.best) || !plan.bits_predicted;
    const std::string bits = no_bits ? "-" : fmt::format("{:.1f}", plan.gains[i].gain);
    fmt::print("{:>4} {:>5} {:>26} {:>9.1f} {}{:>{}}{} {:>19}{} {:>{}.3f}\n", r + 1, i,
               fmt::format("({:.3f}, {:.3f}, {:.3f})", unsigned_zero(p.x(), 3),
                           unsigned_zero(p.y(), 3), unsigned_zero(p.z(), 3)),
               unsigned_zero(yaw_deg(poses[i]), 1), no_bits ? " " : mark, bits, gain_header.size(),
               show_cells
                   ? fmt::format(" {}{:>{}.1f}", mark, plan.gains[i].cells, cells_header.size() - 1)
                   : "",
               greedy, robot ? fmt::format(" {:>10.3f}", report.candidates[i].travel) : "",
               plan.scores[i], score_header.size());
  }
  if (any_estimated) print_estimate_note(plan, planner);
}

/// The next best view, the robot, the map's counts and where the results went.
void print_choice(const PlanReport& report) {
  const PlanOptions& o = report.o;
  const Plan& plan = report.plan;
  const PlannerConfig& planner = report.planner;
  const GainUnits& units = report.units;
  const std::vector<Eigen::Isometry3d>& poses = report.poses;
  const std::optional<Eigen::Isometry3d>& robot = report.robot;
  const CellCounts counts = report.grid.counts();
  fmt::print(
      "\nnext best view: candidate {} ({} method{}, {} search), score {:.1f} {}, decided in "
      "{:.3f} s\n  at {}\n  as --pose: {}\n",
      plan.best, to_string(planner.method),
      has_observability(planner.method)
          ? fmt::format(", a = {}, ranked by {}", planner.gain.alpha, units.objective)
          : "",
      to_string(plan.search), plan.scores[plan.best], units.score, plan.seconds,
      describe_pose(poses[plan.best]), pose_argument(poses[plan.best]));
  if (robot) fmt::print("robot at {} ({})\n", describe_pose(*robot), report.robot_source);
  fmt::print("map: {} unobserved, {} free, {} occupied cells\nresults: {}/plan.json, map.ot{}\n",
             counts.unobserved, counts.free, counts.occupied, report.dir.string(),
             o.plots ? ", map.png" : "");
}

}  // namespace

void report_plan(const PlanReport& report) {
  const json out = plan_json(report);
  write_folder_atomically(report.dir, [&](const fs::path& partial) {
    write_atomically(partial / "plan.json", out.dump(2) + "\n");
    write_map_files(partial, report.grid);
    write_cells_ply(partial / "map.ply", report.grid);
    if (report.o.plots) run_plot_script("plot_run.py", {partial.string()});
  });
  if (report.o.json_only) {
    fmt::print("{}\n", out.dump(2));
    return;
  }
  print_table(report);
  print_choice(report);
}

}  // namespace vantage::cli
