// An office's exploration steps (detail/explorer.hpp): a 360° sweep at each stop, and the next
// stop chosen among the frontier regions' centroids the robot can reach.

#include <algorithm>
#include <cmath>

#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/detail/explorer.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_sets.hpp"

namespace vantage::detail {

void Explorer::observe_sweep(int k, ScanRecord& record) {
  const Eigen::Isometry3d& pose = record.T_world_sensor;
  const auto start = Clock::now();
  sim::SimulatedSweep sweep =
      world_.sweep(pose, stream_seed(config_.seed, static_cast<std::uint64_t>(k), 1));
  record.seconds.scan = seconds_since(start);

  // NOTE: the first stop defines the map frame (its pose is known, §4.1); every step of a
  // sweep shares the stop's pose error, and the pan between steps is known exactly.
  const Eigen::Isometry3d believed = k == 1 ? pose : sweep.T_world_sensor_noisy;
  const Eigen::Isometry3d T_sensor0_world = sweep.T_world_sensor_true.inverse();
  std::vector<ScanPart> parts;
  for (sim::SimulatedScan& step : sweep.steps) {
    parts.push_back(
        {std::move(step.points_sensor), T_sensor0_world * step.T_world_sensor_true, step.fov});
  }
  const MapperUpdate update = mapper_.add_scan(parts, believed);
  record_update(update, pose, record);
  record_reregistered(update, record);
  const Eigen::Isometry3d& corrected = update.T_world_sensor;
  stops_.push_back(corrected.translation().head<2>());
  position_ = corrected.translation().head<2>();
  yaw_ = std::atan2(corrected.linear()(1, 0), corrected.linear()(0, 0));
}

Decision Explorer::plan_stop(int k, std::uint64_t seed) {
  Decision d;
  const auto start = Clock::now();
  const OccupancyGrid& grid = mapper_.grid();
  const PlacedViews stops =
      build_candidates(run_candidate_set(scene_, config_), stop_site(), config_.views);
  d.candidate_seconds = seconds_since(start);
  d.candidates = static_cast<int>(stops.poses.size());
  if (stops.poses.empty()) {
    d.stop = true;
    d.stop_reason = cat("no frontier left to drive to after stop ", k);
    d.seconds = seconds_since(start);
    result_.candidates.clear();
    return d;
  }

  // Each stop plans as the frusta of its sweep: its gains and score are their sums.
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < stops.poses.size(); ++i) {
    std::vector<Frustum> views = sweep_frusta(scene_, stops.poses[i]);
    const Frustum first = views.front();
    views.erase(views.begin());
    candidates.push_back(
        {first, stops.drives[i].length, stops.drives[i].reachable, std::move(views)});
  }
  const std::vector<Eigen::Isometry3d>& poses = stops.poses;
  check_decision_on(grid, candidates, planner_, config_.budget);
  const Plan plan = plan_next_view(grid, candidates, planner_, seed);
  const std::size_t best = plan.best;
  result_.candidates = poses;
  double best_gain = 0.0;  // of any stop, whichever the method chose
  for (const ViewGain& g : plan.gains) best_gain = std::max(best_gain, g.gain);
  if (best_gain < config_.min_gain) {
    d.stop = true;
    d.stop_reason =
        cat("best predicted gain ", best_gain, " fell below ", config_.min_gain, " after stop ", k);
  }
  d.view = static_cast<int>(best);
  record_prediction(plan, candidates[best], best, d);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    d.considered.push_back(considered(plan, i, static_cast<int>(i), poses[i], d));
  }
  d.seconds = seconds_since(start);

  // The drive happens in the true world: to the goal when the map says it is reachable,
  // else to the map's nearest reachable place; where an obstacle the map has not seen yet is
  // in the way, as close as the robot gets (§5.3.1). The robot keeps clear of what its map
  // holds too, so it never squeezes through a gap its map has closed (and then finds itself
  // walled in by its own map).
  const Drive& chosen = stops.drives[best];
  const NavigationGrid nav = NavigationGrid::from_map(grid, navigation_);
  const NavigationPath path =
      find_path(NavigationGrid::combine(true_navigation_, nav), true_position_, chosen.arrival);
  d.fallback = !chosen.reachable || !path.reached;
  d.travel = path.length;
  for (const Eigen::Vector2d& p : path.points) {
    d.path.emplace_back(p.x(), p.y(), scene_.mount.height);
  }
  d.goal = Eigen::Vector3d(chosen.goal.x(), chosen.goal.y(), 0.0);
  const Eigen::Vector2d way = path.end - true_position_;
  const double yaw = way.norm() > 1e-9 ? std::atan2(way.y(), way.x()) : yaw_;
  d.pose = scene_.mount.sensor_pose(path.end.x(), path.end.y(), yaw);
  true_position_ = path.end;
  return d;
}

CandidateSite Explorer::stop_site() const {
  CandidateSite site;
  site.region = Eigen::AlignedBox3d(scene_.grid.origin, scene_.grid.max_corner());
  site.grid = &mapper_.grid();
  GroundRobot& robot = site.robot.emplace();
  robot.position = position_;
  robot.yaw = yaw_;
  robot.navigation = navigation_;
  robot.frontier = frontier_;
  robot.visited = stops_;
  robot.min_move = config_.office.min_move;
  robot.project_stops = config_.office.project_stops;
  robot.sensor_pose = [this](double x, double y, double yaw) {
    return scene_.mount.sensor_pose(x, y, yaw);
  };
  return site;
}

}  // namespace vantage::detail
