#pragma once
/// @file
/// `vantage plan`'s parts (plan.cpp: the command line and the decision; plan_map.cpp: the input
/// read and mapped; plan_candidates.cpp: the sensor and the candidate views; plan_report.cpp:
/// plan.json and the table).

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands/options.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/io/manifest.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::cli {

struct PlanOptions {
  std::string input;  // manifest or folder
  std::string map;    // .bt / .ot to start from
  int every = 0;      // of a TUM folder's or a recording's frames, every n-th (0: not given)
  std::string topic;  // of a recording, in place of the manifest's

  // issue 53: a damaged recording; a recording alone (the input a .bag or .mcap file).
  bool salvage = false;     // of a damaged recording, map the whole frames before the damage
  std::string roi;          // of a recording alone: xmin,ymin,zmin,xmax,ymax,zmax [m]
  double resolution = 0.0;  // of a recording alone [m]; 0: suited to the sensor's range

  std::string candidates = "ring";
  double radius = 0.0;  // 0: from the ROI
  double height = std::numeric_limits<double>::quiet_NaN();
  std::string sensor_height;  // frontier candidates: H or MIN,MAX [m]; empty: any height
  int views = 0;              // 0: 10 ring positions / 50 sphere views
  std::string fov_deg = "57,43";
  std::string range = "0.5,3.5";
  bool sensor_given = false;  // --fov-deg or --range on the command line
  PlanningOptions planning;
  std::string pose;  // x,y,z,roll,pitch,yaw of the robot's sensor now
  std::string out;
  bool json_only = false;
  bool plots = true;
  int top = 10;
  std::uint64_t max_memory = 0;              // 0: what the machine has available
  double max_work = kDefaultMaxWorkSeconds;  // [s] of a decision's estimated work
  bool predict = true;  // the chosen view's full prediction in bits after the decision
};

/// --fov-deg and --range as the sensor without a manifest; throws UsageError.
SensorFov fov_from_options(const PlanOptions& o);
/// --sensor-height: one height, or a range min,max [m]; throws UsageError.
std::optional<std::pair<double, double>> sensor_band(const PlanOptions& o);
/// The candidate views --candidates names that do not depend on the map (all but frontier), in
/// the map's frame; nothing for frontier.
/// Whether --candidates names a pose file rather than one of the registry's sets.
bool names_pose_file(const PlanOptions& o);

std::optional<std::vector<Eigen::Isometry3d>> planned_poses(const PlanOptions& o,
                                                            const Eigen::AlignedBox3d& roi,
                                                            CloudFrame frame);
/// The candidate views --candidates names, in the map's frame (ring, sphere, hemisphere,
/// frontier, or a file of poses in `frame`).
std::vector<Eigen::Isometry3d> candidate_poses(const PlanOptions& o, const Eigen::AlignedBox3d& roi,
                                               CloudFrame frame, const OccupancyGrid& grid);

/// The pose as `--pose` takes it: x,y,z,roll,pitch,yaw (m, deg).
std::string pose_argument(const Eigen::Isometry3d& T);

/// The robot's sensor pose now, for the travel of latombe and yamauchi, and where it came from.
struct RobotPose {
  std::optional<Eigen::Isometry3d> pose;
  std::string source;
};

/// What `vantage plan` carries from one step to the next (plan.cpp's run).
struct PlanRun {
  const PlanOptions& o;
  PlannerConfig planner;
  std::filesystem::path dir = {};  ///< the results folder
  RobotPose robot = {};
  std::optional<Manifest> manifest = {};  ///< none: --map alone
  SensorFov fov = {};
  CloudFrame frame = CloudFrame::kOptical;
};

/// Reads the input (plan_map.cpp): a manifest or a data folder, a recording alone, or none
/// (--map alone), a damaged recording's salvage said; the sensor, the manifest's or --fov-deg and
/// --range. Throws UsageError for the options that do not fit the input.
void read_input(PlanRun& run);
/// Builds the map (plan_map.cpp) from --map and the manifest's clouds, each said in a line unless
/// --json, the grid first checked against the memory and work budgets; the robot's pose the last
/// cloud's unless --pose gave it.
Mapper build_map(PlanRun& run);

/// What plan.json and the table report of a decision.
struct PlanReport {
  const PlanOptions& o;
  const Plan& plan;
  const PlannerConfig& planner;
  const GainUnits& units;
  const std::vector<Candidate>& candidates;
  const std::vector<Eigen::Isometry3d>& poses;
  const std::optional<Eigen::Isometry3d>& robot;
  const std::string& robot_source;
  const OccupancyGrid& grid;
  CloudFrame frame;
  SensorFov fov;
  std::size_t clouds;  ///< the manifest's clouds mapped
  double map_seconds;  ///< [s]
  const std::filesystem::path& dir;
  double estimated_seconds;  ///< the work budget's estimate of the decision [s]

  const RecordingSalvage* salvage = nullptr;  ///< the manifest's recording was damaged
};

/// Writes the results folder whole (plan.json, the maps, the picture) and prints plan.json
/// (--json) or the ranked table and the next best view.
void report_plan(const PlanReport& report);

}  // namespace vantage::cli
