/// `vantage view`: a results folder (explore or plan) as one self-contained HTML page with a 3D
/// view of the map, the candidate views and their gains, the views taken and a slider over them.

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/experiment/viewer.hpp"
#include "vantage/io/atomic_file.hpp"

namespace vantage::cli {
namespace {

struct ViewOptions {
  std::string dir;
  std::string out;
  ViewerConfig viewer;
};

void run(const ViewOptions& o) {
  const std::filesystem::path dir(o.dir);
  const std::filesystem::path out =
      o.out.empty() ? dir / "view.html" : std::filesystem::path(o.out);
  // NOTE: before the page is built: the page never replaces what it is built from, and its
  // folder must exist, as for every output (scene --out, ray --plot).
  check_output_file(out, "--out",
                    {dir / "plan.json", dir / "run.json", dir / "map.bt", dir / "map.ot"});
  const std::string page = build_view_page(o.dir, o.viewer);
  write_atomically(out, page);
  fmt::print("view: {} ({:.1f} MB); open it in a browser, no network needed\n", out.string(),
             static_cast<double>(page.size()) / 1e6);
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view", "A 3D view of an explore or plan folder: one HTML file that opens offline");
  cmd->add_option("dir", o->dir, "the results folder (explore: run.json, map.bt; plan: plan.json)")
      ->required();
  cmd->add_option("--out,-o", o->out, "the page to write (default: DIR/view.html)");
  cmd->add_option("--max-cells", o->viewer.max_cells,
                  "cells drawn per layer (occupied, unobserved); more are thinned evenly")
      ->check(whole_in(1, std::int64_t{1} << 30))
      ->capture_default_str();
  cmd->add_option("--max-candidates", o->viewer.max_candidates,
                  "candidates drawn per decision: the chosen view and the best by score; the "
                  "page says how many were cut")
      ->check(whole_in(1, std::int64_t{1} << 30))
      ->capture_default_str();
  add_memory_option(*cmd, o->viewer.max_memory);
  cmd->callback([o] { run(*o); });
}

}  // namespace vantage::cli
