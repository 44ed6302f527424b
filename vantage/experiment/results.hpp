#pragma once
/// @file
/// What an exploration leaves behind: `scans.csv` (a stable interface), `run.json`, the map as an
/// OctoMap tree, the registered object cloud, and the data its pictures are drawn from.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/experiment/exploration.hpp"

namespace vantage {

/// The header of scans.csv. Other tools read it: append columns, never change these.
inline constexpr std::string_view kScansCsvHeader =
    "scene,method,alpha,trial,scan,view,predicted_gain,greedy_predicted_gain,actual_gain,"
    "unobserved,coverage,plan_seconds";

/// Which run a row belongs to.
struct RunLabel {
  std::string scene;
  PlannerMethod method = PlannerMethod::kProbabilistic;
  double alpha = 0.997;  ///< written only for the probabilistic method
  int trial = 0;
};

/// The rows of scans.csv for one run, without the header; numbers to 12+ significant digits,
/// an empty field where a value does not exist (no prediction before the first scan).
std::string scans_csv_rows(const RunLabel& label, const std::vector<ScanRecord>& scans);

/// Writes scans.csv, run.json, map.bt, cloud.pcd (when any object point was seen) and
/// map_cells.csv (the occupied cells, for the picture) into `dir`, which must exist. The caller
/// writes into a fresh temporary folder and renames it into place, so a run's folder is whole or
/// absent.
void write_run_files(const std::filesystem::path& dir, const sim::Scene& scene,
                     const ExplorationConfig& config, const ExplorationResult& result,
                     const Mapper& mapper);

}  // namespace vantage
