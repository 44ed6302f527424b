// Result files and folders appear whole or not at all.

#include "vantage/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "temp_dir.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

TEST(WriteAtomically, AFailedWriteLeavesTheOldFile) {
  const test::TempDir tmp;
  const fs::path file = tmp / "scans.csv";
  write_atomically(file, "old\n");
  EXPECT_THROW(write_atomically(file,
                                [](std::ostream& out) {
                                  out << "half";
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(test::read_file(file), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1);
}

TEST(WriteFolderAtomically, TheFolderAppearsWhole) {
  const test::TempDir tmp;
  const fs::path dir = tmp / "run";
  fs::create_directories(dir);  // an empty folder is replaced
  write_folder_atomically(dir, [](const fs::path& partial) {
    EXPECT_FALSE(fs::exists(partial.parent_path() / "run" / "a.txt"));
    write_atomically(partial / "a.txt", "a");
    write_atomically(partial / "b.txt", "b");
  });
  EXPECT_EQ(test::read_file(dir / "a.txt"), "a");
  EXPECT_EQ(test::read_file(dir / "b.txt"), "b");
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1);
}

TEST(WriteFolderAtomically, AFailureLeavesNothingBehind) {
  const test::TempDir tmp;
  const fs::path dir = tmp / "run";
  EXPECT_THROW(write_folder_atomically(dir,
                                       [](const fs::path& partial) {
                                         write_atomically(partial / "a.txt", "a");
                                         throw std::runtime_error("plot failed");
                                       }),
               std::runtime_error);
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

TEST(WriteFolderAtomically, NeverReplacesAFolderWithFiles) {
  const test::TempDir tmp;
  const fs::path dir = tmp / "run";
  write_atomically(dir / "keep.txt", "mine");
  EXPECT_ANY_THROW(write_folder_atomically(
      dir, [](const fs::path& partial) { write_atomically(partial / "a.txt", "a"); }));
  EXPECT_EQ(test::read_file(dir / "keep.txt"), "mine");
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1);
}

// Issue 15: messages name the folder being written, never its `*.partial-PID` sibling, and a
// filesystem error is said as "<path>: <reason>", not as the C++ library's text.
TEST(WriteFolderAtomically, FailureNamesTheFolderNotItsTemporary) {
  const test::TempDir tmp;
  const fs::path dir = tmp / "run";
  try {
    write_folder_atomically(dir, [](const fs::path& partial) {
      // A file where a folder should be: writing below it fails with a filesystem error.
      write_atomically(partial / "map", "x");
      fs::create_directories(partial / "map" / "sub");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find("partial"), std::string::npos) << message;
    EXPECT_EQ(message.find("filesystem error"), std::string::npos) << message;
    EXPECT_NE(message.find((dir / "map" / "sub").string()), std::string::npos) << message;
  }
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

}  // namespace
}  // namespace vantage
