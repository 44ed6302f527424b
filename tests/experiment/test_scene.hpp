#pragma once
// The small test scene and helpers shared by the experiment tests.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "vantage/sim/scene.hpp"

namespace vantage::testing {

inline std::filesystem::path source_dir() {
  const char* dir = std::getenv("VANTAGE_SOURCE_DIR");
  return dir != nullptr ? dir : ".";
}

inline std::string small_scene_path() {
  return (source_dir() / "tests/experiment/small_tabletop.yaml").string();
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

/// CSV rows split into fields.
inline std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(line.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    rows.push_back(fields);
  }
  return rows;
}

/// The CSV with its wall-clock columns (plan_seconds, the 12th, and the stage times from the
/// 21st on) emptied.
inline std::string without_timing(const std::string& csv) {
  std::string out;
  for (std::vector<std::string> fields : parse_csv(csv)) {
    if (fields.size() > 11) fields[11].clear();
    for (std::size_t k = 20; k < fields.size(); ++k) fields[k].clear();
    for (std::size_t k = 0; k < fields.size(); ++k) out += (k > 0 ? "," : "") + fields[k];
    out += "\n";
  }
  return out;
}

/// A fresh, empty temporary folder of its own for the running test: named by `name`, the test and
/// the process, since ctest runs the cases of one fixture as processes at once (-j), and other
/// sessions run the suite beside this one.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string owner = test != nullptr ? std::string(test->name()) : std::string("setup");
  std::replace(owner.begin(), owner.end(), '/', '_');  // a parameterised test's index
  const auto dir = std::filesystem::temp_directory_path() /
                   ("vantage-test-" + name + "-" + owner + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace vantage::testing
