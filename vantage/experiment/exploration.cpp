#include "vantage/experiment/exploration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>

#include "vantage/experiment/yardstick.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/observability.hpp"
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
TravelRule ring_walk_rule(const RingConfig& ring) {
  return {TravelRule::Kind::kRingWalk, ring.center, ring.radius};
}

/// Where the next scan is taken, and what the decision recorded.
struct Decision {
  bool stop = false;
  std::string stop_reason;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< true pose of the next scan
  int view = -1;
  std::optional<double> predicted, greedy_predicted;
  std::optional<double> predicted_cells;  ///< the method's prediction in cells seen
  std::optional<double> alpha;            ///< the a the probabilistic method decided with
  std::string search;                     ///< what decided: a search's name, or "sequence"
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
  Explorer(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
           const SurfaceTruth* surface_truth)
      : scene_(scene),
        config_(config),
        mapper_(mapper),
        office_(scene.kind == sim::SceneKind::kOffice),
        world_(noisy(scene, config), sim::WorldConfig{config.planner.gain.num_threads}) {
    planner_ = config.planner;
    // NOTE: Fig. 11 compares greedy's prediction with the method's on the view taken; greedy's
    // is made for that view alone, after the decision (greedy_of), not for every candidate.
    planner_.greedy_reference = false;
    if (config.auto_alpha && has_observability(planner_.method)) {
      fit_.emplace(config.observability);
      planner_.gain.alpha = fit_->alpha();
    }
    if (office_) {
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
      const bool arm = config.candidates == CandidateSet::kHemisphere;
      for (const Eigen::Isometry3d& pose : run_candidates(scene, config)) {
        ring_.push_back({Frustum(pose, scene.fov())});
        result_.candidates.push_back(pose);
      }
      // NOTE: a sequence's tour between two views costs what the robot's move between them does.
      planner_.sequence.travel = arm ? TravelRule{} : ring_walk_rule(scene.ring);
      if (ring_.empty()) {
        throw std::invalid_argument(cat("scene '", scene.name, "' has no candidate views"));
      }
      taken_.assign(ring_.size(), false);
    }
    if (!(world_.scene().grid == mapper.grid().spec())) {
      throw std::invalid_argument(cat("the mapper's grid differs from scene '", scene.name, "''s"));
    }
    // NOTE: observable means seen by the whole candidate set together: an arm's hemisphere
    // sees what the scene's ring may not.
    truth_ = sim::compute_ground_truth(world_, config.planner.gain.num_threads,
                                       config.candidates == CandidateSet::kHemisphere && !office_
                                           ? std::span<const Eigen::Isometry3d>(result_.candidates)
                                           : std::span<const Eigen::Isometry3d>());
    result_.observable_cells = truth_.observable.size();
    if (!office_) {
      if (surface_truth == nullptr) {
        own_surface_ =
            compute_surface_truth(world_, result_.candidates, config.planner.gain.num_threads);
        surface_truth = &*own_surface_;
      }
      if (!(surface_truth->grid == scene.grid) ||
          surface_truth->candidate_hits.size() != result_.candidates.size()) {
        throw std::invalid_argument(cat("the surface truth given for scene '", scene.name,
                                        "' is for another grid or candidate set"));
      }
      surface_ = surface_truth;
      truly_hit_ = surface_->start_hits.at(static_cast<std::size_t>(config.start));
      result_.surface_cells = surface_->surface.size();
      result_.visible_surface_cells = surface_->visible.size();
    }
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
      record.predicted_cells = next.predicted_cells;
      record.alpha = next.alpha;
      record.seconds.plan = next.seconds;
      record.seconds.candidates = next.candidate_seconds;
      record.seconds.reference = next.reference_seconds;
      record.travel = next.travel;
      record.fallback = next.fallback;
      record.goal = next.goal;
      record.path = std::move(next.path);
      record.candidates = next.candidates;
      record.considered = std::move(next.considered);
      record.search = std::move(next.search);

      // --alpha auto: what the view about to be scanned would see under every candidate a, set
      // against what it does see. The first scan calibrates too (on the empty map).
      if (fit_) {
        const auto start = Clock::now();
        const std::vector<Frustum> views = views_at(record.T_world_sensor);
        GainConfig gain = planner_.gain;
        gain.method = gain_method_of(planner_.method);
        record.calibration = expected_cells_by_alpha(mapper_.grid(), views, gain, fit_->alphas());
        record.seconds.calibrate = seconds_since(start);
      }
      if (office_) {
        observe_sweep(k, record);
      } else {
        observe_view(k, record);
      }
      if (fit_) {
        fit_->record(record.calibration, static_cast<double>(record.actual_gain));
        planner_.gain.alpha = fit_->alpha();
      }
      record.unobserved = mapper_.grid().counts().unobserved;
      record.coverage = coverage(mapper_.grid(), truth_.observable);
      if (surface_ != nullptr) {
        // NOTE: recounted from all registered points each scan: a re-registration moves earlier
        // scans' points too.
        const SurfaceCoverage s = surface_coverage(*surface_, mapper_.object_cloud());
        record.surface_coverage = s.visible;
        record.raw_surface_coverage = s.raw;
      }

      bool stop = k == config_.scans;
      if (stop) result_.stop_reason = "took every scan asked for";
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

  /// What the mapper did with a scan taken from the true pose `truth`.
  static void record_update(const MapperUpdate& update, const Eigen::Isometry3d& truth,
                            ScanRecord& record) {
    // NOTE: the errors are judged at truth, the integrated points where the scan saw them.
    const perception::PointSpread points = update.object_spread.transformed(truth);
    record.seconds.register_scan = update.seconds_register;
    record.seconds.segment = update.seconds_segment;
    record.seconds.integrate = update.seconds_integrate;
    const perception::PoseError before =
        perception::pose_error(update.T_world_sensor_guess, truth, points);
    const perception::PoseError after =
        perception::pose_error(update.T_world_sensor, truth, points);
    record.points_spread = points;
    record.pose_error_before = before.translation;
    record.yaw_error_before = before.rotation;
    record.displacement_before = before.displacement;
    record.pose_error_after = after.translation;
    record.yaw_error_after = after.rotation;
    record.displacement_after = after.displacement;
    record.pose_error_final = after.translation;
    record.displacement_final = after.displacement;
    record.registration = update.registration;
    record.registration_sigma = update.registration_result.position_sigma;
    record.registration_mahalanobis2 = update.registration_result.mahalanobis2;
    record.registration_pairs = update.registration_result.correspondences;
    record.registration_points = update.registration_result.points;
    record.yaw_error_final = after.rotation;
    record.points = update.points;
    record.object_points = update.object_points;
    record.actual_gain = update.integration.left_unobserved.size();
    record.reentered = update.integration.entered_unobserved.size();
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
    record_update(update, pose, record);
    record_reregistered(update, record);
  }

  /// The final pose errors of the earlier scans `update` registered again.
  void record_reregistered(const MapperUpdate& update, ScanRecord& record) {
    for (const MapperUpdate::Reregistered& r : update.reregistered) {
      ScanRecord& earlier = result_.scans.at(r.scan);
      const perception::PoseError error =
          perception::pose_error(r.T_world_sensor, earlier.T_world_sensor, earlier.points_spread);
      earlier.pose_error_final = error.translation;
      earlier.yaw_error_final = error.rotation;
      earlier.displacement_final = error.displacement;
      record.reregistered.push_back(earlier.scan);
    }
  }

  /// Office: a 360° sweep at the stop, one scan of many views for the mapper.
  void observe_sweep(int k, ScanRecord& record) {
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

  /// The frusta a scan from `pose` covers: the sensor's, or an office stop's whole sweep.
  std::vector<Frustum> views_at(const Eigen::Isometry3d& pose) const {
    return office_ ? sweep_frusta(scene_, pose) : std::vector<Frustum>{Frustum(pose, scene_.fov())};
  }

  /// Greedy's prediction for the chosen candidate (Fig. 11's reference): the plan's own when the
  /// method scored by greedy's count, else evaluated now for that candidate's views only. Adds
  /// the time it took to `d.reference_seconds`.
  double greedy_of(const Plan& plan, const Candidate& chosen, std::size_t best, Decision& d) const {
    if (!plan.greedy_gains.empty()) return plan.greedy_gains[best];
    const auto start = Clock::now();
    std::vector<Frustum> views{chosen.view};
    views.insert(views.end(), chosen.more_views.begin(), chosen.more_views.end());
    GainConfig greedy = planner_.gain;
    greedy.method = GainMethod::kGreedy;
    double sum = 0.0;
    for (const ViewGain& g : evaluate_views(mapper_.grid(), views, greedy)) sum += g.gain;
    d.reference_seconds += seconds_since(start);
    return sum;
  }

  /// The chosen candidate's predictions: in the method's own units, in cells seen, greedy's.
  void record_prediction(const Plan& plan, const Candidate& chosen, std::size_t best,
                         Decision& d) const {
    d.predicted = plan.gains[best].gain;
    d.predicted_cells = plan.gains[best].cells;
    d.greedy_predicted = greedy_of(plan, chosen, best, d);
    d.search = plan.sequence.empty() ? std::string(to_string(plan.search)) : "sequence";
    if (has_observability(planner_.method)) d.alpha = planner_.gain.alpha;
  }

  /// What the decision recorded of candidate `j`.
  CandidateRecord considered(const Plan& plan, std::size_t j, int view,
                             const Eigen::Isometry3d& pose, const Decision& d) const {
    CandidateRecord r{view, pose, plan.gains[j].gain, std::nullopt, plan.gains[j].cells};
    if (!plan.greedy_gains.empty()) {
      r.greedy_predicted_gain = plan.greedy_gains[j];
    } else if (j == plan.best) {
      r.greedy_predicted_gain = d.greedy_predicted;
    }
    r.estimated = plan.is_estimate(j);
    return r;
  }

  /// Table top: every ring view, scored by the method; the robot walks around the table.
  Decision plan_view(const ScanRecord& current, std::uint64_t seed) {
    const Eigen::Vector3d here = current.T_world_sensor.translation();
    std::vector<Candidate> open;  // the ring's views still to take, and their ring indices
    std::vector<std::size_t> index;
    for (std::size_t i = 0; i < ring_.size(); ++i) {
      if (!config_.revisit && taken_[i]) continue;
      open.push_back(ring_[i]);
      open.back().travel = planner_.sequence.travel(here, ring_[i].view.origin());
      index.push_back(i);
    }
    Decision d;
    d.candidates = static_cast<int>(open.size());
    if (open.empty()) {
      d.stop = true;
      d.stop_reason = cat("every candidate view has been taken after scan ", current.scan);
      return d;
    }
    if (config_.greedy_oracle) return oracle_view(current, open, index, std::move(d));
    const Plan plan = plan_next_view(mapper_.grid(), open, planner_, seed);
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
    record_prediction(plan, open[plan.best], plan.best, d);
    d.seconds = plan.seconds + d.reference_seconds;  // the whole plan step, reference included
    d.travel = open[plan.best].travel;
    for (std::size_t j = 0; j < open.size(); ++j) {
      d.considered.push_back(
          considered(plan, j, static_cast<int>(index[j]), result_.candidates[index[j]], d));
    }
    return d;
  }

  /// Table top, greedy oracle (ExplorationConfig::greedy_oracle): the open candidate whose true
  /// hit set adds the most visible surface cells to the true hit sets of the start and the views
  /// taken; its gain is that count [cells].
  Decision oracle_view(const ScanRecord& current, const std::vector<Candidate>& open,
                       const std::vector<std::size_t>& index, Decision d) {
    const auto start = Clock::now();
    std::vector<double> gains(open.size());
    std::size_t best = 0;
    for (std::size_t j = 0; j < open.size(); ++j) {
      const std::vector<std::uint32_t>& hits = surface_->candidate_hits[index[j]];
      gains[j] = static_cast<double>(hits.size() - count_common(hits, truly_hit_));
      // NOTE: ties go to the shorter travel, then to the lower index (open is in index order).
      if (gains[j] > gains[best] || (gains[j] == gains[best] && open[j].travel < open[best].travel))
        best = j;
    }
    if (gains[best] < config_.min_gain) {
      d.stop = true;
      d.stop_reason = cat("best true gain ", gains[best], " fell below ", config_.min_gain,
                          " after scan ", current.scan);
    }
    const std::size_t view = index[best];
    taken_[view] = true;
    std::vector<std::uint32_t> hit;
    std::set_union(truly_hit_.begin(), truly_hit_.end(), surface_->candidate_hits[view].begin(),
                   surface_->candidate_hits[view].end(), std::back_inserter(hit));
    truly_hit_ = std::move(hit);
    d.view = static_cast<int>(view);
    d.pose = result_.candidates[view];
    d.predicted = gains[best];
    d.predicted_cells = gains[best];
    d.travel = open[best].travel;
    for (std::size_t j = 0; j < open.size(); ++j) {
      d.considered.push_back({static_cast<int>(index[j]), result_.candidates[index[j]], gains[j],
                              std::nullopt, gains[j]});
    }
    d.seconds = seconds_since(start);
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
      std::optional<Index2> cell = nav.cell_of(s.goal);
      s.reachable = cell && travel.reachable(*cell);
      if (!s.reachable && config_.office.project_stops) {
        std::vector<Eigen::Vector2d> places;
        for (const std::uint32_t i : region.cells) {
          places.push_back(grid.spec().center(grid.spec().unravel(i)).head<2>());
        }
        if (const auto projected = travel.nearest_reachable_among(places, s.goal)) {
          cell = projected;
          s.goal = nav.center(*projected);
          s.arrival = s.goal;
          s.reachable = true;
        }
      }
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

    // Each stop plans as the frusta of its sweep: its gains and score are their sums.
    std::vector<Candidate> candidates;
    std::vector<Eigen::Isometry3d> poses;
    for (const Stop& s : stops) {
      const Eigen::Vector2d way = s.goal - position_;
      const double yaw = way.norm() > 1e-9 ? std::atan2(way.y(), way.x()) : yaw_;
      poses.push_back(scene_.mount.sensor_pose(s.goal.x(), s.goal.y(), yaw));
      std::vector<Frustum> views = sweep_frusta(scene_, poses.back());
      const Frustum first = views.front();
      views.erase(views.begin());
      candidates.push_back({first, s.travel, s.reachable, std::move(views)});
    }
    const Plan plan = plan_next_view(grid, candidates, planner_, seed);
    const std::size_t best = plan.best;
    result_.candidates = poses;
    double best_gain = 0.0;  // of any stop, whichever the method chose
    for (const ViewGain& g : plan.gains) best_gain = std::max(best_gain, g.gain);
    if (best_gain < config_.min_gain) {
      d.stop = true;
      d.stop_reason = cat("best predicted gain ", best_gain, " fell below ", config_.min_gain,
                          " after stop ", k);
    }
    d.view = static_cast<int>(best);
    record_prediction(plan, candidates[best], best, d);
    for (std::size_t i = 0; i < stops.size(); ++i) {
      d.considered.push_back(considered(plan, i, static_cast<int>(i), poses[i], d));
    }
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
  std::optional<ObservabilityFit> fit_;  ///< --alpha auto
  sim::World world_;
  sim::GroundTruth truth_;
  std::optional<SurfaceTruth> own_surface_;  ///< table top, when the caller gave none
  const SurfaceTruth* surface_ = nullptr;    ///< table top: the yardstick's truth
  /// Greedy oracle: the visible cells the true hit sets of the start and the views taken hold.
  std::vector<std::uint32_t> truly_hit_;
  PlannerConfig planner_;
  ExplorationResult result_;
  std::vector<Candidate> ring_;  ///< table top: the ring's views
  std::vector<bool> taken_;  ///< table top: ring views already taken (ExplorationConfig::revisit)
  // Office:
  NavigationConfig navigation_;
  FrontierConfig frontier_;
  NavigationGrid true_navigation_{Eigen::Vector2d::Zero(), 1.0, {1, 1}, {0}, 1.0};
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
  hemisphere.validate();
  if (arm && !(arm->reach > 0.0)) {
    throw std::invalid_argument(cat("explore.arm.reach must be > 0 m, got ", arm->reach));
  }
}

std::string_view to_string(CandidateSet set) {
  return set == CandidateSet::kHemisphere ? "hemisphere" : "ring";
}

CandidateSet parse_candidate_set(std::string_view name) {
  if (name == "ring") return CandidateSet::kRing;
  if (name == "hemisphere") return CandidateSet::kHemisphere;
  throw std::invalid_argument(
      cat("unknown candidate set '", name, "' (expected ring or hemisphere)"));
}

HemisphereConfig run_hemisphere(const sim::Scene& scene, const ExplorationConfig& config) {
  HemisphereConfig h = config.hemisphere;
  h.center = scene.mount.target;
  const std::optional<ArmReach>& arm = config.arm ? config.arm : scene.arm;
  if (arm) {
    h.base = arm->base;
    h.reach = arm->reach;
  }
  return h;
}

perception::PoseSigma odometry_prior(const sim::PoseNoise& noise) {
  // NOTE: the simulated error has no height, roll or pitch; the prior keeps a little slack there
  // (PoseSigma's defaults), and a floor where a sigma is 0, which the prior cannot weigh.
  constexpr double kFloor = 1e-4;
  perception::PoseSigma prior;
  prior.x = std::max(noise.x, kFloor);
  prior.y = std::max(noise.y, kFloor);
  prior.yaw = std::max(noise.yaw, kFloor);
  return prior;
}

AlphaSetting default_alpha_setting(PlannerMethod method, double paper) {
  return uses_survival_reading(method) ? AlphaSetting{true, kSurvivalAlpha}
                                       : AlphaSetting{false, default_alpha(method, paper)};
}

MapperConfig default_mapper_config(const sim::Scene& scene) {
  MapperConfig config;
  config.segment_table = scene.kind == sim::SceneKind::kTableTop;
  for (const sim::Shape& shape : scene.shapes) {
    if (shape.kind != "table") continue;
    // NOTE: seen from above (an arm's views), the floor around the table is the largest
    // horizontal plane; the table is the one within 5 cm of the scene's table top.
    constexpr double kTableSlack = 0.05;  // [m]
    config.table.min_table_z = shape.bounds().max().z() - kTableSlack;
    config.table.max_table_z = shape.bounds().max().z() + kTableSlack;
  }
  config.registration.prior =
      odometry_prior(ExplorationConfig{}.pose_noise.value_or(scene.pose_noise));
  if (scene.kind == sim::SceneKind::kOffice) {
    // A sweep is registered as a whole, thinned to one point per map cell, against the sweeps so
    // far at the same resolution; Kinect noise of up to 2 cm at 3.5 m.
    config.thin_to_cells = true;
    config.register_overlap_only = true;
    config.map.voxel_size = scene.grid.resolution;
    config.registration.voxel_size = scene.grid.resolution;
    // NOTE: a point thinned to its cell's centroid is off its surface by up to half a cell: the
    // quantisation's sigma (resolution / sqrt(12)) adds to the Kinect's 1 cm.
    config.registration.sensor_sigma = std::hypot(0.01, scene.grid.resolution / std::sqrt(12.0));
    config.registration.min_distance = 2.0 * scene.grid.resolution;
    // NOTE: a sweep's posterior rarely knows the position better than the prior along one
    // direction (the floor outweighs the walls); 1 cm keeps the sweeps that pin it.
    config.registration.max_position_sigma = 0.01;
    // NOTE: a retry that passes integrates every sweep since the fallback again (~1 s each).
    config.reregister_window = 3;
  }
  return config;
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

std::vector<Eigen::Isometry3d> run_candidates(const sim::Scene& scene,
                                              const ExplorationConfig& config) {
  return config.candidates == CandidateSet::kHemisphere
             ? hemisphere_poses(run_hemisphere(scene, config))
             : scene.candidate_poses();
}

TravelRule run_travel_rule(const sim::Scene& scene, const ExplorationConfig& config) {
  return config.candidates == CandidateSet::kHemisphere ? TravelRule{} : ring_walk_rule(scene.ring);
}

ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan) {
  return explore(scene, config, mapper, on_scan, nullptr);
}

ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan, const SurfaceTruth* surface_truth) {
  config.validate();
  if (scene.start_poses.empty()) {
    throw std::invalid_argument(cat("scene '", scene.name, "' has no start poses"));
  }
  if (static_cast<std::size_t>(config.start) >= scene.start_poses.size()) {
    throw std::invalid_argument(cat("explore.start ", config.start, " is out of range: scene '",
                                    scene.name, "' has ", scene.start_poses.size(),
                                    " start poses"));
  }
  if (scene.kind == sim::SceneKind::kOffice) {
    // NOTE: an office's candidates are frontier stops with sweeps, travel on its floor.
    if (config.candidates != CandidateSet::kRing) {
      throw std::invalid_argument(cat("scene '", scene.name,
                                      "' is an office: its candidates are "
                                      "frontier stops, not a hemisphere"));
    }
    if (config.greedy_oracle) {
      throw std::invalid_argument(
          cat("scene '", scene.name, "' is an office: the greedy oracle is for table tops"));
    }
    if (config.planner.sequence.active()) {
      throw std::invalid_argument(cat("scene '", scene.name,
                                      "' is an office: the sequence "
                                      "planner (horizon, travel weight) is for table tops"));
    }
  }
  if (config.greedy_oracle && !mapper.config().keep_object_cloud) {
    throw std::invalid_argument(
        "explore.greedy_oracle needs the mapper's object cloud (mapper.keep_object_cloud)");
  }
  Explorer explorer(scene, config, mapper, surface_truth);
  return explorer.run(on_scan);
}

}  // namespace vantage
