#include "vantage/experiment/results.hpp"

#include <fmt/core.h>
#include <fmt/os.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "vantage/experiment/detail/run_json.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/io/map_files.hpp"
#include "vantage/map/navigation.hpp"

namespace vantage {
namespace {

using nlohmann::json;

std::string optional_number(const std::optional<double>& value) {
  return value ? fmt::format("{:.15g}", *value) : std::string();
}

/// A top view of the floor for the office picture: per (x, y) column, '#' where the robot's
/// navigation grid sees an obstacle, '.' where a cell in the sensor's height band is known free,
/// ' ' where the band is all unknown. A header line gives origin_x origin_y resolution nx ny.
void write_floor_map(const std::filesystem::path& path, const sim::Scene& scene,
                     const ExplorationConfig& config, const OccupancyGrid& grid) {
  NavigationConfig nav;
  nav.footprint = scene.robot.footprint;
  nav.min_height = config.office.min_obstacle_height;
  nav.max_height = scene.robot.height;
  const NavigationGrid floor = NavigationGrid::from_map(grid, nav);
  const GridSpec& spec = grid.spec();
  const double lo = scene.mount.height - config.office.frontier_band;
  const double hi = scene.mount.height + config.office.frontier_band;
  std::string text = fmt::format("{} {} {} {} {}\n", spec.origin.x(), spec.origin.y(),
                                 spec.resolution, spec.dims.x(), spec.dims.y());
  for (int y = 0; y < spec.dims.y(); ++y) {
    std::string row(static_cast<std::size_t>(spec.dims.x()), ' ');
    for (int x = 0; x < spec.dims.x(); ++x) {
      if (floor.obstacle(floor.linear({x, y}))) {
        row[static_cast<std::size_t>(x)] = '#';
        continue;
      }
      for (int z = 0; z < spec.dims.z(); ++z) {
        const double h = spec.center({x, y, z}).z();
        if (h >= lo && h <= hi && grid.state(spec.linear({x, y, z})) == CellState::kFree) {
          row[static_cast<std::size_t>(x)] = '.';
          break;
        }
      }
    }
    text += row + "\n";
  }
  write_atomically(path, text);
}

}  // namespace

GainUnits gain_units(const PlannerConfig& planner) {
  // NOTE: the surface model's value is a number of cells, the surface a scan is expected to add.
  if (method_traits(planner.method.gain).surface_cells) return {"cells", "cells", "cells"};
  if (is_volumetric_metric(planner.method.gain)) return {"metric", "metric", "metric"};
  if (has_observability(planner.method)) {
    const std::string_view objective = to_string(planner.objective);
    return {"bits", objective, objective};
  }
  if (planner.method.ranking == Ranking::kNearest) return {"cells", "-m", "cells"};
  return {"cells", "cells", "cells"};
}

json sensor_json(const SensorFov& fov) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  return {{"horizontal_fov_deg", fov.h_fov * kDeg},
          {"vertical_fov_deg", fov.v_fov * kDeg},
          {"min_range_m", fov.min_range},
          {"max_range_m", fov.max_range}};
}

json units_json(const GainUnits& units) {
  return {{"predicted_gain", units.predicted_gain},
          {"score", units.score},
          {"predicted_cells", "cells"},
          {"greedy_gain", "cells"},
          {"travel", "m"}};
}

RunLabel run_label(std::string scene, const ExplorationConfig& config) {
  return {std::move(scene),
          config.planner.method,
          AlphaSetting{config.auto_alpha, config.planner.gain.alpha},
          config.planner.objective,
          config.start,
          config.greedy_oracle};
}

std::string scans_csv_rows(const RunLabel& label, const std::vector<ScanRecord>& scans) {
  const bool probabilistic = label.policy.empty() && has_observability(label.method);
  const std::string alpha = probabilistic ? label.alpha.label() : std::string();
  const std::string objective = probabilistic ? std::string(to_string(label.objective)) : "";
  std::string rows;
  for (const ScanRecord& r : scans) {
    rows += fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{:.15g},{:.15g},{:.15g},{:d},{},{},{},{:.6g},{:.6g},{:.6g},"
        "{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{}\n",
        label.scene,
        !label.policy.empty() ? std::string_view(label.policy)
        : label.greedy_oracle ? kGreedyOracleName
                              : to_string(label.method),
        alpha, label.trial, r.scan, r.view, optional_number(r.predicted_gain),
        optional_number(r.greedy_predicted_gain), r.actual_gain, r.unobserved, r.coverage,
        r.seconds.plan, r.travel, r.fallback ? 1 : 0, optional_number(r.predicted_cells),
        optional_number(r.alpha), objective, r.pose_error_before, r.pose_error_after,
        r.pose_error_final, r.seconds.register_scan, r.seconds.segment, r.seconds.integrate,
        r.seconds.reference, r.displacement_before, r.displacement_after, r.displacement_final,
        optional_number(r.surface_coverage), optional_number(r.raw_surface_coverage));
  }
  return rows;
}

void write_run_files(const std::filesystem::path& dir, const sim::Scene& scene,
                     const ExplorationConfig& config, const ExplorationResult& result,
                     const Mapper& mapper) {
  const RunLabel label = run_label(scene.name, config);
  write_atomically(dir / "scans.csv",
                   std::string(kScansCsvHeader) + "\n" + scans_csv_rows(label, result.scans));
  const OccupancyGrid& grid = mapper.grid();
  const GridSpec& spec = grid.spec();
  write_atomically(dir / "run.json", detail::run_json(scene, spec, config, result).dump(2) + "\n");
  write_map_files(dir, grid);  // map.ot (lossless), map.bt, map_top.csv
  if (!mapper.object_cloud().empty()) write_point_cloud(dir / "cloud.pcd", mapper.object_cloud());

  std::string cells = "x,y,z\n";
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) != CellState::kOccupied) continue;
    const Eigen::Vector3d c = spec.center(spec.unravel(i));
    cells += fmt::format("{:.5f},{:.5f},{:.5f}\n", c.x(), c.y(), c.z());
  }
  write_atomically(dir / "map_cells.csv", cells);
  if (scene.kind == sim::SceneKind::kOffice)
    write_floor_map(dir / "floor_map.txt", scene, config, grid);
}

}  // namespace vantage
