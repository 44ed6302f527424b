#pragma once
/// @file
/// `vantage bench`'s sweeps (bench.cpp: the command line, its subcommands and merge;
/// bench_sweep.cpp: a sweep's settings, the checks before it starts, its run and its plots).

#include <cstdint>
#include <string>
#include <vector>

#include "commands/options.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/util/work.hpp"

namespace vantage::cli {

struct BenchOptions {
  std::vector<std::string> scenes = {"tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"};
  /// The default planner beside the paper's three (§5.1).
  std::vector<std::string> methods = {to_string(default_planner_method(ViewTask::kObjects, true)),
                                      "probabilistic", "greedy", "random"};
  std::string alphas;      ///< empty: each method's own, as explore runs it
  std::string objectives;  ///< empty: each method's own
  int trials = 10;
  int scans = 10;
  std::uint64_t seed = 1;
  int jobs = 1;
  std::string shard = "0/1";
  std::string out = "results/bench-tabletop";
  std::string kind = "tabletop";  ///< which experiment: tabletop or office
  bool plots = true;
  bool revisit = false;
  bool greedy_reference = false;
  bool project_stops = true;  ///< office: unreachable frontier centroids move into their region
  PlanningOptions planning;
  MappingOptions mapping;
  CandidateOptions candidates;               ///< tabletop only
  std::uint64_t max_memory = 0;              // 0: what the machine has available
  double max_work = kDefaultMaxWorkSeconds;  ///< [s] of a decision's estimated work
  int generated = 0;  ///< tabletop: generated piles, instead of --scenes unless given
  int objects = sim::PileConfig{}.objects;
  std::uint64_t generated_seed = 1;
  bool scenes_given = false;  ///< --scenes was on the command line
  double max_setup = 3600.0;  ///< [s] of estimated set-up before the first trial (issue 53)
};

/// Runs the sweep `o` describes: its settings, memory, decisions and set-up checked before any
/// trial, then its trials, then its plots.
void run_sweep(const BenchOptions& o);

}  // namespace vantage::cli
