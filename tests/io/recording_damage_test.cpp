// issue 53: recordings damaged as a disk or a kill damages them are found, said and never mapped
// as whole ones. The recordings are the fixture's (tests/data/make_recordings.py: a ROS 1 bag by
// Debian's python3-rosbag; tests/data/make_mcap.js: an MCAP file by npm's @mcap/core), three
// frames on /camera/depth/points, each in a chunk of its own; here they are cut at a record
// boundary, cut inside a record, given a flipped byte or a size that lies, and read as
// `vantage plan` reads them: refused with where, or with `salvage`, the whole frames before the
// damage and how many it dropped.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "temp_dir.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/io/recording_formats.hpp"

namespace vantage {
namespace {

namespace fs = std::filesystem;

fs::path recordings() { return VANTAGE_RECORDINGS; }

std::string read_bytes(const fs::path& path) { return test::read_file(path); }
void write_bytes(const fs::path& path, const std::string& bytes) { test::write_file(path, bytes); }

template <class T>
T get(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

template <class T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

// The test's own walk over each format's records (wiki.ros.org/Bags/Format/2.0, mcap.dev/spec),
// to know where to damage them.

/// A top-level record of a bag: where it begins, its op, where its data begins and its size.
struct Record {
  std::size_t at = 0, data = 0, size = 0;
  int op = 0;
};

std::vector<Record> bag_records(const std::string& b) {
  std::vector<Record> out;
  std::size_t pos = 13;  // "#ROSBAG V2.0\n"
  while (pos < b.size()) {
    const auto header = get<std::uint32_t>(b, pos);
    int op = -1;
    for (std::size_t f = pos + 4; f < pos + 4 + header;) {
      const auto len = get<std::uint32_t>(b, f);
      if (b.compare(f + 4, 3, "op=") == 0) op = static_cast<unsigned char>(b[f + 7]);
      f += 4 + len;
    }
    const std::size_t data = pos + 4 + header + 4;
    out.push_back({pos, data, get<std::uint32_t>(b, data - 4), op});
    pos = data + out.back().size;
  }
  return out;
}

std::vector<Record> mcap_records(const std::string& b) {
  std::vector<Record> out;
  std::size_t pos = 8;
  while (pos + 8 < b.size()) {
    const auto size = get<std::uint64_t>(b, pos + 1);
    out.push_back(
        {pos, pos + 9, static_cast<std::size_t>(size), static_cast<unsigned char>(b[pos])});
    pos += 9 + size;
  }
  return out;
}

/// The `n`-th record (from 0) of op `op`.
Record nth(const std::vector<Record>& records, int op, int n) {
  for (const Record& r : records) {
    if (r.op == op && n-- == 0) return r;
  }
  ADD_FAILURE() << "no record " << n << " of op " << op;
  return {};
}

/// Where the value of a bag record header's field `name` begins.
std::size_t bag_field(const std::string& b, const Record& r, const std::string& name) {
  for (std::size_t f = r.at + 4; f < r.data - 4;) {
    const auto len = get<std::uint32_t>(b, f);
    if (b.compare(f + 4, name.size() + 1, name + "=") == 0) return f + 4 + name.size() + 1;
    f += 4 + len;
  }
  ADD_FAILURE() << "no field " << name;
  return 0;
}

constexpr int kBagChunk = 5, kBagIndexData = 4, kMcapChunk = 6;

/// A damaged copy of a recording, and what reading it must say.
struct Damage {
  std::string name;
  std::string bytes;
  std::string said;                      ///< in the refusal
  std::size_t whole = 1;                 ///< frames before the damage
  std::optional<std::uint64_t> dropped;  ///< frames its index counts after them
};

/// The bag's damages: cut after the first chunk and its index data, cut inside the second chunk,
/// a flipped byte in the second chunk's index data, and a chunk that claims 4 GiB.
std::vector<Damage> bag_damages() {
  const std::string b = read_bytes(recordings() / "kinect.bag");
  const std::vector<Record> records = bag_records(b);
  const Record second = nth(records, kBagChunk, 1);
  std::vector<Damage> out;
  out.push_back(
      {"cut_at_boundary.bag", b.substr(0, second.at),
       "the file ends at byte " + std::to_string(second.at) + ", before the index at byte", 1,
       std::nullopt});
  out.push_back({"cut_inside.bag", b.substr(0, second.data + second.size / 2),
                 "the record at byte " + std::to_string(second.at) + " runs past the file's end", 1,
                 std::nullopt});
  // The high byte of the offset of the first message the second chunk's index data lists.
  std::string flipped = b;
  const Record index = nth(records, kBagIndexData, 3);  // chunk 1 has three connections
  EXPECT_GT(index.at, second.at);
  flipped[index.data + 8 + 3] ^= 0x40;
  out.push_back({"flipped.bag", flipped, "which the chunk does not hold there: damaged", 1, 2});
  std::string claims = b;
  put<std::uint32_t>(claims, bag_field(b, second, "size"), 0xffffffffu);
  out.push_back({"claims_4GiB.bag", claims,
                 "the chunk at byte " + std::to_string(second.at) +
                     " claims 4294967295 bytes uncompressed, but holds",
                 1, 2});
  return out;
}

/// The MCAP file's damages: cut after the first chunk, cut inside the second, a flipped byte in
/// the second chunk's data, and a chunk that claims 2^60 bytes.
std::vector<Damage> mcap_damages() {
  const std::string b = read_bytes(recordings() / "kinect.mcap");
  const std::vector<Record> records = mcap_records(b);
  const Record second = nth(records, kMcapChunk, 1);
  std::vector<Damage> out;
  out.push_back({"cut_at_boundary.mcap", b.substr(0, second.at),
                 "the file ends at byte " + std::to_string(second.at) +
                     " without its footer and closing magic: cut short",
                 1, std::nullopt});
  out.push_back({"cut_inside.mcap", b.substr(0, second.data + second.size / 2),
                 "the record at byte " + std::to_string(second.at) + " runs past the file's end", 1,
                 std::nullopt});
  std::string flipped = b;
  flipped[second.data + second.size / 2] ^= 0x01;  // a point's coordinate
  out.push_back({"flipped.mcap", flipped,
                 "the chunk at byte " + std::to_string(second.at) + " fails its CRC", 1, 2});
  std::string claims = b;
  put<std::uint64_t>(claims, second.data + 16, std::uint64_t{1} << 60);
  out.push_back({"claims_2e60.mcap", claims,
                 "the chunk at byte " + std::to_string(second.at) +
                     " claims 1152921504606846976 bytes uncompressed",
                 1, 2});
  return out;
}

void expect_refused_and_salvaged(const std::vector<Damage>& damages) {
  test::TempDir dir;
  for (const Damage& d : damages) {
    SCOPED_TRACE(d.name);
    const fs::path path = dir / d.name;
    write_bytes(path, d.bytes);
    const RecordingOptions options{.topic = "/camera/depth/points"};
    try {
      (void)read_recording(path, options);
      ADD_FAILURE() << d.name << " was read as a whole recording";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(d.said), std::string::npos) << what;
      EXPECT_NE(what.find("the last whole frame before it is frame 1 of /camera/depth/points "
                          "(stamp 1305031102.175304 s)"),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("--salvage maps the frames before it"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    RecordingOptions salvage = options;
    salvage.salvage = true;
    const Recording read = read_recording(path, salvage);
    EXPECT_EQ(read.frames.size(), d.whole);
    ASSERT_TRUE(read.salvage.has_value());
    EXPECT_EQ(read.salvage->frames, d.whole);
    EXPECT_EQ(read.salvage->dropped, d.dropped);
    EXPECT_NE(read.salvage->damage.find(d.said), std::string::npos) << read.salvage->damage;
    // The frame kept is the whole first frame, posed by tf as in the whole recording.
    const Recording whole = read_recording(
        recordings() / fs::path(d.name).extension().string().replace(0, 1, "kinect."), options);
    ASSERT_EQ(whole.frames.size(), 3u);
    EXPECT_FALSE(whole.salvage.has_value());
    EXPECT_EQ(read.frames.front().points.size(), whole.frames.front().points.size());
    EXPECT_EQ(read.frames.front().stamp, whole.frames.front().stamp);
    ASSERT_TRUE(read.frames.front().T_fixed_cloud.has_value());
    EXPECT_TRUE(read.frames.front().T_fixed_cloud->isApprox(*whole.frames.front().T_fixed_cloud));
  }
}

TEST(RecordingDamage, ADamagedBagIsRefusedAndItsWholeFramesSalvaged) {
  expect_refused_and_salvaged(bag_damages());
}

TEST(RecordingDamage, ADamagedMcapFileIsRefusedAndItsWholeFramesSalvaged) {
  expect_refused_and_salvaged(mcap_damages());
}

TEST(RecordingDamage, EveryCutOfTheRecordingsIsRefusedOrWhole) {
  // A cut at every record boundary and inside every record: never a frame read as whole that is
  // not, never the recording taken as whole, and every refusal one line.
  test::TempDir dir;
  for (const char* name : {"kinect.bag", "kinect.mcap"}) {
    SCOPED_TRACE(name);
    const std::string b = read_bytes(recordings() / name);
    const std::vector<Record> records =
        fs::path(name).extension() == ".bag" ? bag_records(b) : mcap_records(b);
    std::vector<std::size_t> cuts = {8, 13, b.size() - 1, b.size() - 8};
    for (const Record& r : records) {
      cuts.push_back(r.at);
      cuts.push_back(r.data + r.size / 2);
    }
    for (const std::size_t cut : cuts) {
      const fs::path path = dir / name;
      write_bytes(path, b.substr(0, cut));
      try {
        const Recording read =
            read_recording(path, {.topic = "/camera/depth/points", .salvage = true});
        ASSERT_TRUE(read.salvage.has_value()) << "cut at " << cut << " was read as whole";
        EXPECT_LE(read.frames.size(), 3u);
      } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      }
    }
  }
}

TEST(RecordingDamage, AnMcapFileOfOnlyItsMagicIsSaidToBeEmptyOrCut) {
  test::TempDir dir;
  write_bytes(dir / "magic.mcap", std::string("\x89MCAP0\r\n", 8));
  try {
    (void)read_recording(dir / "magic.mcap", {.topic = "/camera/depth/points"});
    ADD_FAILURE() << "an MCAP file of its magic alone was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the file ends at byte 8, right after its opening magic"),
              std::string::npos)
        << e.what();
  }
  write_bytes(dir / "magic.bag", "#ROSBAG V2.0\n");
  try {
    (void)read_recording(dir / "magic.bag", {.topic = "/camera/depth/points"});
    ADD_FAILURE() << "a bag of its magic alone was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the file ends at byte 13, right after its magic"),
              std::string::npos)
        << e.what();
  }
}

TEST(RecordingDamage, AFixedFrameTfDoesNotKnowIsAnError) {
  for (const char* name : {"kinect.bag", "kinect.mcap"}) {
    try {
      (void)read_recording(recordings() / name,
                           {.topic = "/camera/depth/points", .fixed_frame = "mars"});
      ADD_FAILURE() << name << ": fixed_frame mars was taken";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("fixed_frame mars is no frame of its tf (its frames: "
                                           "base_link, camera_depth_optical_frame, world)"),
                std::string::npos)
          << e.what();
    }
    // The frames it knows pose the clouds.
    const Recording world = read_recording(
        recordings() / name, {.topic = "/camera/depth/points", .fixed_frame = "world"});
    ASSERT_EQ(world.frames.size(), 3u);
    EXPECT_TRUE(world.frames.back().T_fixed_cloud.has_value());
  }
}

TEST(RecordingDamage, TheFuzzersDamagedSeedsAreSaidWhereTheWholeOnesRead) {
  // fuzz/make_seeds.py's: a bag by python3-rosbag and an MCAP file with every check the format
  // offers, whole and damaged (cut, flipped, a lying size, never closed, its magic alone).
  std::size_t damaged = 0;
  for (const char* reader : {"rosbag", "mcap"}) {
    for (const auto& entry : fs::directory_iterator(fs::path("fuzz/corpus") / reader)) {
      const std::string name = entry.path().filename().string();
      SCOPED_TRACE(name);
      const std::string bytes = read_bytes(entry.path());
      const auto read = [&] {
        std::size_t messages = 0;
        const MessageVisitor count = [&](const RecordedMessage&) { ++messages; };
        if (std::string(reader) == "rosbag") {
          read_rosbag(bytes, count);
        } else {
          read_mcap(bytes, count);
        }
        return messages;
      };
      const bool whole = name == "tiny.bag" || name == "whole.mcap" || name == "tiny.mcap" ||
                         name == "chunked.mcap" || name == "zstd.mcap" || name == "lz4.mcap";
      if (whole) {
        EXPECT_EQ(read(), 2u);
        continue;
      }
      ++damaged;
      try {
        read();
        ADD_FAILURE() << "read as whole";
      } catch (const RecordingDamage& e) {
        EXPECT_NE(std::string(e.what()).find("byte"), std::string::npos) << e.what();
      }
    }
  }
  EXPECT_GE(damaged, 12u);
}

}  // namespace
}  // namespace vantage
