#pragma once
/// @file
/// The parts of the `vantage._vantage` module, one per binding file.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

namespace vantage {
class OccupancyGrid;
struct MapperConfig;
struct PlannerConfig;
}  // namespace vantage

namespace vantage::python {

/// GridSpec, SensorFov, OccupancyGrid and its integration and OctoMap files.
void bind_map(pybind11::module_& m);
/// Each cell's class (CellState) as uint8, [i, j, k] (OccupancyGrid.states; ExploreEnv's cells).
pybind11::array_t<std::uint8_t> state_array(const OccupancyGrid& grid);
/// Each cell's stored log-odds as float32, [i, j, k] (OccupancyGrid.log_odds; ExploreEnv's).
pybind11::array_t<float> log_odds_array(const OccupancyGrid& grid);
/// The ray model and view gains.
void bind_gain(pybind11::module_& m);
/// PlannerConfig, the decision's settings.
void bind_planner_config(pybind11::module_& m);
/// What PlannerConfig() is, and what the calls given no config take: `vantage plan`'s defaults,
/// its method the default one for views around objects with the robot's pose known or not
/// (default_planner_method).
PlannerConfig default_planner_config(bool knows_pose);
/// Candidate poses: look_at, the ring, the sphere, the candidate sets, and the grid of a region.
void bind_candidates(pybind11::module_& m);
/// The decision: Plan, plan_next_view, and plan (clouds mapped, then the decision).
void bind_plan(pybind11::module_& m);
/// The Mapper, manifests and the clouds they list, point cloud files.
void bind_mapping(pybind11::module_& m);
/// The mapping settings `vantage plan` derives from a manifest with these options.
MapperConfig recorded_mapper_config(const std::string& integration, bool table_segmentation,
                                    bool icp, int num_threads);
/// Simulated scenes, sensors and scans.
void bind_sim(pybind11::module_& m);
/// The exploration loop a scan at a time (ExploreEnv's engine) and a Python policy's sweep.
void bind_env(pybind11::module_& m);

}  // namespace vantage::python
