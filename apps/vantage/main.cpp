/// `vantage`: next-best-view planning in cluttered 3D scenes. A thin shell over the library: each
/// subcommand parses its options and calls the library; any error becomes one line on stderr and
/// exit code 1.

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <exception>

#include "commands/commands.hpp"
#include "vantage/perception/registration.hpp"

int main(int argc, char** argv) {
  CLI::App app("Vantage: next-best-view planning in cluttered 3D scenes", "vantage");
  app.set_version_flag("--version", VANTAGE_VERSION);
  app.require_subcommand(1);
  vantage::cli::add_explore_command(app);
  vantage::cli::add_bench_command(app);
  vantage::cli::add_plan_command(app);
  vantage::cli::add_ray_command(app);
  vantage::cli::add_scan_command(app);
  vantage::cli::add_scene_command(app);
  vantage::cli::add_view_command(app);
  vantage::perception::silence_pcl_console();  // failures are reported per scan, in one line
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != 0) {
      fmt::print(stderr, "vantage: error: {}\n", e.what());
      return e.get_exit_code();
    }
    return app.exit(e);  // --help, --version
  } catch (const std::exception& e) {
    fmt::print(stderr, "vantage: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
