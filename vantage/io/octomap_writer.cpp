// Writing an OctoMap (octomap_io.hpp): the grid's known cells as an OcTree at their OctoMap
// keys, pruned, as a .bt (free and occupied) or a lossless .ot (every log-odds).

#include <octomap/OcTree.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/detail/octomap_keys.hpp"
#include "vantage/io/octomap_io.hpp"

namespace vantage {
namespace fs = std::filesystem;

using detail::kBinaryHeader;
using detail::kFullHeader;
using detail::kKeyCenter;
using detail::require_key_range;
using detail::Voxel;
using detail::voxel_offset;

OctomapExport write_octomap(const fs::path& path, const OccupancyGrid& grid) {
  const OctomapFormat format = octomap_format_of(path);
  const GridSpec& spec = grid.spec();
  const Voxel n = voxel_offset(spec);
  require_key_range(spec, n, path.string());

  OctomapExport result;
  result.format = format;
  octomap::OcTree tree(spec.resolution);
  tree.setClampingThresMin(grid.params().p_min);
  tree.setClampingThresMax(grid.params().p_max);
  const float free_value = tree.getClampingThresMinLog();
  const float occupied_value = tree.getClampingThresMaxLog();

  std::size_t i = 0;
  for (int z = 0; z < spec.dims.z(); ++z) {
    for (int y = 0; y < spec.dims.y(); ++y) {
      for (int x = 0; x < spec.dims.x(); ++x, ++i) {
        const float l = grid.log_odds(i);
        const CellState state = grid.state_of(l);
        float value = l;
        if (format == OctomapFormat::kBinary) {
          // NOTE: .bt knows only free and occupied leaves; writing each class at one value lets
          // OctoMap's pruning merge whole regions of a class.
          if (state == CellState::kUnobserved) continue;
          value = state == CellState::kOccupied ? occupied_value : free_value;
        } else if (l == 0.0f) {
          continue;  // p = 0.5 exactly: unknown, no node
        }
        switch (state) {
          case CellState::kFree:
            ++result.free_cells;
            break;
          case CellState::kOccupied:
            ++result.occupied_cells;
            break;
          case CellState::kUnobserved:
            ++result.unobserved_cells;
            break;
        }
        const octomap::OcTreeKey key(static_cast<octomap::key_type>(x + n[0] + kKeyCenter),
                                     static_cast<octomap::key_type>(y + n[1] + kKeyCenter),
                                     static_cast<octomap::key_type>(z + n[2] + kKeyCenter));
        // NOTE: setNodeValue clamps to the tree's thresholds, which are float(logit) of the same
        // probabilities as the grid's; setting the value on the node keeps it bit for bit anyway.
        octomap::OcTreeNode* node = tree.setNodeValue(key, value, /*lazy_eval=*/true);
        node->setLogOdds(value);
      }
    }
  }
  tree.updateInnerOccupancy();
  tree.prune();  // lossless: merges only 8 leaf siblings of equal value
  result.tree_nodes = tree.size();

  write_atomically(path, [&](std::ostream& out) {
    // NOTE: the header is OctoMap's (AbstractOcTree::write, writeBinaryConst); writing it here
    // keeps Debian's liboctomap, built with debug output, from printing to stderr, and gives
    // "res" all 17 digits.
    out.precision(std::numeric_limits<double>::max_digits10);
    out << (format == OctomapFormat::kBinary ? kBinaryHeader : kFullHeader) << "\n"
        << "# written by Vantage from a " << spec.dims.x() << " x " << spec.dims.y() << " x "
        << spec.dims.z() << " occupancy grid\n"
        << "id " << tree.getTreeType() << "\n"
        << "size " << tree.size() << "\n"
        << "res " << tree.getResolution() << "\n"
        << "data\n";
    if (format == OctomapFormat::kBinary) {
      tree.writeBinaryData(out);
    } else {
      tree.writeData(out);
    }
  });
  return result;
}

}  // namespace vantage
