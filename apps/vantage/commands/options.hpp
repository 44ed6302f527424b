#pragma once
/// @file
/// Options that several subcommands share (explore, bench, plan): how to choose a view and how
/// to build the map.

#include <CLI/CLI.hpp>
#include <string>

#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::cli {

/// Help of --no-stop-projection (explore and bench office).
/// --greedy-reference, explore's and bench's.
inline constexpr const char* kGreedyReferenceHelp =
    "also predict greedy's count for each view taken, beside the method's prediction "
    "(greedy_predicted_gain, the paper's Fig. 11); on the early scans it costs more than the "
    "decision";
inline constexpr const char* kNoStopProjectionHelp =
    "keep the paper's fallback for a frontier centroid the robot cannot reach (drive as close "
    "as possible, section 5.3.1) instead of moving it to its region's nearest reachable cell";

/// --method, --alpha, --objective, --evaluation, --search, --epsilon, --lambda, --threads and
/// the sequence's and the swept search's options: the library's PlanningSettings, which also
/// builds the PlannerConfig (the one builder the CLI and Python share).
struct PlanningOptions : PlanningSettings {
  /// `search`: offer --search (explore, bench, plan).
  void add_to(CLI::App& cmd, bool search = true);
  /// --alpha as a setting; without it `literal`. Throws UsageError naming the option.
  AlphaSetting alpha_setting(double literal = kTableTopAlpha) const;
  /// The decision's settings; throws UsageError naming the option (exit 2), before any work.
  PlannerConfig planner_config(double literal_alpha = kTableTopAlpha) const;
};

/// --candidates (the registry's sets placed around a scene), --views, --view-radius, --arm-base,
/// --reach, --view-spacing, and the yardstick over them, --coverage-tolerance (explore, bench).
struct CandidateOptions {
  std::string candidates;    ///< empty: the scene's own (ring; an object's view-sphere)
  int views = 0;             ///< 0: the set's own
  double view_radius = 0.0;  ///< [m]; 0: the set's own
  std::string arm_base;      ///< "x,y,z" [m]; empty: the scene's arm
  double reach = 0.0;        ///< [m]; 0: the scene's arm
  double spacing = HemisphereConfig{}.spacing;  ///< the hemisphere's view spacing [m]
  std::string radii;                            ///< "r1,r2,..." [m]; empty: HemisphereConfig's
  std::string coverage_tolerance;  ///< "0", "1" [cells] or "5mm"; empty: the scene kind's own

  double object_radius = sim::ObjectProtocol{}.object_radius;  ///< [m]

  void add_to(CLI::App& cmd);
  /// Sets the candidate set, the hemisphere and the arm, and the yardstick's tolerance (the
  /// scene kind's own unless given: 1 cell on a table top, 0 for objects, MA-SCVP's); throws
  /// UsageError naming the option.
  void apply(ExplorationConfig& config, sim::SceneKind kind) const;
  /// The object protocol these options ask for (--views, --view-radius, --object-radius).
  sim::ObjectProtocol object_protocol() const;
};

/// The most threads an option asks for; more is a typo, not a machine.
inline constexpr int kMaxThreads = 1024;

/// The most scans (or trials) an option asks for.
inline constexpr int kMaxScans = 100000;

/// The largest index of a start pose or candidate view an option names.
inline constexpr int kMaxIndex = 1000000;

/// --threads/-j: 0 (all cores) .. kMaxThreads.
void add_threads_option(CLI::App& cmd, int& threads, const std::string& description);

/// The ground truth's: a byte of occupancy a cell and the surface lists, with room to spare.
inline constexpr double kGroundTruthBytesPerCell = 8.0;

/// Bytes a cell costs plan and explore at their peak with `threads` threads (0 = all cores):
/// the measured figure of vantage::mapping_bytes_per_cell (vantage/util/memory.hpp,
/// docs/robustness.md "Memory").
double grid_bytes_per_cell(int threads);
/// What a run holds besides its grid: code, scene meshes, the sensor's images [bytes].
inline constexpr double kFixedRunBytes = 200.0 * 1024 * 1024;

/// --max-memory SIZE (bytes, or with K, M, G, T: 512M, 4G); 0, the default, is the memory the
/// machine has available when the run starts.
void add_memory_option(CLI::App& cmd, std::uint64_t& bytes);

/// --max-work SECONDS: the estimated work one decision may take (docs/robustness.md, "Work").
void add_work_option(CLI::App& cmd, double& seconds);

/// The budget of --max-work and --max-memory.
WorkBudget work_budget(double max_work, std::uint64_t max_memory);

/// Refuses (WorkBudgetError, exit 2) a decision `cost` the budget does not allow, beside a grid
/// of `cells` cells at the mapping figure (threads as --threads).
void check_decision_budget(const DecisionCost& cost, const WorkBudget& budget, std::uint64_t cells,
                           int threads);

/// --integration, --no-icp, --no-segmentation, --no-hole-filling.
struct MappingOptions {
  std::string integration = "paper";
  bool icp = true;
  bool segmentation = true;
  bool hole_filling = true;

  void add_to(CLI::App& cmd);
  /// The scene's defaults with the options applied (segmentation only where the scene has a
  /// table).
  MapperConfig mapper_config(const sim::Scene& scene) const;
};

}  // namespace vantage::cli
