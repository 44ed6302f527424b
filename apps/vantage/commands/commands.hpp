#pragma once
/// @file
/// One function per subcommand; each adds itself to the app and runs from its callback.

#include <CLI/CLI.hpp>

namespace vantage::cli {

void add_ray_command(CLI::App& app);
void add_explore_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_plan_command(CLI::App& app);
void add_scan_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_view_command(CLI::App& app);

}  // namespace vantage::cli
