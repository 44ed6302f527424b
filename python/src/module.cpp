// The `vantage._vantage` extension module; the `vantage` package re-exports it.

#include "bindings.hpp"

PYBIND11_MODULE(_vantage, m) {
  m.doc() =
      "Vantage: next-best-view planning in cluttered 3D scenes (Potthast & Sukhatme). Poses are "
      "4 x 4 rigid transforms T_world_sensor (sensor frame: x forward, y left, z up), points N x 3 "
      "arrays [m], grid arrays indexed [i, j, k]. Errors raise ValueError for bad arguments, "
      "OSError for files that cannot be read or written, RuntimeError otherwise, each with the "
      "library's one-line message.";
  vantage::python::bind_map(m);
  vantage::python::bind_gain(m);
  vantage::python::bind_plan(m);
  vantage::python::bind_sim(m);
}
