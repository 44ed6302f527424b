#include "vantage/experiment/yardstick.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <iterator>
#include <stdexcept>

#include "vantage/sim/ground_truth.hpp"
#include "vantage/util/clock.hpp"

namespace vantage {
namespace {

bool is_support(const sim::Shape& shape) {
  return std::find(std::begin(kSupportKinds), std::end(kSupportKinds), shape.kind) !=
         std::end(kSupportKinds);
}

/// Whether `p` lies in (or within 1 um of) a support's bounding box [m].
bool on_support(const std::vector<Eigen::AlignedBox3d>& supports, const Eigen::Vector3d& p) {
  constexpr double kSlack = 1e-6;  // [m]
  return std::any_of(supports.begin(), supports.end(), [&](const Eigen::AlignedBox3d& box) {
    return (p.array() >= box.min().array() - kSlack).all() &&
           (p.array() <= box.max().array() + kSlack).all();
  });
}

/// A grid one cell larger on every side, for marks of points just outside the grid.
struct PaddedMarks {
  explicit PaddedMarks(const GridSpec& grid)
      : dims(grid.dims + Index3::Constant(2)),
        marks(static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) *
                  static_cast<std::size_t>(dims.z()),
              0) {}

  /// Linear index of padded cell `p` (grid cell p - 1).
  std::size_t at(const Index3& p) const {
    return static_cast<std::size_t>(p.x()) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(p.y()) +
                static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(p.z()));
  }

  Index3 dims;
  std::vector<std::uint8_t> marks;
};

}  // namespace

std::vector<std::uint32_t> object_surface_cells(const sim::Scene& scene, int num_threads) {
  std::vector<sim::Shape> objects;
  for (const sim::Shape& shape : scene.shapes) {
    if (!is_support(shape)) objects.push_back(shape);
  }
  return sim::surface_cells(scene.grid, sim::voxelize(objects, scene.grid, num_threads));
}

CoverageTolerance CoverageTolerance::within(double m) {
  CoverageTolerance t(0);
  t.metres = m;
  return t;
}

void CoverageTolerance::validate() const {
  if (metres != 0.0) {
    if (!(metres > 0.0 && metres <= kMaxCoverageToleranceMetres)) {
      throw std::invalid_argument(fmt::format("coverage tolerance {} m: must be in (0, {}] m",
                                              metres, kMaxCoverageToleranceMetres));
    }
    return;
  }
  if (cells < 0 || cells > kMaxCoverageTolerance) {
    throw std::invalid_argument(fmt::format("coverage tolerance {} cells: must be 0 or {}", cells,
                                            kMaxCoverageTolerance));
  }
}

std::string CoverageTolerance::describe() const {
  if (metres > 0.0) return fmt::format("within {:g} mm of it", metres * 1e3);
  return cells == 0 ? "in it" : "in it or in one of its 26 neighbours";
}

std::string CoverageTolerance::label() const {
  return metres > 0.0 ? fmt::format("{:g}mm", metres * 1e3) : fmt::format("{}", cells);
}

CoverageTolerance parse_coverage_tolerance(std::string_view text) {
  const std::string t(text);
  const auto fail = [&] {
    return std::invalid_argument(fmt::format(
        "coverage tolerance '{}': give 0 or 1 [cells], or a distance such as 5mm or 0.005m", t));
  };
  if (t == "0" || t == "1") return CoverageTolerance(t == "0" ? 0 : 1);
  double scale = 0.0;
  std::string number;
  if (t.size() > 2 && t.compare(t.size() - 2, 2, "mm") == 0) {
    scale = 1e-3;
    number = t.substr(0, t.size() - 2);
  } else if (t.size() > 1 && t.back() == 'm') {
    scale = 1.0;
    number = t.substr(0, t.size() - 1);
  } else {
    throw fail();
  }
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    throw fail();
  }
  if (used != number.size() || !(value > 0.0)) throw fail();
  const CoverageTolerance result = CoverageTolerance::within(value * scale);
  result.validate();
  return result;
}

namespace {

/// The cells within `tolerance.metres` of some point: each point marks the cells of the box
/// around it whose own box it lies within that distance of.
std::vector<std::uint8_t> marks_within(const GridSpec& grid, const PointCloud& points_world,
                                       double metres) {
  std::vector<std::uint8_t> marks(grid.num_cells(), 0);
  const double res = grid.resolution;
  const int reach = static_cast<int>(std::ceil(metres / res)) + 1;
  for (const Eigen::Vector3d& p : points_world) {
    if (!p.allFinite()) continue;
    const Index3 q = grid.lattice_index(p);
    const Index3 lo = (q - Index3::Constant(reach)).cwiseMax(Index3::Zero());
    const Index3 hi = (q + Index3::Constant(reach)).cwiseMin(grid.dims - Index3::Ones());
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const Eigen::Vector3d min = grid.origin + res * Eigen::Vector3d(x, y, z);
          const Eigen::Vector3d gap =
              (min - p).cwiseMax(p - min - Eigen::Vector3d::Constant(res)).cwiseMax(0.0);
          if (gap.squaredNorm() <= metres * metres) marks[grid.linear(Index3(x, y, z))] = 1;
        }
      }
    }
  }
  return marks;
}

}  // namespace

std::vector<std::uint32_t> covered_cells(const GridSpec& grid, std::span<const std::uint32_t> cells,
                                         const PointCloud& points_world,
                                         CoverageTolerance tolerance_rule) {
  tolerance_rule.validate();
  if (tolerance_rule.metres > 0.0) {
    const std::vector<std::uint8_t> marks = marks_within(grid, points_world, tolerance_rule.metres);
    std::vector<std::uint32_t> out;
    for (const std::uint32_t c : cells) {
      if (marks[c] != 0) out.push_back(c);
    }
    return out;
  }
  const int tolerance = tolerance_rule.cells;
  PaddedMarks padded(grid);
  for (const Eigen::Vector3d& p : points_world) {
    if (!p.allFinite()) continue;
    const Index3 q = grid.lattice_index(p) + Index3::Ones();
    if ((q.array() < 0).any() || (q.array() >= padded.dims.array()).any()) continue;
    padded.marks[padded.at(q)] = 1;
  }
  std::vector<std::uint32_t> out;
  for (const std::uint32_t c : cells) {
    const Index3 q = grid.unravel(c) + Index3::Ones();
    bool near = false;
    for (int dz = -tolerance; dz <= tolerance && !near; ++dz) {
      for (int dy = -tolerance; dy <= tolerance && !near; ++dy) {
        for (int dx = -tolerance; dx <= tolerance && !near; ++dx) {
          near = padded.marks[padded.at(q + Index3(dx, dy, dz))] != 0;
        }
      }
    }
    if (near) out.push_back(c);
  }
  return out;
}

std::size_t count_common(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b) {
  std::size_t n = 0;
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i < *j) {
      ++i;
    } else if (*j < *i) {
      ++j;
    } else {
      ++n;
      ++i;
      ++j;
    }
  }
  return n;
}

SurfaceTruth compute_surface_truth(const sim::World& world,
                                   std::span<const Eigen::Isometry3d> candidates,
                                   CoverageTolerance tolerance,
                                   int num_threads) {
  const auto start = std::chrono::steady_clock::now();
  const sim::Scene& scene = world.scene();
  SurfaceTruth truth;
  truth.grid = scene.grid;
  truth.tolerance = tolerance;
  truth.surface = object_surface_cells(scene, num_threads);
  // NOTE: noise-free means the range noise only: the scan is taken from the true pose, and its
  // points are placed through it, so pose noise never enters.
  sim::SensorConfig sensor = scene.sensor;
  sensor.noise = sim::RangeNoise{};
  // NOTE: a run's measured points are the objects' (the mapper segments the table away), so the
  // points on a support are dropped here too: else the table around an object's foot would
  // cover its lowest cells, which no run can.
  std::vector<Eigen::AlignedBox3d> supports;
  for (const sim::Shape& shape : scene.shapes) {
    if (is_support(shape)) supports.push_back(shape.bounds());
  }
  auto hits_from = [&](const Eigen::Isometry3d& pose) {
    const sim::SimulatedScan scan = world.scan(pose, sensor, 0);
    PointCloud objects;
    for (const Eigen::Vector3d& p : scan.points_sensor) {
      const Eigen::Vector3d q = pose * p;
      if (!on_support(supports, q)) objects.push_back(q);
    }
    return covered_cells(truth.grid, truth.surface, objects, tolerance);
  };
  std::vector<std::uint8_t> seen(truth.grid.num_cells(), 0);
  for (const Eigen::Isometry3d& pose : candidates) {
    truth.candidate_hits.push_back(hits_from(pose));
    for (const std::uint32_t c : truth.candidate_hits.back()) seen[c] = 1;
  }
  for (const Eigen::Isometry3d& pose : scene.start_poses) {
    truth.start_hits.push_back(hits_from(pose));
    for (const std::uint32_t c : truth.start_hits.back()) seen[c] = 1;
  }
  for (const std::uint32_t c : truth.surface) {
    if (seen[c] != 0) truth.visible.push_back(c);
  }
  truth.seconds = seconds_since(start);
  return truth;
}

SurfaceCoverage surface_coverage(const SurfaceTruth& truth, const PointCloud& points_world) {
  SurfaceCoverage result;
  const std::vector<std::uint32_t> covered =
      covered_cells(truth.grid, truth.surface, points_world, truth.tolerance);
  std::set_intersection(covered.begin(), covered.end(), truth.visible.begin(), truth.visible.end(),
                        std::back_inserter(result.covered));
  if (!truth.visible.empty()) {
    result.visible =
        static_cast<double>(result.covered.size()) / static_cast<double>(truth.visible.size());
  }
  if (!truth.surface.empty()) {
    result.raw = static_cast<double>(covered.size()) / static_cast<double>(truth.surface.size());
  }
  return result;
}

}  // namespace vantage
