#pragma once
/// @file
/// MCAP's compressed chunks, decompressed for mcap.cpp.

#include <cstdint>
#include <string>
#include <string_view>

namespace vantage::detail {

/// A compressed chunk's records (`data`, compressed with `compression`: zstd or lz4; the chunk
/// at byte `at`), decompressed to exactly `size` bytes. The claimed size is checked against the
/// memory available, and the output never outgrows what the data decompresses to. Throws
/// FormatError when the data does not decompress to `size` bytes, Unsupported for another
/// compression.
std::string decompress_chunk(std::string_view compression, std::string_view data,
                             std::uint64_t size, std::uint64_t at);

}  // namespace vantage::detail
