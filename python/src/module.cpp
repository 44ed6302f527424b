// The `vantage._vantage` extension module; the `vantage` package re-exports it.

#include "bindings.hpp"
#include "vantage/util/memory.hpp"

PYBIND11_MODULE(_vantage, m) {
  m.doc() =
      "Vantage: next-best-view planning in cluttered 3D scenes (Potthast & Sukhatme). Poses are "
      "4 x 4 rigid transforms T_world_sensor (sensor frame: x forward, y left, z up), points N x 3 "
      "arrays [m], grid arrays indexed [i, j, k]. Errors raise ValueError for bad arguments and "
      "malformed files, OSError for files that cannot be read or written, MemoryError for a grid "
      "the memory budget cannot hold (checked before it is allocated), RuntimeError otherwise, "
      "each with the library's one-line message.";
  // NOTE: translators registered last are tried first: this one before pybind11's own, which
  // would make the budget's refusal a RuntimeError.
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const vantage::MemoryBudgetError& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    }
  });
  vantage::python::bind_map(m);
  vantage::python::bind_gain(m);
  vantage::python::bind_plan(m);
  vantage::python::bind_sim(m);
}
