// The checks of an OctoMap file (detail/octomap_check.hpp): its header and its tree's structure.

#include "vantage/io/detail/octomap_check.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>
#include <system_error>
#include <utility>

#include "vantage/io/detail/octomap_keys.hpp"
#include "vantage/io/format_parsing.hpp"

namespace vantage::detail {
namespace fs = std::filesystem;
namespace {

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

/// The bytes of a full tree's node payload by the type its header names.
std::size_t payload_of(const TreeHeader& header, const fs::path& path) {
  if (header.format != OctomapFormat::kFull) return 0;
  if (header.id == "OcTree") return sizeof(float);
  if (header.id == "ColorOcTree") return sizeof(float) + 3;
  fail(path,
       cat("tree type '", printable(header.id, 40), "' is not supported (OcTree, ColorOcTree)"));
}

// NOTE: a full tree whose nodes are of another type than its header names (a ColorOcTree's
// data under "OcTree", issue 53) is said as such, not as the walk's first complaint.
void fail_if_another_type(std::string_view data, const TreeHeader& header, std::size_t payload,
                          const fs::path& path) {
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
      fail(path, cat("the header names tree type '", printable(header.id, 40), "' (", payload,
                     " bytes a node), but its data reads whole as ", header.size, " ", other,
                     " nodes (", bytes_a_node, " bytes each): the header names the wrong type"));
    }
  }
}

}  // namespace

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

void check_tree_data(std::string_view data, const TreeHeader& header, const fs::path& path) {
  const std::size_t payload = payload_of(header, path);
  if (header.size == 0) {
    if (!data.empty()) {
      fail(path,
           cat("the header announces an empty tree but ", data.size(), " bytes of data follow"));
    }
    return;
  }
  StructureCheck check(data, payload);
  std::uint64_t nodes = 0;
  try {
    nodes = header.format == OctomapFormat::kBinary ? check.walk_binary() : check.walk_full();
  } catch (const std::runtime_error& e) {
    fail_if_another_type(data, header, payload, path);
    fail(path, e.what());
  }
  if (nodes != header.size) {
    fail_if_another_type(data, header, payload, path);
    fail(path, cat("the header announces ", header.size, " nodes but the data holds ", nodes));
  }
  if (check.consumed() != data.size()) {
    fail(path, cat(data.size() - check.consumed(), " unexpected bytes after the tree data"));
  }
}

}  // namespace vantage::detail
