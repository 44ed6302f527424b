// MCAP's compressed chunks (mcap.dev/spec): zstd and lz4, decompressed within the size a chunk
// claims and the memory available.

#include "vantage/io/detail/mcap_decompress.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

#include "vantage/io/detail/recording_records.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {
namespace {

/// Decompresses `data` with `step`, which turns some input into some output and says whether a
/// frame ended, into exactly `size` bytes. The output grows only as the decompressor fills it,
/// never past one byte beyond the claim (which shows that it lies), so that a chunk that claims
/// more than its data holds is refused before anything is allocated for the claim.
template <class Step>
std::string inflate(std::string_view data, std::uint64_t size, std::string_view name,
                    std::uint64_t at, Step step) {
  const std::uint64_t limit = size + 1;
  std::string out(static_cast<std::size_t>(std::min<std::uint64_t>(
                      limit, std::max<std::uint64_t>(std::uint64_t{1} << 16, 4 * data.size()))),
                  '\0');
  std::size_t read = 0, written = 0;
  bool ended = false;
  while (!(ended && read == data.size())) {
    if (written == out.size()) {
      if (out.size() >= limit) break;
      out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(limit, 2 * out.size())));
    }
    std::size_t in = data.size() - read, produced = out.size() - written;
    ended = step(data.data() + read, in, out.data() + written, produced);
    read += in;
    written += produced;
    if (in == 0 && produced == 0 && written < out.size()) break;  // the data is cut short
  }
  if (!ended || read != data.size() || written != size) {
    throw FormatError(
        cat("the ", name, " chunk at byte ", at, " does not decompress to its ", size, " bytes"));
  }
  out.resize(written);
  return out;
}

}  // namespace

std::string decompress_chunk(std::string_view compression, std::string_view data,
                             std::uint64_t size, std::uint64_t at) {
  if (size > kMaxRecordingFileBytes || (available_memory() > 0 && size > available_memory())) {
    throw FormatError(cat("the chunk at byte ", at, " claims ", size,
                          " bytes uncompressed, more than the memory available"));
  }
  if (compression == "zstd") {
    const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> dctx(ZSTD_createDCtx(),
                                                                    &ZSTD_freeDCtx);
    if (!dctx) throw FormatError("zstd could not start");
    return inflate(
        data, size, "zstd", at, [&](const char* src, std::size_t& in, char* dst, std::size_t& out) {
          ZSTD_inBuffer input{src, in, 0};
          ZSTD_outBuffer output{dst, out, 0};
          const std::size_t r = ZSTD_decompressStream(dctx.get(), &output, &input);
          if (ZSTD_isError(r)) {
            throw FormatError(
                cat("the zstd chunk at byte ", at, " does not decompress: ", ZSTD_getErrorName(r)));
          }
          in = input.pos;
          out = output.pos;
          return r == 0;
        });
  }
  if (compression == "lz4") {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
      throw FormatError("lz4 could not start");
    }
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(
        raw, &LZ4F_freeDecompressionContext);
    return inflate(
        data, size, "lz4", at, [&](const char* src, std::size_t& in, char* dst, std::size_t& out) {
          const std::size_t r = LZ4F_decompress(dctx.get(), dst, &out, src, &in, nullptr);
          if (LZ4F_isError(r)) {
            throw FormatError(
                cat("the lz4 chunk at byte ", at, " does not decompress: ", LZ4F_getErrorName(r)));
          }
          return r == 0;
        });
  }
  throw Unsupported(cat("the chunk at byte ", at, " is compressed with '",
                        printable(compression, 20), "' (Vantage reads zstd, lz4 and none)"));
}

}  // namespace vantage::detail
