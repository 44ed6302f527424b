/// `vantage ray`: the paper's ray model on one ray, as numbers and as a picture (Figs. 3 and 5).

#include <fmt/core.h>
#include <fmt/os.h>

#include <array>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands/commands.hpp"
#include "shell.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/io/atomic_file.hpp"

namespace vantage::cli {
namespace {

/// The four scenarios of Figs. 3–5: the origin's free cell, then free, occupied, unobserved, or a
/// mix of all three.
std::vector<double> scenario_cells(int scenario) {
  constexpr double kFree = 0.12, kOccupied = 0.97, kUnknown = 0.5;
  auto run = [](std::vector<double>& cells, double p, int n) { cells.insert(cells.end(), n, p); };
  std::vector<double> cells = {kFree};
  switch (scenario) {
    case 1:
      run(cells, kFree, 39);
      break;
    case 2:
      run(cells, kOccupied, 39);
      break;
    case 3:
      run(cells, kUnknown, 39);
      break;
    case 4:
      run(cells, kFree, 7);
      run(cells, kOccupied, 2);
      run(cells, kUnknown, 10);
      run(cells, kFree, 6);
      run(cells, kUnknown, 14);
      break;
    default:
      throw UsageError(fmt::format("--scenario must be 1, 2, 3 or 4, got {}", scenario));
  }
  return cells;
}

std::string to_csv(const std::vector<RayState>& states) {
  std::ostringstream out;
  out << "cell,occupancy,visibility,posterior,gain\n";
  for (const RayState& s : states) {
    out << fmt::format("{},{:.15g},{:.15g},{:.15g},{:.15g}\n", s.m, s.occupancy, s.visibility,
                       s.posterior, s.gain());
  }
  return out.str();
}

struct RayOptions {
  double alpha = kTableTopAlpha;
  std::string cells;
  int scenario = 0;
  bool use_scenario = false;  ///< --scenario was given (0 is a wrong value, not "none")
  std::string csv_path;
  std::string plot_path;
};

void run(const RayOptions& options) {
  if (!options.plot_path.empty()) check_picture_format(options.plot_path, "--plot");
  const RayModel model = from_options([&] { return RayModel(options.alpha); });
  const std::vector<double> cells = options.use_scenario ? scenario_cells(options.scenario)
                                                         : parse_numbers(options.cells, "--cells");
  const std::string csv = from_options([&] { return to_csv(model.trace(cells)); });
  if (!options.csv_path.empty()) check_output_file(options.csv_path, "--csv");
  if (!options.plot_path.empty()) check_output_file(options.plot_path, "--plot");
  fmt::print("{}", csv);
  if (!options.csv_path.empty()) write_atomically(options.csv_path, csv);
  if (!options.plot_path.empty()) {
    const TemporaryFile data(".csv");
    write_atomically(data.path(), csv);
    const std::string title =
        options.use_scenario ? fmt::format("Scenario #{}, a = {}", options.scenario, options.alpha)
                             : fmt::format("a = {}", options.alpha);
    run_plot_script("plot_ray.py", {data.path().string(), options.plot_path, title});
    fmt::print(stderr, "picture: {}\n", options.plot_path);
  }
}

}  // namespace

void add_ray_command(CLI::App& app) {
  auto options = std::make_shared<RayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "ray", "Visibility and occupancy posterior along one ray (the paper's Figs. 3 and 5)");
  cmd->add_option("--alpha,-a", options->alpha, "observability parameter a, in (0, 1]")
      ->check(number_in(0.0, 1.0, /*open_low=*/true))
      ->capture_default_str();
  auto* cells = cmd->add_option("--cells", options->cells,
                                "occupancy probabilities p0,p1,...,pM in ray order from the "
                                "sensor's cell");
  auto* scenario =
      cmd->add_option("--scenario", options->scenario, "one of the paper's scenarios, 1..4");
  cells->excludes(scenario);
  cmd->add_option("--csv", options->csv_path, "also write the CSV to this file");
  cmd->add_option("--plot", options->plot_path, "draw visibility and posterior into this PNG");
  cmd->callback([options, cells, scenario] {
    if (cells->count() == 0 && scenario->count() == 0) {
      throw UsageError("give the ray with --cells p0,...,pM or --scenario 1..4");
    }
    options->use_scenario = scenario->count() > 0;
    run(*options);
  });
}

}  // namespace vantage::cli
