#include "vantage/map/integrate.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using CellList = std::vector<std::uint32_t>;

constexpr std::uint8_t kMarkMiss = 1;
constexpr std::uint8_t kMarkHit = 2;

void require_finite(const Scan& scan) {
  for (std::size_t i = 0; i < scan.points_world.size(); ++i) {
    if (!scan.points_world[i].allFinite()) {
      throw std::invalid_argument(cat("scan point ", i, " is not finite (NaN or infinite)"));
    }
  }
}

/// Applies an update to each listed cell and sorts the cells into left / entered U.
template <typename Update>
void apply(OccupancyGrid& grid, const CellList& cells, Update&& update, IntegrationResult& out) {
  for (const std::uint32_t i : cells) {
    const bool was_unobserved = grid.is_unobserved(i);
    update(i);
    const bool is_unobserved = grid.is_unobserved(i);
    if (was_unobserved && !is_unobserved) out.left_unobserved.push_back(i);
    if (!was_unobserved && is_unobserved) out.entered_unobserved.push_back(i);
  }
}

/// A scan's points in the world, one per index.
struct PointSource {
  const PointCloud& points;
  std::size_t size() const { return points.size(); }
  bool get(std::size_t k, Eigen::Vector3d& p) const {
    p = points[k];
    return true;
  }
};

/// A depth image's ray ends in the world, one per pixel; a pixel without depth, or masked out,
/// has none.
struct DepthSource {
  const DepthFrame& frame;
  const Eigen::Isometry3d& T_world_sensor;
  std::span<const std::uint8_t> mask;
  std::size_t size() const { return frame.depth.size(); }
  bool get(std::size_t k, Eigen::Vector3d& p) const {
    const std::uint16_t d = frame.depth[k];
    if (d == frame.invalid || (!mask.empty() && mask[k] == 0)) return false;
    const auto width = static_cast<std::size_t>(frame.width);
    const Eigen::Vector3d o =
        frame.optical_point(static_cast<int>(k % width), static_cast<int>(k / width), d);
    // NOTE: the optical frame (z forward, x right, y down) turned into the sensor's (x forward,
    // y left, z up), exactly as the rotation matrix of its 0 and +-1 entries turns it.
    p = T_world_sensor * Eigen::Vector3d(o.z(), -o.x(), -o.y());
    return true;
  }
};

/// The distinct cells holding the scan's points, ascending.
template <typename Source>
CellList hit_cells(const GridSpec& spec, const Source& source, IntegrationResult& out) {
  CellList cells;
  cells.reserve(source.size());
  Eigen::Vector3d p;
  for (std::size_t k = 0; k < source.size(); ++k) {
    if (!source.get(k, p)) continue;
    if (const auto cell = spec.find(p)) {
      cells.push_back(static_cast<std::uint32_t>(spec.linear(*cell)));
      ++out.points_inside;
    } else {
      ++out.points_outside;
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

/// Unknown-space estimation (§4.3.1): the unobserved cells in the frustum with a clear line of
/// sight from the scan's origin. The grid is only read; rows run in parallel and are joined in
/// order.
CellList visible_unobserved(const OccupancyGrid& grid, const Frustum& view) {
  const GridSpec& spec = grid.spec();
  const Eigen::AlignedBox3d box = view.bounds();
  const Index3 lo = spec.lattice_index(box.min()).cwiseMax(Index3::Zero());
  const Index3 hi = spec.lattice_index(box.max()).cwiseMin(spec.dims - Index3::Ones());
  if ((hi.array() < lo.array()).any()) return {};
  const int ny = hi.y() - lo.y() + 1;
  const auto rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(hi.z() - lo.z() + 1);
  std::vector<CellList> per_row(rows);
  const Eigen::Vector3d origin = view.origin();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const auto& range) {
    for (std::size_t row = range.begin(); row != range.end(); ++row) {
      Index3 cell(0, lo.y() + static_cast<int>(row % static_cast<std::size_t>(ny)),
                  lo.z() + static_cast<int>(row / static_cast<std::size_t>(ny)));
      for (cell.x() = lo.x(); cell.x() <= hi.x(); ++cell.x()) {
        const std::size_t linear = spec.linear(cell);
        if (grid.is_unobserved(linear) && view.contains(spec.center(cell)) &&
            line_of_sight(grid, origin, cell)) {
          per_row[row].push_back(static_cast<std::uint32_t>(linear));
        }
      }
    }
  });
  CellList cells;
  for (const CellList& row : per_row) cells.insert(cells.end(), row.begin(), row.end());
  return cells;
}

template <typename Source>
IntegrationResult integrate_paper(OccupancyGrid& grid, const Source& source, const Frustum& view,
                                  const IntegrationConfig& config) {
  IntegrationResult out;
  const CellList hits = hit_cells(grid.spec(), source, out);
  out.hit_cells = hits.size();
  apply(
      grid, hits, [&](std::uint32_t i) { grid.hit(i); }, out);

  const HoleFillingResult filled = fill_holes(grid, config.hole_filling);
  out.filled_cells = filled.filled.size();
  out.left_unobserved.insert(out.left_unobserved.end(), filled.filled.begin(), filled.filled.end());

  const CellList misses = visible_unobserved(grid, view);
  out.missed_cells = misses.size();
  apply(
      grid, misses, [&](std::uint32_t i) { grid.miss(i); }, out);
  return out;
}

template <typename Source>
IntegrationResult integrate_endpoint(OccupancyGrid& grid, const Source& source,
                                     const Frustum& view) {
  IntegrationResult out;
  const GridSpec& spec = grid.spec();
  const Eigen::Vector3d origin = view.origin();
  std::vector<std::uint8_t> marks(grid.size(), 0);
  tbb::enumerable_thread_specific<CellList> touched_by_thread;

  auto mark = [&](std::size_t linear, std::uint8_t bit, CellList& touched) {
    std::atomic_ref<std::uint8_t> flag(marks[linear]);
    if (flag.fetch_or(bit, std::memory_order_relaxed) == 0) {
      touched.push_back(static_cast<std::uint32_t>(linear));
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size(), 256), [&](const auto& range) {
    CellList& touched = touched_by_thread.local();
    Eigen::Vector3d point;
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      if (!source.get(k, point)) continue;
      const auto end = spec.find(point);
      const std::size_t end_linear = end ? spec.linear(*end) : SIZE_MAX;
      traverse(spec, origin, point, [&](const Index3&, std::size_t linear, int) {
        if (linear != end_linear) mark(linear, kMarkMiss, touched);
      });
      if (end) mark(end_linear, kMarkHit, touched);
    }
  });

  CellList touched;
  for (const CellList& part : touched_by_thread)
    touched.insert(touched.end(), part.begin(), part.end());
  std::sort(touched.begin(), touched.end());  // a fixed order, whatever the threads did
  Eigen::Vector3d p;
  for (std::size_t k = 0; k < source.size(); ++k) {
    if (source.get(k, p)) ++(spec.find(p) ? out.points_inside : out.points_outside);
  }
  apply(
      grid, touched,
      [&](std::uint32_t i) {
        if (marks[i] & kMarkHit) {
          grid.hit(i);
          ++out.hit_cells;
        } else {
          grid.miss(i);
          ++out.missed_cells;
        }
      },
      out);
  return out;
}

}  // namespace

std::string_view to_string(IntegrationMode mode) {
  switch (mode) {
    case IntegrationMode::kPaper:
      return "paper";
    case IntegrationMode::kEndpoint:
      return "endpoint";
  }
  return "unknown";
}

IntegrationMode parse_integration_mode(std::string_view name) {
  if (name == "paper") return IntegrationMode::kPaper;
  if (name == "endpoint") return IntegrationMode::kEndpoint;
  throw std::invalid_argument(
      cat("unknown integration mode '", name, "' (expected paper or endpoint)"));
}

void IntegrationConfig::validate() const {
  hole_filling.validate();
  if (num_threads < 0) {
    throw std::invalid_argument(cat("integration.num_threads must be >= 0, got ", num_threads));
  }
}

namespace {

template <typename Source>
IntegrationResult integrate(OccupancyGrid& grid, const Source& source, const Frustum& view,
                            const IntegrationConfig& config) {
  IntegrationResult result;
  run_with_threads(config.num_threads, [&] {
    result = config.mode == IntegrationMode::kPaper ? integrate_paper(grid, source, view, config)
                                                    : integrate_endpoint(grid, source, view);
  });
  std::sort(result.left_unobserved.begin(), result.left_unobserved.end());
  std::sort(result.entered_unobserved.begin(), result.entered_unobserved.end());
  return result;
}

}  // namespace

IntegrationResult integrate_scan(OccupancyGrid& grid, const Scan& scan,
                                 const IntegrationConfig& config) {
  config.validate();
  require_finite(scan);
  return integrate(grid, PointSource{scan.points_world}, scan.view, config);
}

void DepthFrame::validate() const {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (width < 1 || height < 1) {
    throw std::invalid_argument(
        cat("depth frame: size must be positive, got ", width, " x ", height));
  }
  if (!positive(fx) || !positive(fy)) {
    throw std::invalid_argument(cat("depth frame: fx and fy must be > 0, got ", fx, " and ", fy));
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) {
    throw std::invalid_argument(
        cat("depth frame: cx and cy must be finite, got ", cx, " and ", cy));
  }
  if (!positive(units_per_metre)) {
    throw std::invalid_argument(
        cat("depth frame: units_per_metre must be > 0, got ", units_per_metre));
  }
  if (depth.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument(
        cat("depth frame: ", depth.size(), " depth values for ", width, " x ", height, " pixels"));
  }
}

Eigen::Vector3d DepthFrame::optical_point(int u, int v, std::uint16_t d) const {
  const auto round = [](double x) { return static_cast<double>(static_cast<float>(x)); };
  const double z = static_cast<double>(d) / units_per_metre;
  return {round((u - cx) * z / fx), round((v - cy) * z / fy), round(z)};
}

IntegrationResult integrate_depth(OccupancyGrid& grid, const DepthFrame& frame, const Frustum& view,
                                  const IntegrationConfig& config,
                                  std::span<const std::uint8_t> mask) {
  config.validate();
  frame.validate();
  if (!mask.empty() && mask.size() != frame.depth.size()) {
    throw std::invalid_argument(
        cat("depth frame: a mask of ", mask.size(), " values for ", frame.depth.size(), " pixels"));
  }
  return integrate(grid, DepthSource{frame, view.T_world_sensor(), mask}, view, config);
}

}  // namespace vantage
