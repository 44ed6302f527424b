// Bindings of the decision's settings: PlannerConfig, built by the library's one builder
// (PlanningSettings), as the CLI builds it.

#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {
namespace py = pybind11;
namespace {

/// PlannerConfig(...): the library's one builder (PlanningSettings, as the CLI's), then the
/// GainConfig given, if one is (its method follows from `method`); without one, the method's own
/// a, as `vantage plan` takes it. Without a method, the default one for views around objects,
/// with the robot's pose known or not.
PlannerConfig planner_config(const std::optional<std::string>& method, bool knows_pose,
                             const std::optional<GainConfig>& gain, double lambda,
                             bool greedy_reference, const std::optional<std::string>& objective,
                             const std::optional<std::string>& search, int sample, int horizon,
                             double travel_weight, int swept_rays, bool predict_chosen) {
  PlanningSettings settings;
  settings.method = method.value_or("");
  settings.knows_pose = knows_pose;
  settings.objective = objective.value_or("");
  settings.search = search.value_or("");
  if (gain) {
    settings.evaluation = std::string(to_string(gain->evaluation));
    settings.epsilon = gain->epsilon;
    settings.threads = gain->num_threads;
  }
  settings.lambda = lambda;
  settings.sample = sample;
  settings.horizon = horizon;
  settings.travel_weight = travel_weight;
  settings.swept_rays = swept_rays;
  PlannerConfig config;
  try {
    config = settings.planner_config(kTableTopAlpha);
  } catch (const SettingError& e) {
    throw std::invalid_argument(cat(e.setting(), ": ", e.what()));
  }
  if (gain) config.gain = *gain;
  config.greedy_reference = greedy_reference;
  config.predict_chosen = predict_chosen;
  config.validate();
  return config;
}

/// Python's PlannerConfig(...): it knows no robot pose.
PlannerConfig planner_config_of(const std::optional<std::string>& method,
                                const std::optional<GainConfig>& gain, double lambda,
                                bool greedy_reference, const std::optional<std::string>& objective,
                                const std::optional<std::string>& search, int sample, int horizon,
                                double travel_weight, int swept_rays, bool predict_chosen) {
  return planner_config(method, false, gain, lambda, greedy_reference, objective, search, sample,
                        horizon, travel_weight, swept_rays, predict_chosen);
}

}  // namespace

PlannerConfig default_planner_config(bool knows_pose) {
  return planner_config(std::nullopt, knows_pose, std::nullopt, PlannerConfig{}.lambda, false,
                        std::nullopt, std::nullopt, 1, 1, 0.0, PlannerConfig{}.swept_rays, true);
}

void bind_planner_config(py::module_& m) {
  py::class_<PlannerConfig>(m, "PlannerConfig", "Settings of the next-best-view decision.")
      .def(
          py::init(&planner_config_of), py::arg("method") = std::nullopt,
          py::arg("gain") = std::nullopt, py::arg("lambda_") = PlannerConfig{}.lambda,
          py::arg("greedy_reference") = false, py::arg("objective") = std::nullopt,
          py::arg("search") = std::nullopt, py::arg("sample") = 1, py::arg("horizon") = 1,
          py::arg("travel_weight") = 0.0, py::arg("swept_rays") = PlannerConfig{}.swept_rays,
          py::arg("predict_chosen") = true,
          "method: a name as `vantage explore --method` takes ('surface', 'survival', "
          "'probabilistic', 'greedy', 'random', 'latombe', 'yamauchi', 'sequence' or a metric; "
          "default None: `vantage plan`'s, 'latombe+surface', or 'surface' where no robot pose is "
          "given, which this config cannot know: plan_next_view and plan pick it when given no "
          "config); gain: a GainConfig "
          "(its method follows from `method`; "
          "default None: the method's own a, as `vantage plan`); lambda_: latombe's travel penalty "
          "[1/m]; greedy_reference: also predict every candidate's greedy gain; objective: "
          "'bits' or 'cells' (default: the method's own); search: 'swept', 'pruned' or "
          "'exhaustive' (docs/decision.md; default None: the fastest that serves the method, as "
          "`vantage plan`); sample: a sequence's values on one unobserved cell in `sample` "
          "(1: exact); horizon, travel_weight: plan that many views ahead and tour them "
          "(docs/decision.md, 'Planning a sequence') [views, 1/m]; swept_rays: the "
          "swept search's rays across a view's image in its first round, in [1, 4096]; "
          "predict_chosen: False leaves the chosen view's full prediction in bits, which on a "
          "large grid takes longer than the decision, out of it (`vantage plan --no-prediction`).")
      .def_property_readonly(
          "method", [](const PlannerConfig& c) { return std::string(to_string(c.method)); },
          "How the next view is chosen.")
      .def_readonly("gain", &PlannerConfig::gain, "The GainConfig of the gain evaluation.")
      .def_readonly("lambda_", &PlannerConfig::lambda, "Latombe's travel penalty [1/m].")
      .def_readonly("greedy_reference", &PlannerConfig::greedy_reference,
                    "Whether every candidate's greedy gain is predicted too.")
      .def_property_readonly(
          "search", [](const PlannerConfig& c) { return std::string(resolve_decider(c).name()); },
          "The search that decides: the one given, or the fastest that serves the method.")
      .def_property_readonly(
          "objective", [](const PlannerConfig& c) { return std::string(to_string(c.objective)); },
          "What the method ranks by: bits or cells.")
      .def_property_readonly(
          "horizon", [](const PlannerConfig& c) { return sequence_of(c).horizon; },
          "Views planned ahead (the sequence method's default when it is not told).")
      .def_readonly("swept_rays", &PlannerConfig::swept_rays,
                    "The swept search's rays across a view's image in its first round.")
      .def_readonly("predict_chosen", &PlannerConfig::predict_chosen,
                    "Whether the chosen view's full prediction in bits follows the decision.");
}

}  // namespace vantage::python
