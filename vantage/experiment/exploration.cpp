#include "vantage/experiment/exploration.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "vantage/perception/registration.hpp"
#include "vantage/sim/ground_truth.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

}  // namespace

void ExplorationConfig::validate() const {
  planner.validate();
  mapper.validate();
  if (scans < 1) throw std::invalid_argument(cat("explore.scans must be >= 1, got ", scans));
  if (!(min_gain >= 0.0)) {
    throw std::invalid_argument(cat("explore.min_gain must be >= 0, got ", min_gain));
  }
  if (start < 0) throw std::invalid_argument(cat("explore.start must be >= 0, got ", start));
  if (pose_noise) pose_noise->validate();
}

MapperConfig default_mapper_config(const sim::Scene& scene) {
  MapperConfig config;
  config.segment_table = scene.kind == sim::SceneKind::kTableTop;
  return config;
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
  ExplorationResult result;
  result.candidates = scene.candidate_poses();
  if (result.candidates.empty()) {
    throw std::invalid_argument(cat("scene '", scene.name, "' has no candidate views"));
  }
  std::vector<Candidate> candidates;
  for (const Eigen::Isometry3d& pose : result.candidates) {
    candidates.push_back({Frustum(pose, scene.fov())});
  }

  sim::Scene noisy_scene = scene;
  if (config.pose_noise) noisy_scene.pose_noise = *config.pose_noise;
  const sim::World world(std::move(noisy_scene), sim::WorldConfig{config.planner.gain.num_threads});
  if (!(world.scene().grid == mapper.grid().spec())) {
    throw std::invalid_argument(cat("the mapper's grid differs from scene '", scene.name, "''s"));
  }
  const sim::GroundTruth truth = sim::compute_ground_truth(world, config.planner.gain.num_threads);
  const std::vector<std::uint32_t>& observable = truth.observable;
  result.observable_cells = observable.size();

  PlannerConfig planner = config.planner;
  planner.greedy_reference = true;  // Fig. 11: both predictions on the same poses

  Eigen::Isometry3d pose = scene.start_poses[static_cast<std::size_t>(config.start)];
  int view = -1;  // the start pose's index among the candidates, when it is one
  for (std::size_t i = 0; i < result.candidates.size(); ++i) {
    if (result.candidates[i].isApprox(pose, 1e-9)) view = static_cast<int>(i);
  }
  std::optional<double> predicted, greedy_predicted;
  double plan_seconds = 0.0;

  for (int k = 1; k <= config.scans; ++k) {
    ScanRecord record;
    record.scan = k;
    record.view = view;
    record.T_world_sensor = pose;
    record.predicted_gain = predicted;
    record.greedy_predicted_gain = greedy_predicted;
    record.seconds.plan = plan_seconds;

    auto start = std::chrono::steady_clock::now();
    const auto u = static_cast<std::uint64_t>(k);
    sim::SimulatedScan scan = world.scan(pose, stream_seed(config.seed, u, 1));
    // NOTE: the first scan defines the map frame, so its pose is taken as known (§4.1); later
    // moves carry the scene's pose noise.
    const Eigen::Isometry3d believed =
        k == 1 ? pose : world.noisy_pose(pose, stream_seed(config.seed, u, 2));
    record.seconds.scan = seconds_since(start);

    const MapperUpdate update = mapper.add_scan(scan.points_sensor, believed, scan.fov);
    record.seconds.register_scan = update.seconds_register;
    record.seconds.segment = update.seconds_segment;
    record.seconds.integrate = update.seconds_integrate;
    const perception::PoseError before = perception::pose_error(believed, pose);
    const perception::PoseError after = perception::pose_error(update.T_world_sensor, pose);
    record.pose_error_before = before.translation;
    record.yaw_error_before = before.rotation;
    record.pose_error_after = after.translation;
    record.yaw_error_after = after.rotation;
    record.points = update.points;
    record.object_points = update.object_points;
    record.actual_gain = update.integration.left_unobserved.size();
    record.reentered = update.integration.entered_unobserved.size();
    record.unobserved = mapper.grid().counts().unobserved;
    record.coverage = coverage(mapper.grid(), observable);

    bool stop = k == config.scans;
    if (stop) result.stop_reason = cat("took all ", config.scans, " scans");
    if (!stop) {
      const Plan plan =
          plan_next_view(mapper.grid(), candidates, planner, stream_seed(config.seed, u, 3));
      plan_seconds = plan.seconds;
      double best_gain = 0.0;  // of any candidate, whichever the method chose
      for (const ViewGain& g : plan.gains) best_gain = std::max(best_gain, g.gain);
      if (best_gain < config.min_gain) {
        stop = true;
        result.stop_reason = cat("best predicted gain ", best_gain, " fell below ", config.min_gain,
                                 " after scan ", k);
      }
      view = static_cast<int>(plan.best);
      pose = result.candidates[plan.best];
      predicted = plan.gains[plan.best].gain;
      greedy_predicted = plan.greedy_gains[plan.best];
    }
    result.scans.push_back(record);
    if (on_scan) on_scan(record, config.scans);
    if (stop) break;
  }
  return result;
}

}  // namespace vantage
