#include "commands/options.hpp"

#include "vantage/experiment/exploration.hpp"

namespace vantage::cli {

void PlanningOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--method,-m", method, "probabilistic, greedy, random, latombe or yamauchi")
      ->capture_default_str();
  cmd.add_option("--alpha,-a", alpha, "observability parameter a of the probabilistic method")
      ->capture_default_str();
  cmd.add_option("--evaluation", evaluation,
                 "gain evaluation: auto (the cheaper of the two on each map state), fast or exact")
      ->capture_default_str();
  cmd.add_option("--epsilon", epsilon, "early stop of a ray's model, in [0, 0.5)")
      ->capture_default_str();
  cmd.add_option("--lambda", lambda, "latombe's travel penalty [1/m]")->capture_default_str();
  cmd.add_option("--threads,-j", threads, "threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
}

PlannerConfig PlanningOptions::planner_config() const {
  PlannerConfig config;
  config.method = parse_planner_method(method);
  config.gain.alpha = alpha;
  config.gain.evaluation = parse_gain_evaluation(evaluation);
  config.gain.epsilon = epsilon;
  config.gain.num_threads = threads;
  config.lambda = lambda;
  config.validate();
  return config;
}

void MappingOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--integration", integration, "scan integration: paper or endpoint")
      ->capture_default_str();
  cmd.add_flag("!--no-icp", icp, "trust the believed poses, no scan-to-map registration");
  cmd.add_flag("!--no-segmentation", segmentation, "integrate the table's points too");
  cmd.add_flag("!--no-hole-filling", hole_filling, "skip the MRF/ICM hole filling");
}

MapperConfig MappingOptions::mapper_config(const sim::Scene& scene) const {
  MapperConfig config = default_mapper_config(scene);
  config.integration.mode = parse_integration_mode(integration);
  config.integration.hole_filling.enabled = hole_filling;
  config.register_scans = icp;
  config.segment_table = config.segment_table && segmentation;
  return config;
}

}  // namespace vantage::cli
