#include "vantage/io/octomap_io.hpp"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/detail/octomap_check.hpp"
#include "vantage/io/detail/octomap_keys.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;
namespace {

using detail::fail;
using detail::kAlignmentTolerance;
using detail::kKeyCenter;
using detail::kResolutionTolerance;
using detail::kTreeDepth;
using detail::require_key_range;
using detail::TreeHeader;
using detail::Voxel;
using detail::voxel_offset;

// One leaf of the tree, expanded to the finest level: voxels [min, min + width) per axis.
struct Leaf {
  Voxel min;
  std::int64_t width;
  float log_odds;
  bool occupied;
};

template <typename Tree>
std::vector<Leaf> leaves_of(const Tree& tree) {
  std::vector<Leaf> leaves;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const octomap::OcTreeKey key = it.getIndexKey();
    const int level = kTreeDepth - static_cast<int>(it.getDepth());
    leaves.push_back({{key[0] - kKeyCenter, key[1] - kKeyCenter, key[2] - kKeyCenter},
                      std::int64_t{1} << level,
                      it->getLogOdds(),
                      tree.isNodeOccupied(*it)});
  }
  return leaves;
}

std::vector<Leaf> decode(const std::string& bytes, const TreeHeader& header) {
  std::istringstream in(bytes.substr(header.data_offset));
  if (header.format == OctomapFormat::kBinary) {
    octomap::OcTree tree(header.resolution);
    tree.readBinaryData(in);
    return leaves_of(tree);
  }
  if (header.id == "ColorOcTree") {
    octomap::ColorOcTree tree(header.resolution);
    tree.readData(in);
    return leaves_of(tree);
  }
  octomap::OcTree tree(header.resolution);
  tree.readData(in);
  return leaves_of(tree);
}

std::string read_bytes(const fs::path& path) {
  try {
    return read_input_file(path, InputKind::kOctomap);
  } catch (const FormatError& e) {
    fail(path, e.what());
  }
}

GridSpec derive_spec(const std::vector<Leaf>& leaves, double resolution, int padding,
                     const fs::path& path) {
  if (leaves.empty()) fail(path, "the tree has no known voxels, so no grid can be derived from it");
  Voxel lo, hi;
  lo.fill(std::numeric_limits<std::int64_t>::max());
  hi.fill(std::numeric_limits<std::int64_t>::min());
  for (const Leaf& leaf : leaves) {
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], leaf.min[a]);
      hi[a] = std::max(hi[a], leaf.min[a] + leaf.width - 1);
    }
  }
  GridSpec spec;
  spec.resolution = resolution;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::int64_t cells = hi[a] - lo[a] + 1 + 2 * std::int64_t{padding};
    if (cells > std::numeric_limits<int>::max()) {
      fail(path,
           cat("the tree spans ", cells, " voxels along ", "xyz"[a], ", too many for a grid"));
    }
    spec.dims[static_cast<int>(a)] = static_cast<int>(cells);
    spec.origin[static_cast<int>(a)] = static_cast<double>(lo[a] - padding) * resolution;
  }
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    fail(path, cat("the grid that holds the tree is unusable: ", e.what()));
  }
  return spec;
}

/// The grid the tree goes into: the one given, at the tree's resolution, or one derived from
/// the tree's leaves.
GridSpec grid_for_tree(const std::vector<Leaf>& leaves, const TreeHeader& header,
                       const OctomapImportConfig& config, const fs::path& path) {
  if (!config.grid) return derive_spec(leaves, header.resolution, config.padding, path);
  const GridSpec& spec = *config.grid;
  const double mismatch = std::abs(header.resolution - spec.resolution) / spec.resolution;
  if (mismatch > kResolutionTolerance) {
    fail(path, cat("the tree's resolution ", header.resolution,
                   " m does not match the grid's resolution ", spec.resolution, " m"));
  }
  return spec;
}

/// Sets the cells of `leaf` that lie in the grid (`n`: the grid's voxel offset), counting them
/// known and those outside cropped, or failing on those outside when not cropping.
void import_leaf(const Leaf& leaf, const Voxel& n, const TreeHeader& header,
                 const OctomapImportConfig& config, const fs::path& path, OctomapImport& result) {
  OccupancyGrid& grid = result.grid;
  const GridSpec& spec = grid.spec();
  // The leaf's voxels in grid cell coordinates, and their part inside the grid.
  Voxel lo, hi;
  std::uint64_t inside = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::int64_t first = leaf.min[a] - n[a];
    lo[a] = std::max<std::int64_t>(first, 0);
    hi[a] = std::min<std::int64_t>(first + leaf.width, spec.dims[static_cast<int>(a)]);
    inside *= hi[a] > lo[a] ? static_cast<std::uint64_t>(hi[a] - lo[a]) : 0u;
  }
  const auto total = static_cast<std::uint64_t>(leaf.width) *
                     static_cast<std::uint64_t>(leaf.width) *
                     static_cast<std::uint64_t>(leaf.width);
  if (inside < total) {
    if (!config.crop) {
      const double r = header.resolution;
      fail(path,
           cat("the tree has known voxels outside the grid, e.g. the leaf at (",
               static_cast<double>(leaf.min[0]) * r, ", ", static_cast<double>(leaf.min[1]) * r,
               ", ", static_cast<double>(leaf.min[2]) * r,
               ") m; give a grid that holds the tree, or crop"));
    }
    result.cropped_voxels += total - inside;
  }
  if (inside == 0) return;
  result.known_voxels += inside;

  float value = leaf.log_odds;
  if (header.format == OctomapFormat::kBinary) {
    value =
        static_cast<float>(logit(leaf.occupied ? config.occupancy.p_max : config.occupancy.p_min));
  }
  const CellState wanted = header.format == OctomapFormat::kBinary
                               ? (leaf.occupied ? CellState::kOccupied : CellState::kFree)
                               : grid.state_of(value);
  for (std::int64_t z = lo[2]; z < hi[2]; ++z) {
    for (std::int64_t y = lo[1]; y < hi[1]; ++y) {
      for (std::int64_t x = lo[0]; x < hi[0]; ++x) {
        const std::size_t i =
            spec.linear(Index3(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)));
        grid.set_log_odds(i, value);
        if (grid.state(i) != wanted) {
          fail(path, cat("the voxel at cell (", x, ", ", y, ", ", z, ") has log-odds ", value,
                         ", whose class the grid's clamp [p_min ", config.occupancy.p_min,
                         ", p_max ", config.occupancy.p_max, "] cannot keep"));
        }
      }
    }
  }
}

}  // namespace

std::string_view to_string(OctomapFormat format) {
  return format == OctomapFormat::kBinary ? "bt" : "ot";
}

OctomapFormat octomap_format_of(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".bt") return OctomapFormat::kBinary;
  if (ext == ".ot") return OctomapFormat::kFull;
  throw std::invalid_argument(
      cat(path.string(), ": an OctoMap file must end in .bt or .ot, not '", ext, "'"));
}

void require_octomap_range(const GridSpec& spec, const std::string& what) {
  require_key_range(spec, voxel_offset(spec), what);
}

bool octomap_aligned(const GridSpec& spec) {
  for (int a = 0; a < 3; ++a) {
    const double o = spec.origin[a] / spec.resolution;
    if (std::abs(o - std::round(o)) > kAlignmentTolerance) return false;
  }
  return true;
}

void OctomapImportConfig::validate() const {
  if (grid) grid->validate();
  if (padding < 0) throw std::invalid_argument(cat("octomap.padding must be >= 0, got ", padding));
  if (grid && padding != 0) {
    throw std::invalid_argument("octomap.padding applies to a derived grid only; grid is given");
  }
  if (!grid && crop) {
    throw std::invalid_argument("octomap.crop applies to a given grid only; grid is not given");
  }
  occupancy.validate();
}

OctomapImport read_octomap(const fs::path& path, const OctomapImportConfig& config) {
  config.validate();
  OctomapFormat expected;
  try {
    expected = octomap_format_of(path);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  const std::string bytes = read_bytes(path);
  const TreeHeader header = detail::parse_header(bytes, path);
  if (header.format != expected) {
    fail(path, cat("the file is an OctoMap .", to_string(header.format), " file but is named .",
                   to_string(expected)));
  }
  detail::check_tree_data(std::string_view(bytes).substr(header.data_offset), header, path);
  const std::vector<Leaf> leaves = header.size > 0 ? decode(bytes, header) : std::vector<Leaf>{};

  const GridSpec spec = grid_for_tree(leaves, header, config, path);
  if (config.check_grid) config.check_grid(spec);
  const Voxel n = voxel_offset(spec);
  OctomapImport result{OccupancyGrid(spec, config.occupancy), header.format, header.id,
                       header.resolution};
  for (const Leaf& leaf : leaves) import_leaf(leaf, n, header, config, path, result);
  return result;
}

}  // namespace vantage
