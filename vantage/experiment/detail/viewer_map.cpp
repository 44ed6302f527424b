// The map's layers for `vantage view`'s page (detail/results_reader.hpp, map_layers): the
// occupied cells and the surface of what is still unobserved, read from the results' map.bt in the
// box its known voxels span when that box can stand for the grid.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "vantage/experiment/detail/results_reader.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::detail {
namespace {

/// Cell indices as one flat array (x0, y0, z0, x1, ...) of the cells `keep` picks, in the grid's
/// order, thinned evenly to at most `cap` of their `n`; a cell's index is the grid's plus `offset`
/// (where the grid's cell (0, 0, 0) lies in the results' grid).
template <typename Keep>
json cell_layer(const OccupancyGrid& grid, const Index3& offset, std::size_t n, std::size_t cap,
                Keep&& keep) {
  json flat = json::array();
  const GridSpec& spec = grid.spec();
  std::size_t k = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (!keep(i)) continue;
    // NOTE: keeps the k-th cell where floor(k * cap / n) steps up, so a cut layer stays spread
    // over the whole map instead of ending at some height.
    const bool drawn = n <= cap || (k + 1) * cap / n != k * cap / n;
    ++k;
    if (!drawn) continue;
    const Index3 c = spec.unravel(i) + offset;
    flat.push_back(c.x());
    flat.push_back(c.y());
    flat.push_back(c.z());
  }
  return {{"total", n}, {"cells", flat}};
}

/// The map read for the page: a grid and where its cell (0, 0, 0) lies in the results' grid.
struct MapBox {
  OccupancyGrid grid;
  Index3 offset = Index3::Zero();
};

/// The map in the known voxels' box grown by one cell, when its cells are the results grid's:
/// what the page draws lies there (an occupied cell is known; an unobserved cell drawn touches a
/// known one), so a small map in a large grid costs the map's cells, not the grid's (issue 39:
/// dims of 1024^3 around a 32 x 32 x 17 map took 4.45 GB). Nothing when the box cannot stand for
/// the grid (cells not on OctoMap's lattice, another resolution, a known voxel outside the grid, a
/// file that cannot be read this way): the caller reads the whole grid, which says what is wrong.
std::optional<MapBox> read_map_box(const fs::path& map_file, const GridSpec& spec,
                                   const std::function<void(const GridSpec&)>& budget) {
  if (!octomap_aligned(spec)) return std::nullopt;
  OctomapImportConfig own;
  own.padding = 1;
  own.check_grid = budget;
  std::optional<OctomapImport> imported;
  try {
    imported.emplace(read_octomap(map_file, own));
  } catch (const MemoryBudgetError&) {
    throw;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const GridSpec& box = imported->grid.spec();
  if (std::abs(box.resolution - spec.resolution) > 1e-5 * spec.resolution) return std::nullopt;
  const Eigen::Vector3d shift = (box.origin - spec.origin) / spec.resolution;
  const Eigen::Vector3d rounded = shift.array().round();
  if ((shift - rounded).cwiseAbs().maxCoeff() > 1e-6) return std::nullopt;
  MapBox map{std::move(imported->grid), rounded.cast<int>()};
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    if (map.grid.state(i) != CellState::kUnobserved &&
        !spec.contains(Index3(box.unravel(i) + map.offset))) {
      return std::nullopt;  // the whole grid's read names the voxel outside it
    }
  }
  return map;
}

}  // namespace

/// The occupied cells, and the unobserved cells that touch observed space (the surface of what is
/// still unknown; cells deeper inside it would be hidden behind those anyway). Counted first and
/// drawn second, so that what the page holds is bounded by the cap whatever the grid's size.
json map_layers(const fs::path& map_file, const GridSpec& spec, const ViewerConfig& config) {
  const auto budget = [&](const GridSpec& g) {
    check_memory(
        {static_cast<std::uint64_t>(g.num_cells()), kViewerBytesPerCell, kViewerFixedBytes},
        config.max_memory,
        fmt::format("vantage view of {} ({} x {} x {} cells)", map_file.string(), g.dims.x(),
                    g.dims.y(), g.dims.z()));
  };
  std::optional<MapBox> map = read_map_box(map_file, spec, budget);
  if (!map) {
    budget(spec);
    OctomapImportConfig import;
    import.grid = spec;
    map = MapBox{read_octomap(map_file, import).grid, Index3::Zero()};
  }
  const OccupancyGrid& grid = map->grid;
  const GridSpec& box = grid.spec();
  const std::array<Index3, 6> steps = {Index3(1, 0, 0),  Index3(-1, 0, 0), Index3(0, 1, 0),
                                       Index3(0, -1, 0), Index3(0, 0, 1),  Index3(0, 0, -1)};
  // NOTE: cells of the box outside the results' grid (its padding) are neither drawn nor counted.
  const auto inside = [&](std::size_t i) {
    return spec.contains(Index3(box.unravel(i) + map->offset));
  };
  const auto occupied = [&](std::size_t i) {
    return grid.state(i) == CellState::kOccupied && inside(i);
  };
  const auto surface = [&](std::size_t i) {
    if (grid.state(i) != CellState::kUnobserved || !inside(i)) return false;
    const Index3 c = box.unravel(i);
    for (const Index3& step : steps) {
      const Index3 n = c + step;
      if (box.contains(n) && spec.contains(Index3(n + map->offset)) &&
          grid.state(box.linear(n)) != CellState::kUnobserved) {
        return true;
      }
    }
    return false;
  };
  std::size_t n_occupied = 0, n_surface = 0, known = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    n_occupied += occupied(i) ? 1 : 0;
    n_surface += surface(i) ? 1 : 0;
    known += grid.state(i) != CellState::kUnobserved && inside(i) ? 1 : 0;
  }
  json layers = {
      {"occupied", cell_layer(grid, map->offset, n_occupied, config.max_cells, occupied)},
      {"unobserved", cell_layer(grid, map->offset, n_surface, config.max_cells, surface)}};
  layers["unobserved"]["all"] = spec.num_cells() - known;
  return layers;
}

}  // namespace vantage::detail
