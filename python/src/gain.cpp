// Bindings of the gain: the paper's ray model (§3.1, §3.2) and the gains of candidate views
// (eqs. 1, 3, 4).

#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {

namespace {

/// The states of one traced ray, read as arrays.
struct RayTrace {
  std::vector<RayState> states;

  template <typename F>
  py::array_t<double> column(F&& f) const {
    py::array_t<double> out(static_cast<py::ssize_t>(states.size()));
    for (std::size_t i = 0; i < states.size(); ++i) out.mutable_at(i) = f(states[i]);
    return out;
  }
};

GainConfig make_gain_config(const std::string& method, const std::string& evaluation, double alpha,
                            double epsilon, double ray_spacing, int num_threads) {
  GainConfig config;
  config.method = parse_gain_method(method);
  config.evaluation = parse_gain_evaluation(evaluation);
  config.alpha = alpha;
  config.epsilon = epsilon;
  config.ray_spacing = ray_spacing;
  config.num_threads = num_threads;
  config.validate();
  return config;
}

/// RayTrace and RayModel: the paper's model of one ray, cell by cell.
void def_ray_model(py::module_& m) {
  py::class_<RayTrace>(m, "RayTrace",
                       "The model's state at every cell of one ray, cell 0 being the sensor's.")
      .def_property_readonly(
          "visibility",
          [](const RayTrace& r) { return r.column([](auto& s) { return s.visibility; }); },
          "v_m, the chance that cell m is visible, eqs. (5)-(7).")
      .def_property_readonly(
          "posterior",
          [](const RayTrace& r) { return r.column([](auto& s) { return s.posterior; }); },
          "q_m, the expected occupancy after a measurement, eqs. (11)-(15).")
      .def_property_readonly(
          "gain", [](const RayTrace& r) { return r.column([](auto& s) { return s.gain(); }); },
          "Expected information gain on cell m as the target, eq. (4): H(p_m) - H(q_m) [bits].")
      .def_property_readonly(
          "t", [](const RayTrace& r) { return r.column([](auto& s) { return s.t; }); },
          "a^m, the chance to stay visible, eq. (10).")
      .def_property_readonly(
          "occupancy",
          [](const RayTrace& r) { return r.column([](auto& s) { return s.occupancy; }); },
          "The map's occupancy p_m, as given.")
      .def("__len__", [](const RayTrace& r) { return r.states.size(); });

  py::class_<RayModel>(m, "RayModel",
                       "The paper's visibility-aware model of one ray (docs/model.md, 'One ray').")
      .def(py::init<double>(), py::arg("alpha") = kTableTopAlpha,
           "Observability parameter a in (0, 1]; ValueError otherwise.")
      .def_property_readonly("alpha", &RayModel::alpha, "Observability parameter a.")
      .def(
          "trace",
          [](const RayModel& model, const DoubleArray& occupancy) {
            if (occupancy.ndim() != 1) {
              throw std::invalid_argument("occupancy must be a 1-D sequence of probabilities");
            }
            return RayTrace{
                model.trace({occupancy.data(), static_cast<std::size_t>(occupancy.size())})};
          },
          py::arg("occupancy"),
          "Runs the model along a ray of occupancy probabilities, cell 0 at the sensor. "
          "ValueError for an empty ray or a probability outside [0, 1].");
}

}  // namespace

void bind_gain(py::module_& m) {
  m.attr("TABLE_TOP_ALPHA") = kTableTopAlpha;
  m.attr("OFFICE_ALPHA") = kOfficeAlpha;
  m.def("entropy_bits", &entropy_bits, py::arg("p"), "Binary entropy of p [bits].");

  def_ray_model(m);

  py::class_<GainConfig>(m, "GainConfig", "Settings of a gain evaluation.")
      .def(py::init(&make_gain_config), py::arg("method") = "probabilistic",
           py::arg("evaluation") = "auto", py::arg("alpha") = kTableTopAlpha,
           py::arg("epsilon") = GainConfig{}.epsilon,
           py::arg("ray_spacing") = GainConfig{}.ray_spacing, py::arg("num_threads") = 0,
           "method 'probabilistic', 'survival', 'greedy' or a metric's name; evaluation 'auto' or "
           "'exact' (a metric's every third or every ray); alpha in (0, 1]; epsilon (early stop) "
           "in [0, 0.5); ray_spacing [cells] in (0, 1] for the metrics' rays; num_threads 0 = all "
           "cores (results do not depend on it). ValueError "
           "naming the field when one is bad.")
      .def_property_readonly(
          "method", [](const GainConfig& c) { return std::string(to_string(c.method)); },
          "'probabilistic' (the paper's model) or 'greedy' (infinite visibility).")
      .def_property_readonly(
          "evaluation", [](const GainConfig& c) { return std::string(to_string(c.evaluation)); },
          "'exact' (a metric's every ray) or 'auto' (every third along each image axis).")
      .def_readonly("alpha", &GainConfig::alpha, "Observability parameter a, in (0, 1].")
      .def_readonly("epsilon", &GainConfig::epsilon,
                    "Early stop: a ray stops once its visibility falls below it, in [0, 0.5).")
      .def_readonly("ray_spacing", &GainConfig::ray_spacing,
                    "The metrics: spacing of neighbouring rays at the farthest cell [cells].")
      .def_readonly("num_threads", &GainConfig::num_threads,
                    "0 = all cores; results are identical for any count.");

  py::class_<ViewGain>(m, "ViewGain", "The predicted gain of one view.")
      .def_readonly("gain", &ViewGain::gain,
                    "Expected information gain of the view, eq. (1) [bits].")
      .def_readonly("cells", &ViewGain::cells,
                    "Expected number of the unobserved cells in view that the view sees, E (the "
                    "sum of each target's visibility) [cells]; greedy's count for greedy.")
      .def_readonly("targets", &ViewGain::targets,
                    "Unobserved cells evaluated: all those in the frustum.")
      .def("__repr__", [](const ViewGain& g) {
        return cat("ViewGain(gain=", g.gain, ", cells=", g.cells, ", targets=", g.targets, ")");
      });

  m.def(
      "evaluate_views",
      [](const OccupancyGrid& grid, const DoubleArray& poses, const SensorFov& fov,
         const GainConfig& config) {
        config.validate();
        const std::vector<Frustum> views = to_views(poses, fov, "poses");
        py::gil_scoped_release release;
        return evaluate_views(grid, views, config);
      },
      py::arg("grid"), py::arg("poses"), py::arg("fov"), py::arg("config") = GainConfig{},
      "Predicted gain of every view: K x 4 x 4 sensor poses (or a list of 4 x 4), one field of "
      "view. Returns a list of ViewGain; the grid is only read.");
}

}  // namespace vantage::python
