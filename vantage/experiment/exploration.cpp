#include "vantage/experiment/exploration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vantage/perception/registration.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/sim/ground_truth.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/frontier.hpp"

namespace vantage {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Seeds of the independent random streams of one run: scan k's sensor noise, its pose noise,
/// and the random choice after it. Mixing keeps runs with neighbouring seeds unrelated.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t scan, std::uint64_t stream) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL + scan * 0xBF58476D1CE4E5B9ULL + stream;
  z = (z ^ (z >> 31)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 29);
}

/// Share of the observable surface cells that the map holds as occupied.
double coverage(const OccupancyGrid& grid, const std::vector<std::uint32_t>& observable) {
  if (observable.empty()) return 0.0;
  std::size_t seen = 0;
  for (const std::uint32_t i : observable) seen += grid.state(i) == CellState::kOccupied;
  return static_cast<double>(seen) / static_cast<double>(observable.size());
}

/// The walk around the table between two views: the arc between their bearings at the ring's
/// radius, plus any difference in their distance from the ring's centre [m].
double ring_walk(const RingConfig& ring, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector2d a = from.head<2>() - ring.center.head<2>();
  const Eigen::Vector2d b = to.head<2>() - ring.center.head<2>();
  double turn = std::abs(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()));
  if (turn > std::numbers::pi) turn = 2.0 * std::numbers::pi - turn;
  return ring.radius * turn + std::abs(b.norm() - a.norm());
}

/// One point per map cell (the centroid of the cell's points), in the sensor frame. Paper-mode
/// integration gives a cell one hit however many points it holds, so the map is the same; ICP
/// and the clouds kept get far smaller.
PointCloud thin_to_cells(const PointCloud& points_sensor, const Eigen::Isometry3d& T_world_sensor,
                         const GridSpec& grid) {
  // NOTE: shifted so that the filter's voxels are the grid's cells.
  Eigen::Isometry3d T_grid_sensor = T_world_sensor;
  T_grid_sensor.translation() -= grid.origin;
  const PointCloud thinned =
      perception::voxel_downsample(transform(T_grid_sensor, points_sensor), grid.resolution);
  return transform(T_grid_sensor.inverse(), thinned);
}

/// The points of `cloud` within a square of half-side `reach` around (x, y) of `centre`.
PointCloud crop(const PointCloud& cloud, const Eigen::Vector3d& centre, double reach) {
  PointCloud out;
  for (const Eigen::Vector3d& p : cloud) {
    if (std::abs(p.x() - centre.x()) <= reach && std::abs(p.y() - centre.y()) <= reach) {
      out.push_back(p);
    }
  }
  return out;
}

/// The points (sensor frame) that land, under the pose guess, in cells the map already knows:
/// where the sweep overlaps what earlier sweeps saw. ICP pairs every point with its nearest
/// reference point, and a new sweep's points in unexplored space would pair with the edge of
/// the explored part and drag the pose towards it.
PointCloud known_part(const PointCloud& points_sensor, const Eigen::Isometry3d& T_world_sensor,
                      const OccupancyGrid& grid) {
  PointCloud out;
  for (const Eigen::Vector3d& p : points_sensor) {
    const std::optional<Index3> cell = grid.spec().find(T_world_sensor * p);
    if (cell && !grid.is_unobserved(grid.spec().linear(*cell))) out.push_back(p);
  }
  return out;
}

/// Nets the cells that left and re-entered the unobserved set over several integrations (a
/// sweep's steps), so that each cell counts once per stop.
class NetChange {
 public:
  explicit NetChange(std::size_t cells) : net_(cells, 0) {}
  void add(const IntegrationResult& r) {
    for (const std::uint32_t i : r.left_unobserved) step(i, -1);
    for (const std::uint32_t i : r.entered_unobserved) step(i, +1);
  }
  std::size_t left() const { return count(-1); }
  std::size_t entered() const { return count(+1); }

 private:
  void step(std::uint32_t i, int delta) {
    if (net_[i] == 0) touched_.push_back(i);
    net_[i] = static_cast<std::int8_t>(net_[i] + delta);
  }
  std::size_t count(int value) const {
    std::size_t n = 0;
    for (const std::uint32_t i : touched_) n += net_[i] == value;
    return n;
  }
  std::vector<std::int8_t> net_;
  std::vector<std::uint32_t> touched_;
};

/// Where the next scan is taken, and what the decision recorded.
struct Decision {
  bool stop = false;
  std::string stop_reason;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< true pose of the next scan
  int view = -1;
  std::optional<double> predicted, greedy_predicted;
  double seconds = 0.0, candidate_seconds = 0.0, reference_seconds = 0.0;
  double travel = 0.0;
  bool fallback = false;
  std::optional<Eigen::Vector3d> goal;
  std::vector<Eigen::Vector2d> path;
  int candidates = 0;
  std::vector<CandidateRecord> considered;
};

/// One exploration run. Table top and office share this loop; they differ in how a place is
/// observed (one scan, or a sweep) and where the candidates come from (the ring, or frontiers).
class Explorer {
 public:
  Explorer(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper)
      : scene_(scene),
        config_(config),
        mapper_(mapper),
        office_(scene.kind == sim::SceneKind::kOffice),
        world_(noisy(scene, config), sim::WorldConfig{config.planner.gain.num_threads}) {
    planner_ = config.planner;
    planner_.greedy_reference = true;  // Fig. 11: both predictions on the same poses
    if (office_) {
      if (mapper.config().register_scans) {
        throw std::invalid_argument(
            cat("office scene '", scene.name,
                "': the mapper must not register single scans, explore() registers whole sweeps "
                "(build it from default_mapper_config(), see ExplorationConfig::office)"));
      }
      navigation_.footprint = scene.robot.footprint;
      navigation_.max_height = scene.robot.height;
      navigation_.min_height = config.office.min_obstacle_height;
      navigation_.unknown_blocks = config.office.unknown_blocks;
      navigation_.validate();
      frontier_.min_z = scene.mount.height - config.office.frontier_band;
      frontier_.max_z = scene.mount.height + config.office.frontier_band;
      frontier_.min_cells = config.office.min_frontier_cells;
      frontier_.max_radius = config.office.max_frontier_radius;
      frontier_.validate();
    } else {
      for (const Eigen::Isometry3d& pose : scene.candidate_poses()) {
        ring_.push_back({Frustum(pose, scene.fov())});
        result_.candidates.push_back(pose);
      }
      if (ring_.empty()) {
        throw std::invalid_argument(cat("scene '", scene.name, "' has no candidate views"));
      }
      taken_.assign(ring_.size(), false);
    }
    if (!(world_.scene().grid == mapper.grid().spec())) {
      throw std::invalid_argument(cat("the mapper's grid differs from scene '", scene.name, "''s"));
    }
    truth_ = sim::compute_ground_truth(world_, config.planner.gain.num_threads);
    result_.observable_cells = truth_.observable.size();
    if (office_) {
      true_navigation_ = NavigationGrid::from_occupancy(scene.grid, truth_.occupied, navigation_);
    }
    const Eigen::Isometry3d& start = scene.start_poses[static_cast<std::size_t>(config.start)];
    true_position_ = start.translation().head<2>();
    position_ = true_position_;
    yaw_ = std::atan2(start.linear()(1, 0), start.linear()(0, 0));
  }

  ExplorationResult run(const ScanCallback& on_scan) {
    Decision next;
    next.pose = scene_.start_poses[static_cast<std::size_t>(config_.start)];
    for (std::size_t i = 0; i < result_.candidates.size(); ++i) {
      if (result_.candidates[i].isApprox(next.pose, 1e-9)) next.view = static_cast<int>(i);
    }
    if (next.view >= 0 && !taken_.empty()) taken_[static_cast<std::size_t>(next.view)] = true;
    for (int k = 1; k <= config_.scans; ++k) {
      ScanRecord record;
      record.scan = k;
      record.view = next.view;
      record.T_world_sensor = next.pose;
      record.predicted_gain = next.predicted;
      record.greedy_predicted_gain = next.greedy_predicted;
      record.seconds.plan = next.seconds;
      record.seconds.candidates = next.candidate_seconds;
      record.seconds.reference = next.reference_seconds;
      record.travel = next.travel;
      record.fallback = next.fallback;
      record.goal = next.goal;
      record.path = std::move(next.path);
      record.candidates = next.candidates;
      record.considered = std::move(next.considered);

      if (office_) {
        observe_sweep(k, record);
      } else {
        observe_view(k, record);
      }
      record.unobserved = mapper_.grid().counts().unobserved;
      record.coverage = coverage(mapper_.grid(), truth_.observable);

      bool stop = k == config_.scans;
      if (stop) result_.stop_reason = cat("took all ", config_.scans, " scans");
      if (!stop) {
        const auto u = static_cast<std::uint64_t>(k);
        next = office_ ? plan_stop(k, stream_seed(config_.seed, u, 3))
                       : plan_view(record, stream_seed(config_.seed, u, 3));
        if (next.stop) {
          stop = true;
          result_.stop_reason = next.stop_reason;
        }
      }
      result_.scans.push_back(record);
      if (on_scan) on_scan(record, config_.scans);
      if (stop) break;
    }
    return std::move(result_);
  }

 private:
  static sim::Scene noisy(const sim::Scene& scene, const ExplorationConfig& config) {
    sim::Scene s = scene;
    if (config.pose_noise) s.pose_noise = *config.pose_noise;
    return s;
  }

  void record_pose_errors(const Eigen::Isometry3d& believed, const Eigen::Isometry3d& used,
                          const Eigen::Isometry3d& truth, ScanRecord& record) const {
    const perception::PoseError before = perception::pose_error(believed, truth);
    const perception::PoseError after = perception::pose_error(used, truth);
    record.pose_error_before = before.translation;
    record.yaw_error_before = before.rotation;
    record.pose_error_after = after.translation;
    record.yaw_error_after = after.rotation;
  }

  /// Table top: one scan from the view.
  void observe_view(int k, ScanRecord& record) {
    const Eigen::Isometry3d& pose = record.T_world_sensor;
    const auto u = static_cast<std::uint64_t>(k);
    auto start = Clock::now();
    const sim::SimulatedScan scan = world_.scan(pose, stream_seed(config_.seed, u, 1));
    // NOTE: the first scan defines the map frame, so its pose is taken as known (§4.1); later
    // moves carry the scene's pose noise.
    const Eigen::Isometry3d believed =
        k == 1 ? pose : world_.noisy_pose(pose, stream_seed(config_.seed, u, 2));
    record.seconds.scan = seconds_since(start);

    const MapperUpdate update = mapper_.add_scan(scan.points_sensor, believed, scan.fov);
    record.seconds.register_scan = update.seconds_register;
    record.seconds.segment = update.seconds_segment;
    record.seconds.integrate = update.seconds_integrate;
    record_pose_errors(believed, update.T_world_sensor, pose, record);
    record.points = update.points;
    record.object_points = update.object_points;
    record.actual_gain = update.integration.left_unobserved.size();
    record.reentered = update.integration.entered_unobserved.size();
  }

  /// Office: a 360° sweep at the stop, registered as a whole, integrated step by step.
  void observe_sweep(int k, ScanRecord& record) {
    const Eigen::Isometry3d& pose = record.T_world_sensor;
    const GridSpec& grid = scene_.grid;
    auto start = Clock::now();
    const sim::SimulatedSweep sweep =
        world_.sweep(pose, stream_seed(config_.seed, static_cast<std::uint64_t>(k), 1));
    record.seconds.scan = seconds_since(start);

    start = Clock::now();
    // NOTE: the first stop defines the map frame (its pose is known, §4.1); every step of a
    // sweep shares the stop's pose error, and the pan between steps is known exactly.
    const Eigen::Isometry3d believed = k == 1 ? pose : sweep.T_world_sensor_noisy;
    const PointCloud merged = thin_to_cells(sweep.points_sensor, believed, grid);
    Eigen::Isometry3d corrected = believed;
    const OfficeConfig& office = config_.office;
    if (office.register_sweeps && !reference_.empty() && !merged.empty()) {
      const double reach =
          scene_.fov().max_range + 2.0 * office.icp.initial_correspondence_distance;
      const PointCloud nearby = crop(reference_, believed.translation(), reach);
      const PointCloud overlap = known_part(merged, believed, mapper_.grid());
      if (!nearby.empty() && overlap.size() >= 3) {
        const perception::IcpResult icp =
            perception::register_scan(overlap, believed, nearby, office.icp);
        const perception::PoseError step = perception::pose_error(icp.T_world_sensor, believed);
        if (icp.converged && step.translation <= office.max_icp_translation &&
            step.rotation <= office.max_icp_rotation) {
          corrected = icp.T_world_sensor;
        }
      }
    }
    // The reference of later sweeps: every registered sweep, one point per cell.
    const PointCloud merged_world = transform(corrected, merged);
    reference_.insert(reference_.end(), merged_world.begin(), merged_world.end());
    Eigen::Isometry3d to_grid = Eigen::Isometry3d::Identity();
    to_grid.translation() = -grid.origin;
    reference_ = transform(to_grid.inverse(), perception::voxel_downsample(
                                                  transform(to_grid, reference_), grid.resolution));
    record.seconds.register_scan = seconds_since(start);
    record_pose_errors(believed, corrected, pose, record);
    stops_.push_back(corrected.translation().head<2>());
    position_ = corrected.translation().head<2>();
    yaw_ = std::atan2(corrected.linear()(1, 0), corrected.linear()(0, 0));

    NetChange change(grid.num_cells());
    const Eigen::Isometry3d T_sensor0_world = sweep.T_world_sensor_true.inverse();
    for (const sim::SimulatedScan& step : sweep.steps) {
      const Eigen::Isometry3d T_world_step =
          corrected * (T_sensor0_world * step.T_world_sensor_true);  // the known pan
      start = Clock::now();
      const PointCloud points = thin_to_cells(step.points_sensor, T_world_step, grid);
      record.seconds.integrate += seconds_since(start);
      const MapperUpdate update = mapper_.add_scan(points, T_world_step, step.fov);
      record.seconds.segment += update.seconds_segment;
      record.seconds.integrate += update.seconds_integrate;
      record.points += step.points_sensor.size();
      record.object_points += update.object_points;
      change.add(update.integration);
    }
    record.actual_gain = change.left();
    record.reentered = change.entered();
  }

  /// Table top: every ring view, scored by the method; the robot walks around the table.
  Decision plan_view(const ScanRecord& current, std::uint64_t seed) {
    const Eigen::Vector3d here = current.T_world_sensor.translation();
    std::vector<Candidate> open;  // the ring's views still to take, and their ring indices
    std::vector<std::size_t> index;
    for (std::size_t i = 0; i < ring_.size(); ++i) {
      if (!config_.revisit && taken_[i]) continue;
      open.push_back(ring_[i]);
      open.back().travel = ring_walk(scene_.ring, here, ring_[i].view.origin());
      index.push_back(i);
    }
    Decision d;
    d.candidates = static_cast<int>(open.size());
    if (open.empty()) {
      d.stop = true;
      d.stop_reason = cat("every candidate view has been taken after scan ", current.scan);
      return d;
    }
    const Plan plan = plan_next_view(mapper_.grid(), open, planner_, seed);
    d.seconds = plan.seconds;
    d.reference_seconds = plan.reference_seconds;
    double best_gain = 0.0;  // of any candidate, whichever the method chose
    for (const ViewGain& g : plan.gains) best_gain = std::max(best_gain, g.gain);
    if (best_gain < config_.min_gain) {
      d.stop = true;
      d.stop_reason = cat("best predicted gain ", best_gain, " fell below ", config_.min_gain,
                          " after scan ", current.scan);
    }
    const std::size_t view = index[plan.best];
    taken_[view] = true;
    d.view = static_cast<int>(view);
    d.pose = result_.candidates[view];
    d.predicted = plan.gains[plan.best].gain;
    d.greedy_predicted = plan.greedy_gains[plan.best];
    d.travel = open[plan.best].travel;
    for (std::size_t j = 0; j < open.size(); ++j) {
      d.considered.push_back({static_cast<int>(index[j]), result_.candidates[index[j]],
                              plan.gains[j].gain, plan.greedy_gains[j]});
    }
    return d;
  }

  /// Office: a stop at every frontier region's centroid, its travel on the map's navigation
  /// grid, its gain over the frusta of its sweep; then the drive there, in the true world.
  Decision plan_stop(int k, std::uint64_t seed) {
    Decision d;
    const auto start = Clock::now();
    const OccupancyGrid& grid = mapper_.grid();
    const NavigationGrid nav = NavigationGrid::from_map(grid, navigation_);
    const TravelMap travel(nav, position_);
    struct Stop {
      Eigen::Vector2d goal;     ///< the frontier centroid
      Eigen::Vector2d arrival;  ///< the goal, or the map's nearest reachable place to it
      double travel;
      bool reachable;
    };
    std::vector<Stop> stops;
    for (const FrontierRegion& region : frontier_regions(grid, frontier_)) {
      Stop s{region.centroid.head<2>(), region.centroid.head<2>(), 0.0, false};
      const std::optional<Index2> cell = nav.cell_of(s.goal);
      s.reachable = cell && travel.reachable(*cell);
      const Index2 end = s.reachable ? *cell : travel.nearest_reachable(s.goal);
      if (!s.reachable) s.arrival = nav.center(end);
      s.travel = travel.distance(end);
      const bool visited = std::any_of(stops_.begin(), stops_.end(), [&](const auto& p) {
        return (p - s.arrival).norm() < config_.office.min_move;
      });
      if (!visited) stops.push_back(s);
    }
    d.candidate_seconds = seconds_since(start);
    d.candidates = static_cast<int>(stops.size());
    if (stops.empty()) {
      d.stop = true;
      d.stop_reason = cat("no frontier left to drive to after stop ", k);
      d.seconds = seconds_since(start);
      result_.candidates.clear();
      return d;
    }

    // Each stop plans as the frusta of its sweep, all through the one planner. Every method's
    // score of a frustum is its gain times a factor of the stop (Latombe), or a value of the
    // stop alone (Yamauchi: its travel), so a stop's score is the sum over its frusta; a random
    // frustum is a uniformly random stop.
    std::vector<Candidate> frusta;
    std::vector<Eigen::Isometry3d> poses;
    std::size_t per_stop = 0;
    for (const Stop& s : stops) {
      const Eigen::Vector2d way = s.goal - position_;
      const double yaw = way.norm() > 1e-9 ? std::atan2(way.y(), way.x()) : yaw_;
      poses.push_back(scene_.mount.sensor_pose(s.goal.x(), s.goal.y(), yaw));
      const std::vector<Frustum> views = sweep_frusta(scene_, poses.back());
      per_stop = views.size();
      for (const Frustum& f : views) frusta.push_back({f, s.travel, s.reachable});
    }
    const Plan plan = plan_next_view(grid, frusta, planner_, seed);
    d.reference_seconds = plan.reference_seconds;
    std::vector<double> scores(stops.size(), 0.0), gains(stops.size(), 0.0),
        greedy(stops.size(), 0.0);
    for (std::size_t i = 0; i < frusta.size(); ++i) {
      scores[i / per_stop] += plan.scores[i];
      gains[i / per_stop] += plan.gains[i].gain;
      greedy[i / per_stop] += plan.greedy_gains[i];
    }
    const std::size_t best =
        planner_.method == PlannerMethod::kRandom ? plan.best / per_stop : choose_best(scores);
    result_.candidates = poses;
    const double best_gain = *std::max_element(gains.begin(), gains.end());
    if (best_gain < config_.min_gain) {
      d.stop = true;
      d.stop_reason = cat("best predicted gain ", best_gain, " fell below ", config_.min_gain,
                          " after stop ", k);
    }
    d.view = static_cast<int>(best);
    for (std::size_t i = 0; i < stops.size(); ++i) {
      d.considered.push_back({static_cast<int>(i), poses[i], gains[i], greedy[i]});
    }
    d.predicted = gains[best];
    d.greedy_predicted = greedy[best];
    d.seconds = seconds_since(start);

    // The drive happens in the true world: to the goal when the map says it is reachable,
    // else to the map's nearest reachable place; where an obstacle the map has not seen yet is
    // in the way, as close as the robot gets (§5.3.1). The robot keeps clear of what its map
    // holds too, so it never squeezes through a gap its map has closed (and then finds itself
    // walled in by its own map).
    const Stop& chosen = stops[best];
    const NavigationPath path =
        find_path(NavigationGrid::combine(true_navigation_, nav), true_position_, chosen.arrival);
    d.fallback = !chosen.reachable || !path.reached;
    d.travel = path.length;
    d.path = path.points;
    d.goal = Eigen::Vector3d(chosen.goal.x(), chosen.goal.y(), 0.0);
    const Eigen::Vector2d way = path.end - true_position_;
    const double yaw = way.norm() > 1e-9 ? std::atan2(way.y(), way.x()) : yaw_;
    d.pose = scene_.mount.sensor_pose(path.end.x(), path.end.y(), yaw);
    true_position_ = path.end;
    return d;
  }

 private:
  const sim::Scene& scene_;
  const ExplorationConfig& config_;
  Mapper& mapper_;
  bool office_;
  sim::World world_;
  sim::GroundTruth truth_;
  PlannerConfig planner_;
  ExplorationResult result_;
  std::vector<Candidate> ring_;  ///< table top: the ring's views
  std::vector<bool> taken_;  ///< table top: ring views already taken (ExplorationConfig::revisit)
  // Office:
  NavigationConfig navigation_;
  FrontierConfig frontier_;
  NavigationGrid true_navigation_{Eigen::Vector2d::Zero(), 1.0, {1, 1}, {0}, 1.0};
  PointCloud reference_;                ///< registered sweeps, one point per cell (world)
  std::vector<Eigen::Vector2d> stops_;  ///< believed positions of the stops taken [m]
  Eigen::Vector2d position_ = Eigen::Vector2d::Zero();       ///< believed position [m]
  Eigen::Vector2d true_position_ = Eigen::Vector2d::Zero();  ///< [m]
  double yaw_ = 0.0;                                         ///< believed heading [rad]
};

}  // namespace

void OfficeConfig::validate() const {
  if (!(frontier_band >= 0.0 && std::isfinite(frontier_band))) {
    throw std::invalid_argument(cat("office.frontier_band must be >= 0 m, got ", frontier_band));
  }
  if (min_frontier_cells < 1) {
    throw std::invalid_argument(
        cat("office.min_frontier_cells must be >= 1, got ", min_frontier_cells));
  }
  if (!(max_frontier_radius >= 0.0 && std::isfinite(max_frontier_radius))) {
    throw std::invalid_argument(
        cat("office.max_frontier_radius must be >= 0 m, got ", max_frontier_radius));
  }
  if (!std::isfinite(min_obstacle_height)) {
    throw std::invalid_argument(
        cat("office.min_obstacle_height must be finite, got ", min_obstacle_height));
  }
  if (!(min_move >= 0.0 && std::isfinite(min_move))) {
    throw std::invalid_argument(cat("office.min_move must be >= 0 m, got ", min_move));
  }
  if (register_sweeps) icp.validate();
  if (!(max_icp_translation >= 0.0) || !(max_icp_rotation >= 0.0)) {
    throw std::invalid_argument(
        cat("office.max_icp_translation and office.max_icp_rotation must "
            "be >= 0, got ",
            max_icp_translation, " m and ", max_icp_rotation, " rad"));
  }
}

void ExplorationConfig::validate() const {
  planner.validate();
  mapper.validate();
  if (scans < 1) throw std::invalid_argument(cat("explore.scans must be >= 1, got ", scans));
  if (!(min_gain >= 0.0)) {
    throw std::invalid_argument(cat("explore.min_gain must be >= 0, got ", min_gain));
  }
  if (start < 0) throw std::invalid_argument(cat("explore.start must be >= 0, got ", start));
  if (pose_noise) pose_noise->validate();
  office.validate();
}

MapperConfig default_mapper_config(const sim::Scene& scene) {
  MapperConfig config;
  config.segment_table = scene.kind == sim::SceneKind::kTableTop;
  config.register_scans = scene.kind != sim::SceneKind::kOffice;
  return config;
}

void apply_registration_switch(const sim::Scene& scene, ExplorationConfig& config) {
  if (scene.kind != sim::SceneKind::kOffice) return;
  config.office.register_sweeps = config.mapper.register_scans;
  config.mapper.register_scans = false;
}

std::vector<Frustum> sweep_frusta(const sim::Scene& scene,
                                  const Eigen::Isometry3d& T_world_sensor) {
  const int steps = scene.sensor.sweep_steps;
  SensorFov fov = scene.fov();
  fov.h_fov = std::min(fov.h_fov, 2.0 * std::numbers::pi / steps);
  std::vector<Frustum> frusta;
  for (int k = 0; k < steps; ++k) {
    Eigen::Isometry3d T = T_world_sensor;
    T.linear() = Eigen::AngleAxisd(2.0 * std::numbers::pi * k / steps, Eigen::Vector3d::UnitZ()) *
                 T_world_sensor.linear();
    frusta.emplace_back(T, fov);
  }
  return frusta;
}

ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan) {
  config.validate();
  if (scene.start_poses.empty()) {
    throw std::invalid_argument(cat("scene '", scene.name, "' has no start poses"));
  }
  if (static_cast<std::size_t>(config.start) >= scene.start_poses.size()) {
    throw std::invalid_argument(cat("explore.start ", config.start, " is out of range: scene '",
                                    scene.name, "' has ", scene.start_poses.size(),
                                    " start poses"));
  }
  Explorer explorer(scene, config, mapper);
  return explorer.run(on_scan);
}

}  // namespace vantage
