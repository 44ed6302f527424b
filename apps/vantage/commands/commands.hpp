#pragma once
/// @file
/// One function per subcommand; each adds itself to the app and runs from its callback.

#include <CLI/CLI.hpp>

namespace vantage::cli {

void add_ray_command(CLI::App& app);

}  // namespace vantage::cli
