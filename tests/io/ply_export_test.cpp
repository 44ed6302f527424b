#include "vantage/io/ply_export.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace vantage {
namespace {

using test::TempDir;

struct Vertex {
  float x, y, z;
  int r, g, b;
  float p;
};

// A minimal reader for the files write_cells_ply makes: checks the header, returns the vertices.
std::vector<Vertex> read_ply(const std::filesystem::path& path, bool binary) {
  const std::string bytes = test::read_file(path);
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::string line, format;
  std::size_t count = 0;
  std::vector<std::string> properties;
  std::getline(header, line);
  EXPECT_EQ(line, "ply");
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") words >> format;
    if (word == "element") {
      words >> word >> count;
      EXPECT_EQ(word, "vertex");
    }
    if (word == "property") {
      std::string type, name;
      words >> type >> name;
      properties.push_back(type + " " + name);
    }
  }
  EXPECT_EQ(format, binary ? "binary_little_endian" : "ascii");
  EXPECT_EQ(properties,
            (std::vector<std::string>{"float x", "float y", "float z", "uchar red", "uchar green",
                                      "uchar blue", "float probability"}));
  std::vector<Vertex> vertices(count);
  const char* data = bytes.data() + end + 11;
  if (binary) {
    EXPECT_EQ(bytes.size() - (end + 11), count * 19);
    for (Vertex& v : vertices) {
      std::memcpy(&v.x, data, 4);
      std::memcpy(&v.y, data + 4, 4);
      std::memcpy(&v.z, data + 8, 4);
      v.r = static_cast<unsigned char>(data[12]);
      v.g = static_cast<unsigned char>(data[13]);
      v.b = static_cast<unsigned char>(data[14]);
      std::memcpy(&v.p, data + 15, 4);
      data += 19;
    }
  } else {
    std::istringstream body(bytes.substr(end + 11));
    for (Vertex& v : vertices) body >> v.x >> v.y >> v.z >> v.r >> v.g >> v.b >> v.p;
    EXPECT_FALSE(body.fail());
    std::string rest;
    body >> rest;
    EXPECT_TRUE(rest.empty());
  }
  return vertices;
}

OccupancyGrid sample_grid() {
  OccupancyGrid grid(GridSpec::centered({0.5, -0.2, 0.1}, 0.05, {6, 5, 4}));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (i % 3 == 0) grid.miss(i);
    if (i % 5 == 0) grid.hit(i), grid.hit(i);  // occupied, even after a miss
    if (i % 7 == 0) grid.set_probability(i, 0.55);
  }
  return grid;
}

class CellPly : public ::testing::TestWithParam<bool> {};

TEST_P(CellPly, OneColouredVertexPerSelectedCellAtItsCentre) {
  TempDir dir;
  const OccupancyGrid grid = sample_grid();
  CellPlyConfig config;
  config.binary = GetParam();
  const CellPlyExport written = write_cells_ply(dir / "cells.ply", grid, config);
  const CellCounts counts = grid.counts();
  ASSERT_GT(counts.free, 0u);
  EXPECT_EQ(written.occupied, counts.occupied);
  EXPECT_EQ(written.unobserved, counts.unobserved);
  const std::vector<Vertex> vertices = read_ply(dir / "cells.ply", config.binary);
  ASSERT_EQ(vertices.size(), counts.occupied + counts.unobserved);
  std::size_t n = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) == CellState::kFree) continue;
    const Vertex& v = vertices[n++];
    const Eigen::Vector3f c = grid.spec().center(grid.spec().unravel(i)).cast<float>();
    EXPECT_EQ(v.x, c.x());
    EXPECT_EQ(v.y, c.y());
    EXPECT_EQ(v.z, c.z());
    EXPECT_EQ(v.p, static_cast<float>(grid.probability(i)));
    const bool occupied = grid.state(i) == CellState::kOccupied;
    EXPECT_EQ(v.r, 255);
    EXPECT_EQ(v.g, occupied ? 0 : 255);
    EXPECT_EQ(v.b, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, CellPly, ::testing::Values(true, false),
                         [](const auto& param_info) {
                           return param_info.param ? "Binary" : "Ascii";
                         });

TEST(CellPlyExport, SelectsClasses) {
  TempDir dir;
  const OccupancyGrid grid = sample_grid();
  CellPlyConfig config;
  config.unobserved = false;
  const CellPlyExport written = write_cells_ply(dir / "occupied.ply", grid, config);
  EXPECT_EQ(written.unobserved, 0u);
  const std::vector<Vertex> vertices = read_ply(dir / "occupied.ply", true);
  ASSERT_EQ(vertices.size(), grid.counts().occupied);
  for (const Vertex& v : vertices) EXPECT_EQ(v.g, 0);
}

TEST(CellPlyExport, FailureLeavesNoFile) {
  TempDir dir;
  test::write_file(dir / "blocker", "a file where a folder should be");
  EXPECT_THROW(write_cells_ply(dir / "blocker" / "cells.ply", sample_grid()), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir / "blocker" / "cells.ply"));
}

}  // namespace
}  // namespace vantage
