#pragma once
/// @file
/// One exploration run's loop (exploration.hpp's explore): the Explorer and what its steps share.
/// exploration.cpp holds the loop and the table top's decisions, exploration_office.cpp an
/// office's sweeps and frontier stops. Included by those .cpp files only.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>

#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/gain/models/surface_rates.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/sim/ground_truth.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/frontier.hpp"

namespace vantage::detail {

using Clock = std::chrono::steady_clock;

/// Seeds of the independent random streams of one run: scan k's sensor noise, its pose noise,
/// and the random choice after it. Mixing keeps runs with neighbouring seeds unrelated.
inline std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t scan, std::uint64_t stream) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL + scan * 0xBF58476D1CE4E5B9ULL + stream;
  z = (z ^ (z >> 31)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 29);
}

/// Share of the observable surface cells that the map holds as occupied.
inline double coverage(const OccupancyGrid& grid, const std::vector<std::uint32_t>& observable) {
  if (observable.empty()) return 0.0;
  std::size_t seen = 0;
  for (const std::uint32_t i : observable) seen += grid.state(i) == CellState::kOccupied;
  return static_cast<double>(seen) / static_cast<double>(observable.size());
}

/// Where the next scan is taken, and what the decision recorded.
struct Decision {
  bool stop = false;
  std::string stop_reason;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< true pose of the next scan
  int view = -1;
  std::optional<double> predicted, greedy_predicted;
  std::optional<double> predicted_cells;      ///< the method's prediction in cells seen
  std::optional<double> alpha;                ///< the a the probabilistic method decided with
  std::optional<SurfaceRates> surface_rates;  ///< the surface model's rates it decided with
  std::string search;                         ///< what decided: a search's name, or "sequence"
  double seconds = 0.0, candidate_seconds = 0.0, reference_seconds = 0.0;
  double travel = 0.0;
  bool fallback = false;
  std::optional<Eigen::Vector3d> goal;
  std::vector<Eigen::Vector3d> path;  ///< ScanRecord::path
  int candidates = 0;
  std::vector<CandidateRecord> considered;
};

/// One exploration run. Table top and office share this loop; they differ in how a place is
/// observed (one scan, or a sweep) and where the candidates come from (the ring, or frontiers).
class Explorer {
 public:
  Explorer(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
           const SurfaceTruth* surface_truth);

  /// Exploration::step: the start's scan first, then the planner's choice; null when over.
  const ScanRecord* step();
  /// Exploration::step(view): the caller's choice.
  const ScanRecord& step(int view, double decision_seconds);
  /// Exploration::propose: the planner's table-top decision, not taken.
  Decision propose();

  bool done() const { return done_; }
  const ExplorationResult& result() const { return result_; }
  ExplorationResult& result() { return result_; }
  const std::vector<bool>& taken() const { return taken_; }
  const Mapper& mapper() const { return mapper_; }
  /// Table top: the travel from the current view to each candidate [m]; empty before the first
  /// scan and in an office.
  std::vector<double> travel() const;

 private:
  /// Takes the scan `next` decided on, and records it; ends the run after the last scan asked
  /// for, or once no candidate is left.
  const ScanRecord& take(Decision next);

  /// Table top: marks the chosen view taken (the greedy oracle: its true hits hit).
  void commit_view(std::size_t view);

  static sim::Scene noisy(const sim::Scene& scene, const ExplorationConfig& config);

  /// What the mapper did with a scan taken from the true pose `truth`.
  static void record_update(const MapperUpdate& update, const Eigen::Isometry3d& truth,
                            ScanRecord& record);

  /// Table top: one scan from the view.
  void observe_view(int k, ScanRecord& record);

  /// The final pose errors of the earlier scans `update` registered again.
  void record_reregistered(const MapperUpdate& update, ScanRecord& record);

  /// Office: a 360° sweep at the stop, one scan of many views for the mapper.
  void observe_sweep(int k, ScanRecord& record);

  /// Where an office's next stops are found (the stops set): the map and the robot as it believes
  /// it stands.
  CandidateSite stop_site() const;
  /// The frusta a scan from `pose` covers: the sensor's, or an office stop's whole sweep.
  std::vector<Frustum> views_at(const Eigen::Isometry3d& pose) const;

  /// Greedy's prediction for the chosen candidate (Fig. 11's reference): the plan's own when the
  /// method scored by greedy's count, else, when the run's PlannerConfig::greedy_reference asks,
  /// evaluated now for that candidate's views only (adding the time it took to
  /// `d.reference_seconds`); else none.
  std::optional<double> greedy_of(const Plan& plan, const Candidate& chosen, std::size_t best,
                                  Decision& d) const;

  /// The chosen candidate's predictions: in the method's own units, in cells seen, greedy's.
  void record_prediction(const Plan& plan, const Candidate& chosen, std::size_t best,
                         Decision& d) const;

  /// What the decision recorded of candidate `j`.
  CandidateRecord considered(const Plan& plan, std::size_t j, int view,
                             const Eigen::Isometry3d& pose, const Decision& d) const;

  /// Table top: every ring view, scored by the method; the robot walks around the table. Takes
  /// nothing (commit_view does).
  Decision plan_view(const ScanRecord& current, std::uint64_t seed);

  /// Table top, greedy oracle (ExplorationConfig::greedy_oracle): the open candidate whose true
  /// hit set adds the most visible surface cells to the true hit sets of the start and the views
  /// taken; its gain is that count [cells].
  Decision oracle_view(const ScanRecord& current, const std::vector<Candidate>& open,
                       const std::vector<std::size_t>& index, Decision d) const;

  /// Office: a stop at every frontier region's centroid, its travel on the map's navigation
  /// grid, its gain over the frusta of its sweep; then the drive there, in the true world.
  Decision plan_stop(int k, std::uint64_t seed);

 private:
  const sim::Scene& scene_;
  const ExplorationConfig& config_;
  Mapper& mapper_;
  bool office_;
  std::optional<ObservabilityFit> fit_;        ///< --alpha auto
  std::optional<SurfaceRateFit> surface_fit_;  ///< the surface model's rates, always fitted
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
  bool done_ = false;        ///< the run is over
  // Office:
  NavigationConfig navigation_;
  FrontierConfig frontier_;
  NavigationGrid true_navigation_{Eigen::Vector2d::Zero(), 1.0, {1, 1}, {0}, 1.0};
  std::vector<Eigen::Vector2d> stops_;  ///< believed positions of the stops taken [m]
  Eigen::Vector2d position_ = Eigen::Vector2d::Zero();       ///< believed position [m]
  Eigen::Vector2d true_position_ = Eigen::Vector2d::Zero();  ///< [m]
  double yaw_ = 0.0;                                         ///< believed heading [rad]
};

}  // namespace vantage::detail
