// The `vantage._vantage` extension module; the `vantage` package re-exports it.

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"
#include "vantage/util/work.hpp"

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
    } catch (const vantage::WorkBudgetError& e) {
      PyErr_SetString(e.memory ? PyExc_MemoryError : PyExc_ValueError, e.what());
    }
  });
  m.def(
      "set_budget",
      [](const pybind11::int_& max_memory, double max_work) {
        // NOTE: a negative or huge max_memory is a range error (ValueError), not a type error.
        const unsigned long long bytes = PyLong_AsUnsignedLongLong(max_memory.ptr());
        if (PyErr_Occurred()) {
          PyErr_Clear();
          throw std::invalid_argument(
              vantage::cat("max_memory must be a whole number of bytes in [0, 2^64), 0 for what is "
                           "available, got ",
                           std::string(pybind11::str(pybind11::handle(max_memory)))));
        }
        if (!(max_work > 0.0)) {
          throw std::invalid_argument(
              vantage::cat("max_work must be a positive number of seconds, got ", max_work));
        }
        vantage::WorkBudget& budget = vantage::python::python_budget();
        budget.max_bytes = bytes;
        budget.max_seconds = max_work;
      },
      pybind11::arg("max_memory") = 0, pybind11::arg("max_work") = vantage::kDefaultMaxWorkSeconds,
      "The budget every later call is checked against, as the CLI's --max-memory and --max-work "
      "(docs/robustness.md, \"Work\"): max_memory [bytes] for a grid (OccupancyGrid, Mapper, "
      "plan, load) and a decision beside it, 0 for the memory available when the call is made; "
      "max_work [s] for a decision's estimated work (plan_next_view, plan). A grid past it raises "
      "MemoryError, a decision past it ValueError (MemoryError for its memory), each one line "
      "naming the estimate, before anything is allocated or computed.");
  m.def(
      "budget",
      [] {
        const vantage::WorkBudget& budget = vantage::python::python_budget();
        pybind11::dict out;
        out["max_memory"] = budget.max_bytes;
        out["max_work"] = budget.max_seconds;
        return out;
      },
      "The budget set_budget set: {'max_memory': bytes (0: what is available), 'max_work': s}.");
  vantage::python::bind_map(m);
  vantage::python::bind_gain(m);
  vantage::python::bind_planner_config(m);
  vantage::python::bind_candidates(m);
  vantage::python::bind_plan(m);
  vantage::python::bind_mapping(m);
  vantage::python::bind_sim(m);
  vantage::python::bind_env(m);
}
