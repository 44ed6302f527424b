#pragma once
/// @file
/// What every subcommand of the CLI shares: parsing helpers, plots, and the error convention
/// (exceptions become one line on stderr and a non-zero exit, in main).

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vantage::cli {

/// Parses "a,b,c" into numbers; throws std::invalid_argument naming `what` and the bad item.
std::vector<double> parse_numbers(std::string_view text, std::string_view what);

/// Runs `/usr/bin/python3 scripts/<script> args...`; throws std::runtime_error when it fails.
/// The scripts folder is VANTAGE_SCRIPTS_DIR from the environment, else the source tree's.
void run_plot_script(std::string_view script, const std::vector<std::string>& args);

}  // namespace vantage::cli
