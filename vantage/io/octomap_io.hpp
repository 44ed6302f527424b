#pragma once
/// @file
/// OctoMap interchange: an OccupancyGrid to and from OctoMap's `.bt` and `.ot` files.
///
/// How docs/model.md's three classes meet OctoMap's nodes:
///
/// | grid cell                        | written to `.bt`          | written to `.ot`             |
/// |----------------------------------|---------------------------|------------------------------|
/// | free, p <= 0.4                   | free leaf                 | leaf with the cell's log-odds|
/// | occupied, p >= 0.6               | occupied leaf             | leaf with the cell's log-odds|
/// | unobserved, p == 0.5 exactly     | no node (unknown)         | no node (unknown)            |
/// | unobserved, 0.4 < p < 0.6, != 0.5| no node (unknown)         | leaf with the cell's log-odds|
///
/// | OctoMap voxel                    | read from `.bt`           | read from `.ot`              |
/// |----------------------------------|---------------------------|------------------------------|
/// | no node (unknown)                | p = 0.5, unobserved       | p = 0.5, unobserved          |
/// | free leaf (log-odds < 0)         | p = p_min, free           | the node's log-odds, clamped |
/// | occupied leaf (log-odds >= 0)    | p = p_max, occupied       | the node's log-odds, clamped |
///
/// So `.bt` carries the classes free and occupied and turns every unobserved cell into unknown
/// (p = 0.5): a round trip keeps every cell's class but not its probability. `.ot` keeps every
/// stored log-odds value bit for bit (both store float log-odds), so the unobserved band with
/// p != 0.5 survives only in `.ot`. Nodes are stored at the finest level and merged by OctoMap's
/// lossless pruning; coarse leaves of foreign trees are expanded to cells on import.
///
/// Geometry: OctoMap's voxels lie on the lattice of its resolution through the world origin. A
/// grid whose origin is a whole multiple of its resolution (`octomap_aligned`) maps each cell to
/// the voxel it coincides with. Otherwise every cell maps to the voxel that holds its centre,
/// ties going to the upper voxel (a grid from GridSpec::centered with an odd number of cells puts
/// centres exactly on voxel faces); that voxel is then displaced from the cell by less than half a
/// cell on each axis. Import applies the same rule in reverse, so a round trip through the same
/// GridSpec is exact either way.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// OctoMap's two file formats.
enum class OctomapFormat {
  kBinary,  ///< `.bt`: the tree's structure with each leaf free or occupied
  kFull,    ///< `.ot`: the tree with every node's float log-odds
};

std::string_view to_string(OctomapFormat format);

/// The format a file name asks for: `.bt` or `.ot` (case-insensitive); throws
/// std::invalid_argument naming the path otherwise.
OctomapFormat octomap_format_of(const std::filesystem::path& path);

/// Whether the grid's cells coincide with OctoMap voxels: its origin is a whole multiple of its
/// resolution on every axis (within 1e-6 of a cell).
bool octomap_aligned(const GridSpec& spec);

/// Throws std::invalid_argument, naming `what` (the grid's source), when the grid's cells lie
/// outside OctoMap's key range (±32768 voxels around the origin), so its map could not be
/// written; a run that ends in map files checks it before its work.
void require_octomap_range(const GridSpec& spec, const std::string& what);

/// What an export wrote.
struct OctomapExport {
  OctomapFormat format = OctomapFormat::kBinary;
  std::size_t free_cells = 0;        ///< cells written as free
  std::size_t occupied_cells = 0;    ///< cells written as occupied
  std::size_t unobserved_cells = 0;  ///< unobserved cells with p != 0.5 written (`.ot` only)
  std::size_t tree_nodes = 0;        ///< nodes of the pruned tree
};

/// Writes the grid as an OctoMap OcTree with the grid's resolution, in the format the extension
/// names (see the table above), atomically. Throws std::invalid_argument for another extension or
/// a grid outside OctoMap's key range (±32768 voxels around the origin), and std::runtime_error
/// naming the path when writing fails.
OctomapExport write_octomap(const std::filesystem::path& path, const OccupancyGrid& grid);

/// How an OctoMap file is read into a grid.
struct OctomapImportConfig {
  /// The grid to fill. Its resolution must match the tree's (relative 1e-5, as OctoMap prints
  /// six significant digits). Nothing: derive it from the tree — the smallest box of whole voxels
  /// that holds every known voxel, grown by `padding` cells on every side.
  std::optional<GridSpec> grid;
  int padding = 0;  ///< cells added on every side of a derived grid
  /// With a given grid: drop known voxels outside it (counted in OctomapImport::cropped_voxels)
  /// instead of failing.
  bool crop = false;
  OccupancyParams occupancy;  ///< the new grid's parameters; `.bt` leaves take p_min and p_max
  /// Called with the grid, given or derived, before it is allocated; may throw to refuse it (a
  /// memory budget: a tree of a hundred bytes can derive a grid of 2^30 cells).
  std::function<void(const GridSpec&)> check_grid;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// A grid read from an OctoMap file.
struct OctomapImport {
  OccupancyGrid grid;
  OctomapFormat format = OctomapFormat::kBinary;
  std::string tree_type;             ///< "OcTree" or "ColorOcTree" (colours are ignored)
  double tree_resolution = 0.0;      ///< as the file states it [m]
  std::uint64_t known_voxels = 0;    ///< finest-level voxels of the tree's leaves inside the grid
  std::uint64_t cropped_voxels = 0;  ///< known voxels outside the grid, dropped (crop only)
};

/// Reads a `.bt` or `.ot` file (the extension must match the file's header). Every error — a
/// missing file, a header of the wrong type, a truncated or malformed tree, a resolution mismatch,
/// a known voxel outside the grid without `crop`, a value the grid's clamp cannot keep in its class
/// — throws std::runtime_error with one line that names the file.
OctomapImport read_octomap(const std::filesystem::path& path,
                           const OctomapImportConfig& config = {});

}  // namespace vantage
