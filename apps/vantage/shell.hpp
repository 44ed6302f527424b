#pragma once
/// @file
/// What every subcommand of the CLI shares: parsing helpers, plots, and the error convention
/// (exceptions become one line on stderr and a non-zero exit, in main).

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vantage::cli {

/// Parses "a,b,c" into numbers; throws std::invalid_argument naming `what` and the bad item.
std::vector<double> parse_numbers(std::string_view text, std::string_view what);

/// Parses "x,y,z,roll,pitch,yaw" (m, degrees; rotations about the fixed x, y, z axes in that
/// order) into a pose; throws std::invalid_argument naming `what` when it is not six finite
/// numbers.
Eigen::Isometry3d parse_pose(std::string_view text, std::string_view what);

/// Roll, pitch and yaw of a rotation, the inverse of parse_pose's angles [rad].
Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R);

/// "x 1.0000 y 0.0000 z 1.1000 m, roll 0.000 pitch 0.000 yaw 90.000 deg".
std::string describe_pose(const Eigen::Isometry3d& T);

/// The plot scripts' folder: VANTAGE_SCRIPTS_DIR from the environment, else an installed
/// binary's share/vantage/scripts, else the source tree's scripts/.
std::filesystem::path scripts_dir();

/// Runs `/usr/bin/python3 <scripts_dir()>/<script> args...`; throws std::runtime_error when it
/// fails.
void run_plot_script(std::string_view script, const std::vector<std::string>& args);

}  // namespace vantage::cli
