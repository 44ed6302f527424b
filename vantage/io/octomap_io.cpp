#include "vantage/io/octomap_io.hpp"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/detail/octomap_keys.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;
namespace {

using detail::kAlignmentTolerance;
using detail::kBinaryHeader;
using detail::kFullHeader;
using detail::kKeyCenter;
using detail::kKeyCount;
using detail::kMaxResolution;
using detail::kMinResolution;
using detail::kResolutionTolerance;
using detail::kTreeDepth;
using detail::require_key_range;
using detail::Voxel;
using detail::voxel_offset;

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw std::runtime_error(cat(path.string(), ": ", message));
}

// ---- reading -------------------------------------------------------------------------------

struct TreeHeader {
  OctomapFormat format = OctomapFormat::kBinary;
  std::string id;
  std::uint64_t size = 0;
  double resolution = 0.0;
  std::size_t data_offset = 0;
};

// Parses the text header the way OctoMap's AbstractOcTree::readHeader does (keywords id, size,
// res, comment lines, then "data"), but reports what is wrong instead of printing to stderr.
TreeHeader parse_header(const std::string& bytes, const fs::path& path) {
  TreeHeader header;
  std::size_t eol = bytes.find('\n');
  const std::string_view first =
      std::string_view(bytes).substr(0, eol == std::string::npos ? bytes.size() : eol);
  if (first.starts_with(kBinaryHeader)) {
    header.format = OctomapFormat::kBinary;
  } else if (first.starts_with(kFullHeader)) {
    header.format = OctomapFormat::kFull;
  } else {
    fail(path, cat("not an OctoMap file: the first line is not '", kBinaryHeader, "' or '",
                   kFullHeader, "'"));
  }
  bool have_id = false, have_size = false, have_res = false, have_data = false;
  std::size_t pos = eol == std::string::npos ? bytes.size() : eol + 1;
  while (pos < bytes.size() && !have_data) {
    eol = bytes.find('\n', pos);
    const std::size_t end = eol == std::string::npos ? bytes.size() : eol;
    std::istringstream line(bytes.substr(pos, end - pos));
    pos = eol == std::string::npos ? bytes.size() : eol + 1;
    std::string keyword;
    if (!(line >> keyword) || keyword.starts_with("#")) continue;
    // NOTE: OctoMap's reader takes the last of a keyword given twice; a header that states its
    // resolution twice is corrupt, not a choice to make for it.
    if ((keyword == "id" && have_id) || (keyword == "size" && have_size) ||
        (keyword == "res" && have_res)) {
      fail(path, cat("header: '", keyword, "' is given twice"));
    }
    if (keyword == "data") {
      have_data = true;
    } else if (keyword == "id") {
      have_id = static_cast<bool>(line >> header.id);
    } else if (keyword == "size") {
      std::string value;
      line >> value;
      const auto [ptr, ec] =
          std::from_chars(value.data(), value.data() + value.size(), header.size);
      if (ec != std::errc() || ptr != value.data() + value.size() || value.empty()) {
        fail(path, cat("header: 'size' is not a node count: '", printable(value, 40), "'"));
      }
      have_size = true;
    } else if (keyword == "res") {
      if (!(line >> header.resolution) || !std::isfinite(header.resolution) ||
          header.resolution <= 0.0) {
        fail(path, "header: 'res' is not a positive resolution");
      }
      if (header.resolution < kMinResolution || header.resolution > kMaxResolution) {
        fail(path, cat("header: 'res' ", header.resolution, " m is not a map's resolution (",
                       kMinResolution, " .. ", kMaxResolution, " m)"));
      }
      have_res = true;
    }
    // NOTE: OctoMap skips unknown keywords (with a warning); so do we.
  }
  if (!have_data) fail(path, "header: no 'data' line (truncated file?)");
  if (!have_id) fail(path, "header: no tree 'id'");
  if (!have_res) fail(path, "header: no 'res'");
  if (!have_size) fail(path, "header: no 'size'");
  // NOTE: a .bt holds occupancy bits whatever the tree's type; OctoMap writes its own type's name
  // (OcTree, or ColorOcTree for a coloured tree's bits), and any other name is not its writer's.
  if (header.format == OctomapFormat::kBinary && header.id != "OcTree" &&
      header.id != "ColorOcTree") {
    fail(path,
         cat("tree type '", printable(header.id, 40), "' is not supported (OcTree, ColorOcTree)"));
  }
  header.data_offset = pos;
  return header;
}

// Walks the serialized tree without building it, so that a truncated or corrupt file is
// reported instead of handed to OctoMap's reader (which reads past the end of a stream and can
// then build arbitrarily large trees). Counts the nodes as OctoMap does.
class StructureCheck {
 public:
  StructureCheck(std::string_view data, std::size_t payload) : data_(data), payload_(payload) {}

  std::uint64_t walk_binary() {
    nodes_ = 1;
    binary_node(0);
    return nodes_;
  }
  std::uint64_t walk_full() {
    nodes_ = 1;
    full_node(0);
    return nodes_;
  }
  std::size_t consumed() const { return pos_; }

 private:
  void need(std::size_t n) const {
    if (data_.size() - pos_ < n) {
      throw std::runtime_error(cat("truncated tree data: node ", nodes_, " needs ", n,
                                   " bytes at offset ", pos_, " but the data ends at ",
                                   data_.size()));
    }
  }

  // An inner node: two bytes of 2-bit child codes (00 unknown, 10 free, 01 occupied, 11 inner).
  void binary_node(int depth) {
    need(2);
    const auto a = static_cast<unsigned char>(data_[pos_]);
    const auto b = static_cast<unsigned char>(data_[pos_ + 1]);
    pos_ += 2;
    std::array<bool, 8> inner{};
    bool any = false;
    for (unsigned i = 0; i < 8; ++i) {
      const unsigned byte = i < 4 ? a : b;
      const unsigned code = (byte >> (2 * (i % 4))) & 3u;
      if (code == 0) continue;
      any = true;
      ++nodes_;
      inner[i] = code == 3;
    }
    if (!any)
      throw std::runtime_error(cat("malformed tree: inner node ", nodes_, " has no children"));
    for (unsigned i = 0; i < 8; ++i) {
      if (!inner[i]) continue;
      if (depth + 1 >= kTreeDepth) {
        throw std::runtime_error("malformed tree: an inner node below OctoMap's depth of 16");
      }
      binary_node(depth + 1);
    }
  }

  // A node: its payload (float log-odds first), then one byte of child-exists bits.
  void full_node(int depth) {
    need(payload_ + 1);
    float value;
    std::memcpy(&value, data_.data() + pos_, sizeof value);
    if (!std::isfinite(value)) {
      throw std::runtime_error(cat("node ", nodes_, " holds a non-finite log-odds value"));
    }
    pos_ += payload_;
    const auto children = static_cast<unsigned char>(data_[pos_++]);
    for (unsigned i = 0; i < 8; ++i) {
      if (((children >> i) & 1u) == 0) continue;
      if (depth + 1 > kTreeDepth) {
        throw std::runtime_error("malformed tree: a node below OctoMap's depth of 16");
      }
      ++nodes_;
      full_node(depth + 1);
    }
  }

  std::string_view data_;
  std::size_t payload_;
  std::size_t pos_ = 0;
  std::uint64_t nodes_ = 0;
};

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
  const TreeHeader header = parse_header(bytes, path);
  if (header.format != expected) {
    fail(path, cat("the file is an OctoMap .", to_string(header.format), " file but is named .",
                   to_string(expected)));
  }

  std::size_t payload = 0;
  if (header.format == OctomapFormat::kFull) {
    if (header.id == "OcTree") {
      payload = sizeof(float);
    } else if (header.id == "ColorOcTree") {
      payload = sizeof(float) + 3;
    } else {
      fail(path, cat("tree type '", printable(header.id, 40),
                     "' is not supported (OcTree, ColorOcTree)"));
    }
  }

  const std::string_view data = std::string_view(bytes).substr(header.data_offset);
  std::vector<Leaf> leaves;
  if (header.size > 0) {
    StructureCheck check(data, payload);
    std::uint64_t nodes = 0;
    // NOTE: a full tree whose nodes are of another type than its header names (a ColorOcTree's
    // data under "OcTree", issue 53) is said as such, not as the walk's first complaint.
    const auto other_type = [&] {
      if (header.format != OctomapFormat::kFull) return;
      for (const auto& [other, bytes_a_node] :
           {std::pair<std::string_view, std::size_t>{"OcTree", sizeof(float)},
            {"ColorOcTree", sizeof(float) + 3},
            {"OcTreeStamped", sizeof(float) + sizeof(std::uint32_t)}}) {
        if (bytes_a_node == payload) continue;
        StructureCheck alternative(data, bytes_a_node);
        bool whole = false;
        try {
          whole = alternative.walk_full() == header.size && alternative.consumed() == data.size();
        } catch (const std::runtime_error&) {
        }
        if (whole) {
          fail(path,
               cat("the header names tree type '", printable(header.id, 40), "' (", payload,
                   " bytes a node), but its data reads whole as ", header.size, " ", other,
                   " nodes (", bytes_a_node, " bytes each): the header names the wrong type"));
        }
      }
    };
    try {
      nodes = header.format == OctomapFormat::kBinary ? check.walk_binary() : check.walk_full();
    } catch (const std::runtime_error& e) {
      other_type();
      fail(path, e.what());
    }
    if (nodes != header.size) {
      other_type();
      fail(path, cat("the header announces ", header.size, " nodes but the data holds ", nodes));
    }
    if (check.consumed() != data.size()) {
      fail(path, cat(data.size() - check.consumed(), " unexpected bytes after the tree data"));
    }
    leaves = decode(bytes, header);
  } else if (!data.empty()) {
    fail(path,
         cat("the header announces an empty tree but ", data.size(), " bytes of data follow"));
  }

  GridSpec spec;
  if (config.grid) {
    spec = *config.grid;
    const double mismatch = std::abs(header.resolution - spec.resolution) / spec.resolution;
    if (mismatch > kResolutionTolerance) {
      fail(path, cat("the tree's resolution ", header.resolution,
                     " m does not match the grid's resolution ", spec.resolution, " m"));
    }
  } else {
    spec = derive_spec(leaves, header.resolution, config.padding, path);
  }
  if (config.check_grid) config.check_grid(spec);
  const Voxel n = voxel_offset(spec);

  OctomapImport result{OccupancyGrid(spec, config.occupancy), header.format, header.id,
                       header.resolution};
  OccupancyGrid& grid = result.grid;
  const auto p_free = static_cast<float>(logit(config.occupancy.p_min));
  const auto p_occupied = static_cast<float>(logit(config.occupancy.p_max));

  for (const Leaf& leaf : leaves) {
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
    if (inside == 0) continue;
    result.known_voxels += inside;

    float value = leaf.log_odds;
    if (header.format == OctomapFormat::kBinary) value = leaf.occupied ? p_occupied : p_free;
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
  return result;
}

}  // namespace vantage
