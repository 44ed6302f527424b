#pragma once
/// @file
/// run.json, the document `vantage explore` leaves beside scans.csv (results.hpp,
/// write_run_files). Included by results.cpp only.

#include <nlohmann/json.hpp>

#include "vantage/experiment/exploration.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::detail {

/// run.json of a run of `config` on `scene`, mapped in the grid `spec`: the scene, the settings,
/// every scan with its candidates, the candidate views, and the units.
nlohmann::json run_json(const sim::Scene& scene, const GridSpec& spec,
                        const ExplorationConfig& config, const ExplorationResult& result);

}  // namespace vantage::detail
