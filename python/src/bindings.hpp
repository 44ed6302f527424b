#pragma once
/// @file
/// The parts of the `vantage._vantage` module, one per binding file.

#include <pybind11/pybind11.h>

namespace vantage::python {

/// GridSpec, SensorFov, OccupancyGrid and its integration and OctoMap files.
void bind_map(pybind11::module_& m);
/// The ray model and view gains.
void bind_gain(pybind11::module_& m);
/// Candidate poses, the planner, the mapper and recorded data.
void bind_plan(pybind11::module_& m);
/// Simulated scenes, sensors and scans.
void bind_sim(pybind11::module_& m);

}  // namespace vantage::python
