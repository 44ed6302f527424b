#include "vantage/io/input_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "temp_dir.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

std::string problem_of(const fs::path& path, InputKind kind) {
  try {
    read_input_file(path, kind);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

// issue 39: every reader opens its file this one way; a FIFO would block, a device never end.
TEST(InputFile, OnlyRegularFilesAreRead) {
  test::TempDir dir;
  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "zero");
  fs::create_directories(dir / "folder");
  EXPECT_EQ(problem_of(dir / "fifo", InputKind::kPoses), "is a FIFO, not a regular file");
  EXPECT_EQ(problem_of(dir / "zero", InputKind::kPoses),
            "is a character device, not a regular file");
  EXPECT_EQ(problem_of(dir / "folder", InputKind::kSettings), "is a directory, not a file");
  EXPECT_EQ(problem_of(dir / "missing", InputKind::kPointCloud), "no such file");
  test::write_file(dir / "ok.txt", "0 1 0 1 0 0 0 1\n");
  EXPECT_EQ(read_input_file(dir / "ok.txt", InputKind::kPoses), "0 1 0 1 0 0 0 1\n");
  EXPECT_EQ(read_input_file(dir / "ok.txt", InputKind::kPoses, 3), "0 1");
}

// A file larger than its kind may be is refused before a byte is read (sparse: nothing on disk).
TEST(InputFile, AFileLargerThanItsKindIsRefusedUnread) {
  test::TempDir dir;
  test::write_file(dir / "poses.txt", "");
  fs::resize_file(dir / "poses.txt", kMaxPoseFileBytes + 1);
  EXPECT_EQ(input_file_problem(dir / "poses.txt", InputKind::kPoses),
            "is 67108865 bytes, more than the 64 MiB a pose file may have");
  EXPECT_EQ(input_file_problem(dir / "poses.txt", InputKind::kPointCloud), "");
}

TEST(InputFile, TheFirstBytesNameTheFormat) {
  EXPECT_EQ(sniff_format("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\n"), "a PCD point cloud");
  EXPECT_EQ(sniff_format("VERSION .7\nFIELDS x y z\n"), "a PCD point cloud");
  EXPECT_EQ(sniff_format("ply\nformat ascii 1.0\n"), "a PLY file");
  EXPECT_EQ(sniff_format("# Octomap OcTree binary file\nid OcTree\n"), "an OctoMap file");
  EXPECT_EQ(sniff_format("OFF\n4 4 6\n"), "an OFF mesh");
  EXPECT_EQ(sniff_format("# made by hand\nv 0 0 0\nf 1 2 3\n"), "OBJ text");
  EXPECT_EQ(sniff_format("solid x\nfacet normal 0 0 1\n"), "ASCII STL");
  EXPECT_EQ(sniff_format("{\"scene\": 1}"), "JSON");
  // Settings and poses name no format of their own: they are for their readers to judge.
  EXPECT_EQ(sniff_format("clouds: [{file: a.pcd}]\nresolution: 0.01\n"), "");
  EXPECT_EQ(sniff_format("0 1 0 1 0 0 0 1\n"), "");
  EXPECT_EQ(sniff_format(""), "");
}

// `--max-memory 1K` was said as "0 MiB", which reads as no limit.
TEST(InputFile, SmallSizesAreNotSaidAsZero) {
  EXPECT_EQ(describe_bytes(1024.0), "1 KiB");
  EXPECT_EQ(describe_bytes(100.0), "100 bytes");
  EXPECT_EQ(describe_bytes(3.0 * 1024 * 1024), "3 MiB");
}

// The table of limits is the one docs/robustness.md states, row for row.
TEST(InputFile, TheDocsStateEveryLimit) {
  std::ifstream in(std::string(VANTAGE_DOCS_DIR) + "/robustness.md");
  ASSERT_TRUE(in) << VANTAGE_DOCS_DIR;
  std::stringstream text;
  text << in.rdbuf();
  for (const Limit& limit : kLimits) {
    std::ostringstream row;
    row << "| " << limit.name << " | " << limit.value << " " << limit.unit << " |";
    EXPECT_NE(text.str().find(row.str()), std::string::npos)
        << "docs/robustness.md lacks the row '" << row.str() << "'";
  }
}

}  // namespace
}  // namespace vantage
