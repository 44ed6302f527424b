#pragma once
/// @file
/// Simulated NBV exploration, scan by scan: scan from the current view with a noisy pose,
/// register, segment, integrate, predict every candidate's gain, move to the best. One loop for
/// both of the paper's experiments:
/// - table top (§5.1): one scan per view, the candidates are the scene's ring of views, and the
///   robot walks around the table;
/// - office (§5.2): a 360° sweep at every stop, the candidates are frontier-region centroids on
///   the floor, the robot drives there on a navigation grid, and when a goal cannot be reached it
///   scans as close to it as it got (§5.3.1, a "fallback").

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/experiment/yardstick.hpp"
#include "vantage/map/navigation.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/work.hpp"
#include "vantage/views/candidate_set.hpp"
#include "vantage/views/hemisphere.hpp"

namespace vantage {

/// Settings that only office scenes use (§5.2); the robot's footprint and height come from the
/// scene.
struct OfficeConfig {
  /// Frontier cells lie within this height of the sensor's: the band a level sensor sees out to
  /// its full range in every direction, so its frontier is the edge of what a sweep saw [m].
  double frontier_band = 0.1;
  int min_frontier_cells = 20;       ///< smaller frontier regions are dropped
  double max_frontier_radius = 1.5;  ///< frontier regions are cut into pieces this wide [m]
  /// Obstacles on the navigation grid are occupied cells from this height up to the robot's
  /// height; below it are the floor's own hits and their range noise [m].
  double min_obstacle_height = 0.15;
  bool unknown_blocks = false;  ///< unobserved cells block the robot (false: plan into them)
  /// A candidate whose stop (the goal, or its fallback) lies within this distance of a stop
  /// already taken is dropped: the sweep there would see what that one saw. It also drops the
  /// frontier ring that the sensor's minimum range leaves around the robot [m].
  double min_move = 0.5;
  /// A frontier centroid the robot cannot reach (inside furniture, say) moves to the reachable
  /// cell of its own region nearest it, so the robot scans at that frontier; false keeps the
  /// paper's fallback (§5.3.1): drive as close to the centroid as possible and scan there.
  bool project_stops = true;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The error of a robot's believed pose after each move when not told otherwise: 2 cm, 2 cm,
/// 2 degrees (x, y, yaw).
inline const sim::PoseNoise kDefaultPoseNoise{0.02, 0.02, deg2rad(2.0)};

/// Settings of one exploration run.
struct ExplorationConfig {
  /// Method, alpha, evaluation, search (none: the fastest that serves the method). Its
  /// greedy_reference asks for greedy's count of each view taken (ScanRecord::
  /// greedy_predicted_gain), made after the decision; off unless asked for. The methods that
  /// score by greedy's count give it for free, always.
  PlannerConfig planner;
  /// What each decision may cost (decision_cost.hpp): estimated on the map it is made on and
  /// refused (WorkBudgetError) before it is computed.
  WorkBudget budget;
  MapperConfig mapper;    ///< registration, table segmentation, integration
  int scans = 10;         ///< N, the number of scans to take (the first included)
  double min_gain = 0.0;  ///< stop early once the best predicted gain falls below this
  /// Table top: whether a ring view already taken stays a candidate. Off by default, as an
  /// office never returns to a visited stop: a view's own scan has already turned its line of
  /// sight known, and the literal model's small remaining prediction there (gain behind the
  /// surfaces it saw) would otherwise bring the robot back to scan the same view again.
  bool revisit = false;
  int start = 0;           ///< index into the scene's start poses
  std::uint64_t seed = 1;  ///< sensor noise, pose noise and random choice
  /// Error of the robot's belief after each move (x, y, yaw), replacing the scene's; the first
  /// scan's pose defines the map frame and is exact. Default: 2 cm, 2 cm, 2 degrees.
  std::optional<sim::PoseNoise> pose_noise = kDefaultPoseNoise;
  OfficeConfig office;  ///< used by office scenes only
  /// Fit the probabilistic method's a to the run's own outcomes (--alpha auto, the paper's §6):
  /// before each scan, the expected cells seen of its view under every candidate a of
  /// `observability`; after it, the cells it turned known; each decision takes the a that has
  /// predicted best so far. Off: planner.gain.alpha throughout.
  bool auto_alpha = false;
  ObservabilityFitConfig observability;
  /// Table top and object: the candidate set's name (views/candidate_sets.hpp: ring, hemisphere,
  /// sphere, view-sphere); empty: the scene's own (a table top's ring, an object's view sphere).
  std::string candidates;
  /// The set's radius and view count (CandidateParams; 0: the set's or the scene's own). The
  /// hemisphere's rings are `hemisphere`'s.
  CandidateParams views;
  /// The hemisphere's radii, elevations and spacing; the centre is the scene's target (the
  /// ring's), the base and reach `arm`'s, else the scene's arm's, else unlimited.
  HemisphereConfig hemisphere;
  std::optional<ArmReach> arm;  ///< the hemisphere's arm: overrides the scene's
  /// Table top: decide by the greedy oracle instead of `planner` (issue 36, docs/yardstick.md):
  /// among the same open candidates, with the same travel, the view whose true hit set (its
  /// noise-free scan, SurfaceTruth::candidate_hits) adds the most visible surface cells to the
  /// true hit sets of the start and the views taken; ties to the shorter travel, then the lower
  /// index. Its choices depend on the world only, not on the run's noise or registration.
  bool greedy_oracle = false;
  /// Table top: the yardstick's tolerance [cells], 0 or 1 (yardstick.hpp): surface coverage, its
  /// denominator and the greedy oracle's hit sets count a surface cell covered once a scan point
  /// lies in it (0) or within one cell of it (1, issue 36's definition).
  CoverageTolerance coverage_tolerance = 1;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Wall time of each stage of one scan [s].
struct StageTimes {
  double scan = 0.0;
  double register_scan = 0.0;
  double segment = 0.0;
  double integrate = 0.0;
  double plan = 0.0;        ///< the decision that chose this scan's view, candidates included
  double candidates = 0.0;  ///< ... of which finding the candidates (office: frontiers, travel)
  double reference = 0.0;   ///< ... of which greedy's prediction for the same views (Fig. 11)
  double calibrate = 0.0;   ///< --alpha auto: the scan's view evaluated under every candidate a
};

/// One candidate a decision weighed, as `vantage view` shows it.
struct CandidateRecord {
  int view = -1;  ///< table top: ring index; office: index among that decision's stops
  /// Table top: the ring view; office: the stop's sensor pose, heading along the way there.
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  double predicted_gain = 0.0;  ///< under the method (office: summed over the sweep)
  /// Under greedy, same view [cells]: every candidate's for the methods that score by greedy's
  /// count; otherwise only the chosen candidate's, when PlannerConfig::greedy_reference asks for
  /// it (greedy's reference prediction is made for the view taken, after the decision), none
  /// for the rest.
  std::optional<double> greedy_predicted_gain;
  double predicted_cells = 0.0;  ///< the method's expected cells seen [cells]
  /// The search that decided did not evaluate this candidate in full: its predicted gain and
  /// cells are the swept search's estimate or the pruned search's upper bound (Plan::estimated).
  bool estimated = false;
};

/// Everything recorded after one scan (office: one stop, all steps of its sweep).
struct ScanRecord {
  int scan = 0;   ///< 1-based
  int view = -1;  ///< candidate index taken (-1: a start pose not on the ring)
  /// True pose (office: of the sweep's first step, heading along the way the robot came).
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  std::optional<double> predicted_gain;         ///< under the method (none for the first scan)
  std::optional<double> greedy_predicted_gain;  ///< under greedy, same view [cells]
  /// The method's prediction of the cells the scan sees: the probabilistic method's expected
  /// cells seen E, the other methods' greedy count [cells]
  std::optional<double> predicted_cells;
  std::optional<double> alpha;  ///< the a the probabilistic method chose this view with
  /// The surface model's rates per distance class it chose this view with (SurfaceRateFit).
  std::optional<SurfaceRates> surface_rates;
  /// What decided on this view: the search (swept, pruned, exhaustive) or "sequence"; empty for
  /// the first scan.
  std::string search;
  /// --alpha auto: the view's expected cells seen under each candidate a of the fit, before the
  /// scan (ExplorationConfig::observability.alphas) [cells]
  std::vector<double> calibration;
  std::size_t actual_gain = 0;  ///< cells that left the unobserved set
  std::size_t reentered = 0;    ///< cells that came back into it
  std::size_t unobserved = 0;   ///< unobserved cells after the scan
  double coverage = 0.0;        ///< observed share of the observable surface, in [0, 1]
  /// Table top: share of the visible object surface covered by the registered points so far
  /// (yardstick.hpp: a point within one cell), in [0, 1]; none in an office.
  std::optional<double> surface_coverage;
  /// ... of the whole object surface (raw), in [0, 1].
  std::optional<double> raw_surface_coverage;
  double pose_error_before = 0.0;  ///< translation error of the believed pose [m]
  double pose_error_after = 0.0;   ///< ... after registration [m]
  double yaw_error_before = 0.0;   ///< rotation error of the believed pose [rad]
  double yaw_error_after = 0.0;    ///< ... after registration [rad]
  /// ... of the pose the map holds at the end of the run: after registration, or after a later
  /// scan pinned a scan that had fallen back (MapperConfig::reregister_window) [m], [rad]
  double pose_error_final = 0.0;
  double yaw_error_final = 0.0;
  /// How far the points the scan put into the map land from where they belong (root mean
  /// square; PoseError), under the believed, the registered and the final pose [m]: what the map
  /// suffers.
  double displacement_before = 0.0;
  double displacement_after = 0.0;
  double displacement_final = 0.0;
  /// Where those points lie in the world, at the true pose (for the final displacement).
  perception::PointSpread points_spread;
  /// What registration made of this scan: accepted, or why the guess was kept.
  perception::RegistrationOutcome registration = perception::RegistrationOutcome::kEmptyMap;
  /// Registration's own figures: the posterior's position sigma [m], the correction's squared
  /// Mahalanobis distance, the scan's points paired at the solution and its (thinned) points.
  double registration_sigma = 0.0;
  double registration_mahalanobis2 = 0.0;
  std::size_t registration_pairs = 0;
  std::size_t registration_points = 0;
  /// Earlier scans (1-based) that this scan's registration let pass on a second try; the map was
  /// rebuilt with them at their registered poses before this scan was integrated.
  std::vector<int> reregistered;
  std::size_t points = 0;
  std::size_t object_points = 0;  ///< points integrated (office: thinned to one per cell)
  /// Distance travelled to this view from the previous one [m], by the candidate set's travel
  /// rule (TravelRule: the arm's straight line, the walk around the table, the arc on an
  /// object's view sphere); in an office the path driven on the floor.
  double travel = 0.0;
  /// The planned goal was not reachable, and the robot scanned where it got closest (§5.3.1).
  bool fallback = false;
  std::optional<Eigen::Vector3d> goal;  ///< office: where the planner sent the robot [m]
  /// The sensor's path from the previous view as its carrier travels it (TravelRule::path; an
  /// office: the floor path driven, at the sensor's height), empty for the first scan [m].
  std::vector<Eigen::Vector3d> path;
  int candidates = 0;  ///< candidates the decision chose among
  /// Every candidate of the decision that chose this view, in the decision's order (none for
  /// the first scan).
  std::vector<CandidateRecord> considered;
  StageTimes seconds;
};

/// A finished run.
struct ExplorationResult {
  std::vector<ScanRecord> scans;
  /// The candidate poses: the scene's ring; in an office, the frontier stops of the last decision.
  std::vector<Eigen::Isometry3d> candidates;
  std::string stop_reason;
  std::size_t observable_cells = 0;  ///< the coverage denominator
  /// Table top: the object surface cells and the visible ones, surface_coverage's denominator
  /// (yardstick.hpp) [cells]; 0 in an office.
  std::size_t surface_cells = 0;
  std::size_t visible_surface_cells = 0;
};

struct SurfaceTruth;  // yardstick.hpp

/// Called after each scan, for live progress.
using ScanCallback = std::function<void(const ScanRecord&, int total)>;

namespace detail {
class Explorer;
}  // namespace detail

/// The decision the run's planner would make now, not taken (Exploration::propose).
struct ViewProposal {
  int view = -1;  ///< the candidate it chooses
  /// Every open candidate it weighed, in index order, with its predictions (CandidateRecord).
  std::vector<CandidateRecord> considered;
  double seconds = 0.0;  ///< the decision's wall time [s]
};

/// One exploration run, a scan at a time: the loop explore() runs, and what lets a caller choose
/// the views instead of the run's planner (Python's ExploreEnv, a policy in a sweep). Each step
/// scans, registers, segments and integrates, and records the scan as explore does; the first
/// step scans from the start pose. Keeps references to the scene, the config and the mapper,
/// which must outlive it.
class Exploration {
 public:
  /// Checks the settings and the scene (std::invalid_argument naming what) and computes the run's
  /// truth, as explore does; takes no scan. `surface_truth` as explore's (null: computed here).
  Exploration(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
              const SurfaceTruth* surface_truth = nullptr);
  ~Exploration();
  Exploration(Exploration&&) noexcept;
  Exploration& operator=(Exploration&&) noexcept;

  /// Takes the next scan, from the start pose first and then from the view the planner chooses.
  /// Returns its record (valid until the next step), or null when the run is over (done()).
  const ScanRecord* step();
  /// Table top: takes the next scan from candidate `view`, which the caller chose in
  /// `decision_seconds` [s] (its plan_seconds). Throws std::invalid_argument naming the view
  /// when the run is over, before the first scan (which is the start's: step()), in an office
  /// (its candidates are the planner's frontier stops), for a view out of range or already taken
  /// (unless ExplorationConfig::revisit), and for the greedy oracle's runs.
  const ScanRecord& step(int view, double decision_seconds = 0.0);
  /// Table top: what the planner would choose now among the open candidates, without taking it;
  /// the same decision step() would take. Throws std::invalid_argument when the run is over or
  /// before the first scan.
  ViewProposal propose();

  /// Whether the run is over: every scan asked for taken, every candidate taken, or the
  /// planner's stop (min_gain); result().stop_reason says which.
  bool done() const;
  /// The run so far: the scans taken, the candidates, the coverage denominators.
  const ExplorationResult& result() const;
  /// Table top: which candidates have been taken (the start's too, when it is one).
  const std::vector<bool>& taken() const;
  /// The travel from the current view to each candidate under the run's travel rule [m]; empty
  /// before the first scan and in an office.
  std::vector<double> travel() const;
  const Mapper& mapper() const;
  /// Moves the result out; the run is spent after it.
  ExplorationResult finish();

 private:
  std::unique_ptr<detail::Explorer> explorer_;
};

/// Runs one exploration of a simulated scene and returns its records and the final mapper.
ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan = {});
/// The same with the scene's surface truth for this candidate set computed beforehand
/// (compute_surface_truth over the run's candidates), e.g. shared by a sweep's trials of one
/// scene; null computes it. Throws std::invalid_argument when its grid is not the scene's.
ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan, const SurfaceTruth* surface_truth);

/// What a chooser outside the run's planner picked: a candidate's index, and the time it took to
/// pick it [s] (the scan's plan_seconds).
struct ViewChoice {
  int view = -1;
  double seconds = 0.0;
};

/// Chooses the next view of a table-top run from the run so far (a Python policy, say).
using ViewChooser = std::function<ViewChoice(const Exploration& run)>;

/// A table-top run whose views after the start's are chosen by `choose` rather than the planner
/// (Exploration::step(view)): the same loop, seeds and records as explore's otherwise. Throws
/// what Exploration::step(view) throws for a choice it refuses, and what `choose` throws.
ExplorationResult explore_choosing(const sim::Scene& scene, const ExplorationConfig& config,
                                   Mapper& mapper, const ViewChooser& choose,
                                   const SurfaceTruth* surface_truth = nullptr);

/// The candidate set a run takes its views from: config.candidates, else the scene's own (a table
/// top's ring, an office's stops, an object's view-sphere).
std::string run_candidate_set(const sim::Scene& scene, const ExplorationConfig& config);

/// The candidate views of a table-top or object run and the rule of travel between them, from
/// the registry (views/candidate_sets.hpp): the scene's ring, an arm's hemisphere
/// (run_hemisphere), a sphere, or an object's view sphere.
PlacedViews run_candidate_views(const sim::Scene& scene, const ExplorationConfig& config);

/// run_candidate_views' poses.
std::vector<Eigen::Isometry3d> run_candidates(const sim::Scene& scene,
                                              const ExplorationConfig& config);

/// run_candidate_views' rule: how the run measures travel between views [m].
TravelRule run_travel_rule(const sim::Scene& scene, const ExplorationConfig& config);

/// The mapper settings a scene calls for: registration weighed against the explorer's default
/// pose noise; table segmentation for table tops; for offices, each stop's sweep thinned to one
/// point per cell and registered where it overlaps the map, at the map's resolution.
MapperConfig default_mapper_config(const sim::Scene& scene);

/// The a a method explores with when none is given, the one source of explore's and bench's
/// defaults: the survival reading fitted online from kSurvivalAlpha (auto, with
/// survival_fit_config), the others the paper's a for the scene's kind, `paper`.
AlphaSetting default_alpha_setting(PlannerMethod method, double paper);

/// The registration prior of a robot whose believed pose errs by `noise` (sigmas of x, y, yaw).
perception::PoseSigma odometry_prior(const sim::PoseNoise& noise);

/// The hemisphere a run with the hemisphere candidate set takes its views from: `config.hemisphere`
/// centred on the scene's target, with `config.arm`, else the scene's arm, as its reach.
HemisphereConfig run_hemisphere(const sim::Scene& scene, const ExplorationConfig& config);

/// The frusta that plan a stop's 360° sweep: one per step of the scene's sweep, each as wide as
/// the yaw step (2 pi / steps) when the sensor is at least that wide, so they tile the sweep
/// without overlap and a stop counts each cell once (up to cells on a shared boundary plane).
/// A narrower sensor keeps its own width (the sweep then has gaps, and still no overlap).
std::vector<Frustum> sweep_frusta(const sim::Scene& scene, const Eigen::Isometry3d& T_world_sensor);

}  // namespace vantage
