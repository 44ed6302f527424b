#pragma once
/// @file
/// The checks of an OctoMap file before OctoMap's reader is given it: its text header, parsed as
/// OctoMap parses it, and its tree's structure, walked without building the tree, so that a
/// truncated or corrupt file is said as such. Included by octomap_io.cpp only.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/io/octomap_io.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

[[noreturn]] inline void fail(const std::filesystem::path& path, const std::string& message) {
  throw std::runtime_error(cat(path.string(), ": ", message));
}

/// What an OctoMap file's header says.
struct TreeHeader {
  OctomapFormat format = OctomapFormat::kBinary;
  std::string id;
  std::uint64_t size = 0;
  double resolution = 0.0;
  std::size_t data_offset = 0;
};

/// Parses the text header the way OctoMap's AbstractOcTree::readHeader does (keywords id, size,
/// res, comment lines, then "data"), but reports what is wrong instead of printing to stderr.
TreeHeader parse_header(const std::string& bytes, const std::filesystem::path& path);

/// Walks the tree data that follows `header` (`data`) and fails naming `path` unless it holds
/// exactly the nodes the header announces, of a type it supports; a full tree whose data reads
/// whole as another type than its header names is said to be so.
void check_tree_data(std::string_view data, const TreeHeader& header,
                     const std::filesystem::path& path);

}  // namespace vantage::detail
