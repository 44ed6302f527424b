#include "vantage/experiment/exploration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/detail/explorer.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace detail {

Explorer::Explorer(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                   const SurfaceTruth* surface_truth)
    : scene_(scene),
      config_(config),
      mapper_(mapper),
      office_(scene.kind == sim::SceneKind::kOffice),
      world_(noisy(scene, config), sim::WorldConfig{config.planner.gain.num_threads}) {
  planner_ = config.planner;
  // NOTE: Fig. 11 compares greedy's prediction with the method's on the view taken; greedy's
  // is made for that view alone, after the decision (greedy_of), when the run's planner asks for
  // it, not for every candidate.
  planner_.greedy_reference = false;
  // NOTE: the stop on the best predicted gain reads every candidate's, far ones too.
  planner_.gain_of_every_candidate = config.min_gain > 0.0;
  if (config.auto_alpha && has_observability(planner_.method)) {
    fit_.emplace(config.observability);
    planner_.gain.alpha = fit_->alpha();
  }
  if (method_traits(planner_.method.gain).surface_cells) surface_fit_.emplace();
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
    const PlacedViews views = run_candidate_views(scene, config);
    for (const Eigen::Isometry3d& pose : views.poses) {
      ring_.push_back({Frustum(pose, scene.fov())});
      result_.candidates.push_back(pose);
    }
    // NOTE: a sequence's tour between two views costs what the robot's move between them does.
    planner_.sequence.travel = views.travel;
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
                                     std::span<const Eigen::Isometry3d>(result_.candidates));
  result_.observable_cells = truth_.observable.size();
  if (!office_) {
    if (surface_truth == nullptr) {
      check_surface_truth(scene, result_.candidates.size(), config.budget);
      own_surface_ = compute_surface_truth(world_, result_.candidates, config.coverage_tolerance,
                                           config.planner.gain.num_threads);
      surface_truth = &*own_surface_;
    }
    if (!(surface_truth->grid == scene.grid) ||
        surface_truth->candidate_hits.size() != result_.candidates.size() ||
        surface_truth->tolerance != config.coverage_tolerance) {
      throw std::invalid_argument(cat("the surface truth given for scene '", scene.name,
                                      "' is for another grid, candidate set or tolerance"));
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

const ScanRecord* Explorer::step() {
  if (done_) return nullptr;
  Decision next;
  if (result_.scans.empty()) {
    next.pose = scene_.start_poses[static_cast<std::size_t>(config_.start)];
    for (std::size_t i = 0; i < result_.candidates.size(); ++i) {
      if (result_.candidates[i].isApprox(next.pose, 1e-9)) next.view = static_cast<int>(i);
    }
    if (next.view >= 0 && !taken_.empty()) taken_[static_cast<std::size_t>(next.view)] = true;
    return &take(std::move(next));
  }
  const ScanRecord& current = result_.scans.back();
  const std::uint64_t seed = stream_seed(config_.seed, static_cast<std::uint64_t>(current.scan), 3);
  next = office_ ? plan_stop(current.scan, seed) : plan_view(current, seed);
  if (next.stop) {
    done_ = true;
    result_.stop_reason = next.stop_reason;
    return nullptr;
  }
  if (!office_) commit_view(static_cast<std::size_t>(next.view));
  return &take(std::move(next));
}

const ScanRecord& Explorer::step(int view, double decision_seconds) {
  if (done_) {
    throw std::invalid_argument(
        cat("the run is over (", result_.stop_reason, "): view ", view, " cannot be taken"));
  }
  if (result_.scans.empty()) {
    throw std::invalid_argument(
        cat("the first scan is the start pose's (step()), not view ", view, "'s"));
  }
  if (office_) {
    throw std::invalid_argument(cat("scene '", scene_.name,
                                    "' is an office: its candidates are the planner's frontier "
                                    "stops, not views to choose by index"));
  }
  if (config_.greedy_oracle) {
    throw std::invalid_argument("the greedy oracle's runs choose their own views");
  }
  const int n = static_cast<int>(ring_.size());
  if (view < 0 || view >= n) {
    throw std::invalid_argument(cat("view ", view, " is out of range: scene '", scene_.name,
                                    "' has ", n, " candidate views (0 to ", n - 1, ")"));
  }
  const auto i = static_cast<std::size_t>(view);
  if (taken_[i] && !config_.revisit) {
    throw std::invalid_argument(cat("view ", view, " has been taken already"));
  }
  if (!std::isfinite(decision_seconds) || decision_seconds < 0.0) {
    throw std::invalid_argument(
        cat("the decision's time must be a finite number of seconds >= 0, got ", decision_seconds));
  }
  const ScanRecord& current = result_.scans.back();
  Decision d;
  d.view = view;
  d.pose = result_.candidates[i];
  d.travel = planner_.sequence.travel(current.T_world_sensor.translation(), ring_[i].view.origin());
  d.candidates = static_cast<int>(
      config_.revisit ? taken_.size() : std::count(taken_.begin(), taken_.end(), false));
  d.seconds = decision_seconds;
  d.search = "caller";
  commit_view(i);
  return take(std::move(d));
}

Decision Explorer::propose() {
  if (done_) throw std::invalid_argument(cat("the run is over (", result_.stop_reason, ")"));
  if (result_.scans.empty()) {
    throw std::invalid_argument("the first scan is the start pose's: nothing to propose yet");
  }
  if (office_) {
    throw std::invalid_argument(
        cat("scene '", scene_.name, "' is an office: propose() is for table tops"));
  }
  const ScanRecord& current = result_.scans.back();
  return plan_view(current, stream_seed(config_.seed, static_cast<std::uint64_t>(current.scan), 3));
}

std::vector<double> Explorer::travel() const {
  std::vector<double> out;
  if (office_ || result_.scans.empty()) return out;
  const Eigen::Vector3d here = result_.scans.back().T_world_sensor.translation();
  for (const Candidate& c : ring_) out.push_back(planner_.sequence.travel(here, c.view.origin()));
  return out;
}

void Explorer::commit_view(std::size_t view) {
  taken_[view] = true;
  if (!config_.greedy_oracle) return;
  std::vector<std::uint32_t> hit;
  std::set_union(truly_hit_.begin(), truly_hit_.end(), surface_->candidate_hits[view].begin(),
                 surface_->candidate_hits[view].end(), std::back_inserter(hit));
  truly_hit_ = std::move(hit);
}

sim::Scene Explorer::noisy(const sim::Scene& scene, const ExplorationConfig& config) {
  sim::Scene s = scene;
  if (config.pose_noise) s.pose_noise = *config.pose_noise;
  return s;
}

}  // namespace detail

ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan) {
  return explore(scene, config, mapper, on_scan, nullptr);
}

Exploration::Exploration(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                         const SurfaceTruth* surface_truth) {
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
    if (!config.candidates.empty()) {
      throw std::invalid_argument(cat("scene '", scene.name,
                                      "' is an office: its candidates are frontier stops, not "
                                      "the ",
                                      config.candidates));
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
  explorer_ = std::make_unique<detail::Explorer>(scene, config, mapper, surface_truth);
}

Exploration::~Exploration() = default;
Exploration::Exploration(Exploration&&) noexcept = default;
Exploration& Exploration::operator=(Exploration&&) noexcept = default;

const ScanRecord* Exploration::step() { return explorer_->step(); }

const ScanRecord& Exploration::step(int view, double decision_seconds) {
  return explorer_->step(view, decision_seconds);
}

ViewProposal Exploration::propose() {
  detail::Decision d = explorer_->propose();
  return {d.view, std::move(d.considered), d.seconds};
}

bool Exploration::done() const { return explorer_->done(); }
const ExplorationResult& Exploration::result() const { return explorer_->result(); }
const std::vector<bool>& Exploration::taken() const { return explorer_->taken(); }
std::vector<double> Exploration::travel() const { return explorer_->travel(); }
const Mapper& Exploration::mapper() const { return explorer_->mapper(); }
ExplorationResult Exploration::finish() { return std::move(explorer_->result()); }

ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan, const SurfaceTruth* surface_truth) {
  Exploration run(scene, config, mapper, surface_truth);
  while (const ScanRecord* record = run.step()) {
    if (on_scan) on_scan(*record, config.scans);
  }
  return run.finish();
}

ExplorationResult explore_choosing(const sim::Scene& scene, const ExplorationConfig& config,
                                   Mapper& mapper, const ViewChooser& choose,
                                   const SurfaceTruth* surface_truth) {
  Exploration run(scene, config, mapper, surface_truth);
  run.step();
  while (!run.done()) {
    const ViewChoice choice = choose(run);
    run.step(choice.view, choice.seconds);
  }
  return run.finish();
}

}  // namespace vantage
