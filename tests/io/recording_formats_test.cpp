// issue 38: MCAP's compressed chunks. The fixture's MCAP file
// (tests/experiment/recordings_test.cpp) is written by @mcap/core with uncompressed chunks; here a
// chunk compressed by libzstd and by liblz4's frame format, built by hand from the specification
// (mcap.dev/spec), gives the message it holds, and a chunk whose size lies is refused.

#include "vantage/io/recording_formats.hpp"

#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include <cstdint>
#include <string>
#include <vector>

#include "vantage/io/format_parsing.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

template <class T>
std::string le(T v) {
  std::string out(sizeof(T), '\0');
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  return out;
}
std::string str(const std::string& s) {
  return le<std::uint32_t>(static_cast<std::uint32_t>(s.size())) + s;
}
std::string record(std::uint8_t op, const std::string& body) {
  return std::string(1, static_cast<char>(op)) + le<std::uint64_t>(body.size()) + body;
}

/// An MCAP file of one chunk, compressed with `compression`, that holds a schema, a channel and
/// the message "payload" on /topic. `size` is the chunk's claimed uncompressed size (its own by
/// default).
std::string mcap(const std::string& compression, std::uint64_t size = 0) {
  const std::string inner =
      record(3, le<std::uint16_t>(1) + str("std_msgs/String") + str("ros1msg") + str("")) +
      record(4, le<std::uint16_t>(1) + le<std::uint16_t>(1) + str("/topic") + str("ros1") +
                    le<std::uint32_t>(0)) +
      record(5, le<std::uint16_t>(1) + le<std::uint32_t>(0) + le<std::uint64_t>(2'500'000'000) +
                    le<std::uint64_t>(0) + "payload");
  std::string packed = inner;
  if (compression == "zstd") {
    packed.resize(ZSTD_compressBound(inner.size()));
    packed.resize(ZSTD_compress(packed.data(), packed.size(), inner.data(), inner.size(), 3));
  } else if (compression == "lz4") {
    packed.resize(LZ4F_compressFrameBound(inner.size(), nullptr));
    packed.resize(
        LZ4F_compressFrame(packed.data(), packed.size(), inner.data(), inner.size(), nullptr));
  }
  const std::string chunk = le<std::uint64_t>(0) + le<std::uint64_t>(0) +
                            le<std::uint64_t>(size > 0 ? size : inner.size()) +
                            le<std::uint32_t>(0) + str(compression) +
                            le<std::uint64_t>(packed.size()) + packed;
  const std::string magic("\x89MCAP0\r\n", 8);
  return magic + record(1, str("ros1") + str("test")) + record(6, chunk) +
         record(2, le<std::uint64_t>(0) + le<std::uint64_t>(0) + le<std::uint32_t>(0)) + magic;
}

TEST(Mcap, CompressedChunksGiveTheirMessages) {
  for (const std::string compression : {"", "zstd", "lz4"}) {
    std::vector<std::string> got;
    read_mcap(mcap(compression), [&](const RecordedMessage& m) {
      EXPECT_EQ(m.topic, "/topic");
      EXPECT_EQ(m.type, "std_msgs/String");
      EXPECT_EQ(m.encoding, RosEncoding::kRos1);
      EXPECT_EQ(m.log_time, 2.5);
      got.emplace_back(m.data);
    });
    EXPECT_EQ(got, std::vector<std::string>{"payload"}) << "compression '" << compression << "'";
  }
}

TEST(Mcap, AChunkThatDoesNotDecompressToItsSizeIsRefused) {
  // Less than the chunk holds, more, and 4 GB: a claim that the machine's memory would hold but
  // the data cannot back is refused. That it is refused without allocating the claim is the
  // fuzzer's to check (its one-allocation limit of 1 GB on fuzz/corpus/mcap/*-lying-size.mcap,
  // which the reader before 2026-11-29 failed with malloc(4177461443)); here, only the message.
  for (const std::string compression : {"zstd", "lz4"}) {
    for (const std::uint64_t size : {10ULL, 4096ULL, 4'177'461'442ULL}) {
      try {
        read_mcap(mcap(compression, size), [](const RecordedMessage&) {});
        ADD_FAILURE() << compression << ": a chunk of the wrong size was read";
      } catch (const FormatError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      cat("chunk at byte 33 does not decompress to its ", size, " bytes")),
                  std::string::npos)
            << e.what();
      }
    }
  }
  EXPECT_THROW(read_mcap(mcap("bz2"), [](const RecordedMessage&) {}), FormatError);
}

}  // namespace
}  // namespace vantage
