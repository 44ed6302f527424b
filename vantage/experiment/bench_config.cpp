// A sweep's settings, checked, and its trials: the built-in or generated scenes × methods × a's ×
// objectives × trials of bench.hpp, each with a key that names its file.

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

std::string TrialSpec::key() const {
  // NOTE: the bits objective adds nothing to the key, so sweeps from before objectives resume.
  const std::string alpha_part =
      has_observability(method) ? fmt::format("__a{}{}", alpha.label(),
                                              objective == GainObjective::kCells ? "__cells" : "")
                                : std::string();
  if (greedy_oracle) return fmt::format("{}__{}__t{}", scene, kGreedyOracleName, trial);
  if (!policy.empty()) return fmt::format("{}__{}__t{}", scene, policy, trial);
  return fmt::format("{}__{}{}__t{}", scene, to_string(method), alpha_part, trial);
}

void BenchConfig::validate() const {
  if (scenes.empty() && generated == 0) {
    throw std::invalid_argument("bench.scenes must not be empty without generated piles");
  }
  if (generated < 0) {
    throw std::invalid_argument(fmt::format("bench.generated must be >= 0, got {}", generated));
  }
  if (generated > 0) pile.validate();
  objects.validate();
  if (methods.empty() && !greedy_oracle && policies.empty()) {
    throw std::invalid_argument("bench.methods must not be empty");
  }
  std::set<std::string> policy_names;
  for (const ExternalPolicy& p : policies) {
    const bool safe = !p.name.empty() && std::all_of(p.name.begin(), p.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.' || c == '-';
    });
    if (!safe || p.name.find("__") != std::string::npos) {
      throw std::invalid_argument(fmt::format(
          "bench.policies: name '{}' must be letters, digits, '_', '.' or '-' (no '__')", p.name));
    }
    bool builtin = p.name == kGreedyOracleName;
    try {
      (void)parse_planner_method(p.name);
      builtin = true;
    } catch (const std::invalid_argument&) {
      // NOTE: not a method's name: free for the policy.
    }
    if (builtin) {
      throw std::invalid_argument(
          fmt::format("bench.policies: '{}' is a built-in method's name", p.name));
    }
    if (!policy_names.insert(p.name).second) {
      throw std::invalid_argument(fmt::format("bench.policies: '{}' is named twice", p.name));
    }
    if (!p.choose) {
      throw std::invalid_argument(fmt::format("bench.policies: '{}' has no chooser", p.name));
    }
  }
  for (const AlphaSetting& a : alphas) {
    if (!(a.value > 0.0 && a.value <= 1.0)) {
      throw std::invalid_argument(fmt::format("bench.alphas: {} is not in (0, 1]", a.value));
    }
  }
  if (!(paper_alpha > 0.0 && paper_alpha <= 1.0)) {
    throw std::invalid_argument(fmt::format("bench.paper_alpha: {} is not in (0, 1]", paper_alpha));
  }
  if (trials < 1)
    throw std::invalid_argument(fmt::format("bench.trials must be >= 1, got {}", trials));
  if (jobs < 1) throw std::invalid_argument(fmt::format("bench.jobs must be >= 1, got {}", jobs));
  if (shard_count < 1 || shard_index < 0 || shard_index >= shard_count) {
    throw std::invalid_argument(
        fmt::format("bench.shard {}/{} is not a shard: need 0 <= I < N", shard_index, shard_count));
  }
  // NOTE: each trial runs its own method; the settings must hold for every one of them.
  for (const PlannerMethod m : methods) {
    ExplorationConfig e = exploration;
    e.planner.method = m;
    e.planner.objective = natural_objective(m);
    e.validate();
  }
}

BenchConfig office_bench_config() {
  BenchConfig config;
  config.scenes = {"office-small-sparse", "office-small-cluttered", "office-large-sparse",
                   "office-large-cluttered"};
  config.methods = {PlannerMethod::kProbabilistic, PlannerMethod::kGreedy, PlannerMethod::kLatombe,
                    PlannerMethod::kYamauchi, PlannerMethod::kRandom};
  config.alphas = {{false, kOfficeAlpha}, {false, 0.999}};
  config.paper_alpha = kOfficeAlpha;
  config.trials = 5;
  config.exploration.scans = 20;
  return config;
}

std::vector<sim::PileConfig> bench_piles(const BenchConfig& config) {
  std::vector<sim::PileConfig> piles;
  for (int k = 0; k < config.generated; ++k) {
    sim::PileConfig pile = config.pile;
    pile.seed = config.pile.seed + static_cast<std::uint64_t>(k);
    piles.push_back(pile);
  }
  return piles;
}

std::vector<TrialSpec> bench_trials(const BenchConfig& config) {
  // (name, source) of every scene: the named ones loaded to name them, the piles named by rule.
  std::vector<std::pair<std::string, std::string>> scenes;
  for (const std::string& source : config.scenes) {
    scenes.emplace_back(sim::load_scene(source, config.objects).name, source);
  }
  for (const sim::PileConfig& pile : bench_piles(config)) {
    scenes.emplace_back(sim::pile_name(pile), sim::pile_command(pile));
  }
  std::map<std::string, std::string> named;
  for (const auto& [scene, source] : scenes) {
    // NOTE: trial keys start with the scene's name, so two scenes of one name would share them.
    if (const auto [it, fresh] = named.emplace(scene, source); !fresh) {
      throw std::invalid_argument(fmt::format(
          "bench: scenes '{}' and '{}' are both named '{}'; a sweep's scenes need their own names",
          it->second, source, scene));
    }
  }
  std::vector<TrialSpec> specs;
  for (const auto& [scene, source] : scenes) {
    for (const PlannerMethod method : config.methods) {
      const bool probabilistic = has_observability(method);
      // NOTE: a method without a (greedy, ...) runs once; its alpha and objective are unused.
      const AlphaSetting own_alpha = default_alpha_setting(method, config.paper_alpha);
      const std::vector<AlphaSetting> alphas = probabilistic && !config.alphas.empty()
                                                   ? config.alphas
                                                   : std::vector<AlphaSetting>{own_alpha};
      const std::vector<GainObjective> objectives =
          probabilistic && !config.objectives.empty()
              ? config.objectives
              : std::vector<GainObjective>{probabilistic || config.objectives.empty()
                                               ? natural_objective(method)
                                               : config.objectives.front()};
      for (const AlphaSetting& alpha : alphas) {
        for (const GainObjective objective : objectives) {
          for (int t = 0; t < config.trials; ++t) {
            specs.push_back({scene, source, method, alpha, objective, t});
          }
        }
      }
    }
    if (config.greedy_oracle) {
      for (int t = 0; t < config.trials; ++t) {
        specs.push_back({scene, source, PlannerMethod::kGreedy,
                         default_alpha_setting(PlannerMethod::kGreedy, config.paper_alpha),
                         natural_objective(PlannerMethod::kGreedy), t, true});
      }
    }
  }
  // NOTE: after everything else, so the other trials keep their places (and shards).
  for (const ExternalPolicy& policy : config.policies) {
    for (const auto& [scene, source] : scenes) {
      for (int t = 0; t < config.trials; ++t) {
        specs.push_back({scene, source, PlannerMethod::kGreedy,
                         default_alpha_setting(PlannerMethod::kGreedy, config.paper_alpha),
                         natural_objective(PlannerMethod::kGreedy), t, false, policy.name});
      }
    }
  }
  return specs;
}

}  // namespace vantage
