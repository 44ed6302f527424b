#pragma once
/// @file
/// The parts of the `vantage._vantage` module, one per binding file.

#include <pybind11/pybind11.h>

namespace vantage {
struct PlannerConfig;
}  // namespace vantage

namespace vantage::python {

/// GridSpec, SensorFov, OccupancyGrid and its integration and OctoMap files.
void bind_map(pybind11::module_& m);
/// The ray model and view gains.
void bind_gain(pybind11::module_& m);
/// PlannerConfig, the decision's settings.
void bind_planner_config(pybind11::module_& m);
/// What PlannerConfig() is, and what the calls given no config take: `vantage plan`'s defaults,
/// its method the default one for views around objects with the robot's pose known or not
/// (default_planner_method).
PlannerConfig default_planner_config(bool knows_pose);
/// Candidate poses, the planner, the mapper and recorded data.
void bind_plan(pybind11::module_& m);
/// Simulated scenes, sensors and scans.
void bind_sim(pybind11::module_& m);
/// The exploration loop a scan at a time (ExploreEnv's engine) and a Python policy's sweep.
void bind_env(pybind11::module_& m);

}  // namespace vantage::python
