#pragma once
/// @file
/// What an exploration leaves behind: `scans.csv` (a stable interface), `run.json`, the map as an
/// OctoMap tree, the registered object cloud, and the data its pictures are drawn from.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/experiment/exploration.hpp"
#include "vantage/gain/ray_model.hpp"

namespace vantage {

/// The header of scans.csv. Other tools read it: append columns, never change these.
/// travel_m is the distance travelled to the scan's view (table top: the walk along the ring;
/// office: the path driven), fallback 1 where the planned goal was not reachable (§5.3.1).
/// The pose errors are the sensor's position error; displacement_* how far the scan's points land
/// from where they belong (root mean square), under the believed, registered and final pose.
/// `alpha` is the probabilistic method's setting (a number or "auto"), `alpha_used` the a its
/// decision for this scan took; predicted_gain is in bits for the probabilistic method and in
/// cells for the others, predicted_cells always in cells (E, or greedy's count), the unit of
/// actual_gain; `objective` is what the probabilistic method ranked by (bits or cells).
/// surface_coverage is the share of the visible object surface covered by the registered points
/// (a point within one cell; docs/yardstick.md), raw_surface_coverage the share of all object
/// surface, both in [0, 1] and empty in an office. method is `greedy-oracle` for the greedy
/// oracle (ExplorationConfig::greedy_oracle).
inline constexpr std::string_view kScansCsvHeader =
    "scene,method,alpha,trial,scan,view,predicted_gain,greedy_predicted_gain,actual_gain,"
    "unobserved,coverage,plan_seconds,travel_m,fallback,predicted_cells,alpha_used,objective,"
    "pose_error_before_m,pose_error_after_m,pose_error_final_m,register_seconds,segment_seconds,"
    "integrate_seconds,reference_seconds,displacement_before_m,displacement_after_m,"
    "displacement_final_m,surface_coverage,raw_surface_coverage";

/// The fields of a scans.csv row before surface_coverage was appended: a trial file of an older
/// sweep holds this many, and the sweep's scans.csv leaves the newer ones empty.
inline constexpr std::size_t kScansCsvFieldsBeforeSurface = 27;

/// The method name of the greedy oracle in scans.csv and on the command line.
inline constexpr std::string_view kGreedyOracleName = "greedy-oracle";

/// The units a method's numbers are in, the one source of plan.json's and run.json's `units`
/// and of the terminal's (docs/model.md, "Bits are not cells").
struct GainUnits {
  std::string_view predicted_gain;  ///< the method's own gain: bits, cells or metric
  std::string_view score;           ///< what it ranks by: bits, cells, metric or -m (yamauchi)
  /// What the gain ranks by: the probabilistic and survival methods' objective (bits or
  /// cells); cells for the methods that count cells and the surface model (the surface a scan
  /// adds); metric for the field's other metrics.
  std::string_view objective;
};

/// The units of `planner`'s method under its objective.
GainUnits gain_units(const PlannerConfig& planner);

/// The sensor as plan.json and run.json record it: horizontal_fov_deg, vertical_fov_deg,
/// min_range_m, max_range_m.
nlohmann::json sensor_json(const SensorFov& fov);

/// plan.json's and run.json's `units`: predicted_gain, score, predicted_cells, greedy_gain,
/// travel (and the rest a caller adds).
nlohmann::json units_json(const GainUnits& units);

/// Which run a row belongs to.
struct RunLabel {
  std::string scene;
  PlannerMethod method = PlannerMethod::kProbabilistic;
  AlphaSetting alpha;                              ///< written only for the probabilistic method
  GainObjective objective = GainObjective::kBits;  ///< written only for the probabilistic method
  int trial = 0;
  bool greedy_oracle = false;  ///< written as kGreedyOracleName instead of `method`
  /// An external policy's name (ExternalPolicy), written instead of `method` when not empty.
  std::string policy = {};
};

/// The label of an exploration run with `config` on scene `scene`, trial = its start.
RunLabel run_label(std::string scene, const ExplorationConfig& config);

/// The rows of scans.csv for one run, without the header; numbers to 12+ significant digits,
/// an empty field where a value does not exist (no prediction before the first scan).
std::string scans_csv_rows(const RunLabel& label, const std::vector<ScanRecord>& scans);

/// Writes scans.csv, run.json, map.bt, cloud.pcd (when any object point was seen),
/// map_cells.csv (the occupied cells, for the picture) and, for offices, floor_map.txt (a top
/// view of the floor: unknown, seen free and obstacle columns) into `dir`, which must exist. The
/// caller writes into a fresh temporary folder and renames it into place, so a run's folder is
/// whole or absent.
void write_run_files(const std::filesystem::path& dir, const sim::Scene& scene,
                     const ExplorationConfig& config, const ExplorationResult& result,
                     const Mapper& mapper);

}  // namespace vantage
