#include "vantage/io/octomap_io.hpp"

#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "temp_dir.hpp"
#include "vantage/io/map_files.hpp"

namespace vantage {
namespace {

using test::TempDir;

// A grid with every kind of cell: unknown (p = 0.5), unobserved with p != 0.5, free and occupied
// at assorted values, and one 8 x 8 x 8 block of equal free cells that OctoMap can prune (aligned
// to OctoMap's keys when the grid is).
OccupancyGrid mixed_grid(const GridSpec& spec, unsigned seed) {
  OccupancyGrid grid(spec);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> kind(0, 3);
  const auto lo = static_cast<float>(logit(grid.params().p_min));
  const auto hi = static_cast<float>(logit(grid.params().p_max));
  const auto free_max = static_cast<float>(logit(0.4));
  const auto occupied_min = static_cast<float>(logit(0.6));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    switch (kind(rng)) {
      case 0:
        break;  // unknown
      case 1:
        grid.set_log_odds(i, std::uniform_real_distribution<float>(lo, free_max)(rng));
        break;
      case 2:
        grid.set_log_odds(i, std::uniform_real_distribution<float>(occupied_min, hi)(rng));
        break;
      default:
        grid.set_log_odds(
            i, std::uniform_real_distribution<float>(0.9f * free_max, 0.9f * occupied_min)(rng));
    }
  }
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) grid.set_log_odds(spec.linear({x, y, z}), lo);
  return grid;
}

GridSpec aligned_spec() {
  GridSpec spec;
  spec.origin = {0.0, -0.16, 0.32};  // whole multiples of 0.02: cells are OctoMap voxels
  spec.resolution = 0.02;
  spec.dims = {24, 20, 16};
  return spec;
}

GridSpec centered_spec() {
  // Odd dims centred on 0: every cell centre lies on an OctoMap voxel face.
  return GridSpec::centered({0.0, 0.0, 0.3}, 0.02, {25, 21, 17});
}

class OctomapRoundTrip : public ::testing::TestWithParam<bool> {
 protected:
  GridSpec spec() const { return GetParam() ? aligned_spec() : centered_spec(); }
};

TEST(OctomapAligned, DependsOnOriginOnly) {
  EXPECT_TRUE(octomap_aligned(aligned_spec()));
  EXPECT_FALSE(octomap_aligned(centered_spec()));
  EXPECT_TRUE(octomap_aligned(GridSpec::centered({0, 0, 0}, 0.02, {24, 20, 16})));
}

TEST_P(OctomapRoundTrip, BinaryKeepsEveryClass) {
  TempDir dir;
  const OccupancyGrid grid = mixed_grid(spec(), 1);
  const OctomapExport written = write_octomap(dir / "map.bt", grid);
  EXPECT_EQ(written.format, OctomapFormat::kBinary);
  EXPECT_EQ(written.unobserved_cells, 0u);
  const CellCounts counts = grid.counts();
  EXPECT_EQ(written.free_cells, counts.free);
  EXPECT_EQ(written.occupied_cells, counts.occupied);

  OctomapImportConfig config;
  config.grid = spec();
  const OctomapImport read = read_octomap(dir / "map.bt", config);
  EXPECT_EQ(read.format, OctomapFormat::kBinary);
  EXPECT_EQ(read.known_voxels, counts.free + counts.occupied);
  ASSERT_EQ(read.grid.spec(), spec());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(read.grid.state(i), grid.state(i)) << "cell " << i;
    switch (grid.state(i)) {
      case CellState::kUnobserved:  // .bt cannot carry the band: back to unknown
        ASSERT_EQ(read.grid.log_odds(i), 0.0f) << "cell " << i;
        break;
      case CellState::kFree:
        ASSERT_NEAR(read.grid.probability(i), grid.params().p_min, 1e-6) << "cell " << i;
        break;
      case CellState::kOccupied:
        ASSERT_NEAR(read.grid.probability(i), grid.params().p_max, 1e-6) << "cell " << i;
        break;
    }
  }
}

TEST_P(OctomapRoundTrip, FullKeepsEveryLogOddsBitForBit) {
  TempDir dir;
  const OccupancyGrid grid = mixed_grid(spec(), 2);
  const OctomapExport written = write_octomap(dir / "map.ot", grid);
  EXPECT_GT(written.unobserved_cells, 0u);
  OctomapImportConfig config;
  config.grid = spec();
  const OctomapImport read = read_octomap(dir / "map.ot", config);
  EXPECT_EQ(read.format, OctomapFormat::kFull);
  EXPECT_EQ(read.tree_type, "OcTree");
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(read.grid.log_odds(i)),
              std::bit_cast<std::uint32_t>(grid.log_odds(i)))
        << "cell " << i;
    ASSERT_EQ(read.grid.state(i), grid.state(i)) << "cell " << i;
  }
}

// Uniform regions become a few coarse leaves in both formats, and still round trip.
TEST_P(OctomapRoundTrip, UniformRegionsArePruned) {
  TempDir dir;
  OccupancyGrid grid(spec());
  for (std::size_t i = 0; i < grid.size(); ++i) grid.miss(i);
  OctomapImportConfig config;
  config.grid = spec();
  for (const char* name : {"free.bt", "free.ot"}) {
    const OctomapExport written = write_octomap(dir / name, grid);
    EXPECT_EQ(written.free_cells, grid.size());
    EXPECT_LT(written.tree_nodes * 4, grid.size()) << name;
    const OctomapImport read = read_octomap(dir / name, config);
    EXPECT_EQ(read.grid.counts().free, grid.size()) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Grids, OctomapRoundTrip, ::testing::Values(true, false),
                         [](const auto& param_info) {
                           return param_info.param ? "Aligned" : "Centered";
                         });

// OctoMap's own reader sees each cell of an aligned grid in the voxel that coincides with it,
// and each cell of a centred grid in the voxel that holds its centre, ties going up.
TEST(OctomapExport, OctoMapReadsTheCellsWhereTheDocsSay) {
  for (const GridSpec& spec : {aligned_spec(), centered_spec()}) {
    TempDir dir;
    const OccupancyGrid grid = mixed_grid(spec, 3);
    write_octomap(dir / "map.bt", grid);
    write_octomap(dir / "map.ot", grid);
    octomap::OcTree binary(0.1);
    ASSERT_TRUE(binary.readBinary((dir / "map.bt").string()));
    EXPECT_DOUBLE_EQ(binary.getResolution(), spec.resolution);
    std::unique_ptr<octomap::AbstractOcTree> abstract(
        octomap::AbstractOcTree::read((dir / "map.ot").string()));
    auto* full = dynamic_cast<octomap::OcTree*>(abstract.get());
    ASSERT_NE(full, nullptr);
    const double tie_shift = octomap_aligned(spec) ? 0.0 : 0.25 * spec.resolution;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const Eigen::Vector3d c = spec.center(spec.unravel(i)).array() + tie_shift;
      const octomap::point3d p(static_cast<float>(c.x()), static_cast<float>(c.y()),
                               static_cast<float>(c.z()));
      const octomap::OcTreeNode* b = binary.search(p);
      const octomap::OcTreeNode* f = full->search(p);
      switch (grid.state(i)) {
        case CellState::kUnobserved:
          ASSERT_EQ(b, nullptr) << "cell " << i;
          if (grid.log_odds(i) == 0.0f) {
            ASSERT_EQ(f, nullptr) << "cell " << i;
          } else {
            ASSERT_NE(f, nullptr) << "cell " << i;
            ASSERT_EQ(f->getLogOdds(), grid.log_odds(i)) << "cell " << i;
          }
          break;
        case CellState::kFree:
        case CellState::kOccupied:
          ASSERT_NE(b, nullptr) << "cell " << i;
          ASSERT_EQ(binary.isNodeOccupied(b), grid.state(i) == CellState::kOccupied) << i;
          ASSERT_NE(f, nullptr) << "cell " << i;
          ASSERT_EQ(f->getLogOdds(), grid.log_odds(i)) << "cell " << i;
          break;
      }
    }
  }
}

// A tree OctoMap built itself, with a big pruned region, imports voxel for voxel; the derived
// grid is the smallest box of voxels that holds the known ones.
TEST(OctomapImport, ReadsTreesOctoMapWroteWithCoarseLeaves) {
  TempDir dir;
  const double res = 0.05;
  octomap::OcTree tree(res);
  // A 16^3 block of free voxels at keys [32768 - 16, 32768): one pruned leaf four levels up.
  for (int z = -16; z < 0; ++z)
    for (int y = -16; y < 0; ++y)
      for (int x = -16; x < 0; ++x) {
        tree.updateNode(octomap::OcTreeKey(static_cast<octomap::key_type>(32768 + x),
                                           static_cast<octomap::key_type>(32768 + y),
                                           static_cast<octomap::key_type>(32768 + z)),
                        false);
      }
  tree.updateNode(octomap::point3d(0.12f, 0.31f, 0.07f), true);  // occupied, voxel (2, 6, 1)
  tree.updateNode(octomap::point3d(0.12f, 0.31f, 0.07f), true);
  tree.prune();
  ASSERT_LT(tree.getNumLeafNodes(), 100u);
  // NOTE: .ot first: writeBinary turns the tree to maximum likelihood.
  ASSERT_TRUE(tree.write((dir / "octomap.ot").string()));
  ASSERT_TRUE(tree.writeBinary((dir / "octomap.bt").string()));

  for (const char* name : {"octomap.bt", "octomap.ot"}) {
    const OctomapImport read = read_octomap(dir / name);
    const GridSpec& spec = read.grid.spec();
    EXPECT_EQ(spec.dims, Index3(19, 23, 18)) << name;  // voxels -16 .. 2, -16 .. 6, -16 .. 1
    EXPECT_TRUE(spec.origin.isApprox(Eigen::Vector3d(-16, -16, -16) * res)) << name;
    EXPECT_EQ(read.known_voxels, 16u * 16u * 16u + 1u) << name;
    const CellCounts counts = read.grid.counts();
    EXPECT_EQ(counts.free, 16u * 16u * 16u) << name;
    EXPECT_EQ(counts.occupied, 1u) << name;
    EXPECT_EQ(read.grid.state(spec.linear({18, 22, 17})), CellState::kOccupied) << name;
    EXPECT_EQ(read.grid.state(spec.linear({0, 0, 0})), CellState::kFree) << name;
    EXPECT_EQ(read.grid.state(spec.linear({15, 15, 15})), CellState::kFree) << name;
    EXPECT_EQ(read.grid.state(spec.linear({16, 0, 0})), CellState::kUnobserved) << name;
  }
  const OctomapImport full = read_octomap(dir / "octomap.ot");
  const std::size_t hit = full.grid.spec().linear({18, 22, 17});
  EXPECT_FLOAT_EQ(full.grid.log_odds(hit), 2.0f * static_cast<float>(logit(0.7)));

  OctomapImportConfig padded;
  padded.padding = 2;
  const OctomapImport wider = read_octomap(dir / "octomap.bt", padded);
  EXPECT_EQ(wider.grid.spec().dims, Index3(23, 27, 22));
  EXPECT_EQ(wider.grid.counts().free, 16u * 16u * 16u);
}

TEST(OctomapImport, ReadsColorOcTrees) {
  TempDir dir;
  octomap::ColorOcTree tree(0.1);
  tree.updateNode(octomap::point3d(0.05f, 0.05f, 0.05f), true)->setColor(10, 20, 30);
  tree.updateNode(octomap::point3d(0.35f, 0.05f, 0.05f), false);
  tree.updateInnerOccupancy();
  ASSERT_TRUE(tree.write((dir / "color.ot").string()));
  const OctomapImport read = read_octomap(dir / "color.ot");
  EXPECT_EQ(read.tree_type, "ColorOcTree");
  EXPECT_EQ(read.grid.spec().dims, Index3(4, 1, 1));
  EXPECT_EQ(read.grid.state(0), CellState::kOccupied);
  EXPECT_EQ(read.grid.state(1), CellState::kUnobserved);
  EXPECT_EQ(read.grid.state(3), CellState::kFree);
}

// issue 53: a color tree's data under another tree type's name was said as "the header announces
// 17 nodes but the data holds 1"; it is said as the wrong type it is.
TEST(OctomapImport, AColorTreeUnderAnotherNameIsSaidAsTheWrongType) {
  TempDir dir;
  octomap::ColorOcTree tree(0.1);
  for (int i = 0; i < 4; ++i) {
    tree.updateNode(octomap::point3d(0.05f + 0.1f * static_cast<float>(i), 0.05f, 0.05f),
                    i % 2 == 0)
        ->setColor(10, 20, 30);
  }
  tree.updateInnerOccupancy();
  ASSERT_TRUE(tree.write((dir / "color.ot").string()));
  std::string bytes = test::read_file(dir / "color.ot");
  const std::size_t id = bytes.find("id ColorOcTree\n");
  ASSERT_NE(id, std::string::npos);
  bytes.replace(id, 15, "id OcTree\n");
  test::write_file(dir / "renamed.ot", bytes);
  try {
    (void)read_octomap(dir / "renamed.ot");
    ADD_FAILURE() << "a color tree named OcTree was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the header names tree type 'OcTree' (4 bytes a node), "
                                         "but its data reads whole as "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(" ColorOcTree nodes (7 bytes each): the header names the "
                                         "wrong type"),
              std::string::npos)
        << e.what();
  }
}

TEST(OctomapImport, CropsOnlyWhenAsked) {
  TempDir dir;
  const GridSpec spec = aligned_spec();
  const OccupancyGrid grid = mixed_grid(spec, 4);
  write_octomap(dir / "map.bt", grid);
  GridSpec smaller = spec;
  smaller.dims = {24, 20, 8};  // the upper half in z is gone
  OctomapImportConfig config;
  config.grid = smaller;
  EXPECT_THROW(read_octomap(dir / "map.bt", config), std::runtime_error);
  config.crop = true;
  const OctomapImport read = read_octomap(dir / "map.bt", config);
  std::uint64_t known_below = 0, known_above = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) == CellState::kUnobserved) continue;
    (spec.unravel(i).z() < 8 ? known_below : known_above) += 1;
  }
  EXPECT_EQ(read.known_voxels, known_below);
  EXPECT_EQ(read.cropped_voxels, known_above);
  for (std::size_t i = 0; i < read.grid.size(); ++i) {
    ASSERT_EQ(read.grid.state(i), grid.state(spec.linear(smaller.unravel(i))));
  }
}

// The fuzzer's 102-byte tree whose two voxels lie far apart derives a grid of hundreds of millions
// of cells: check_grid sees it before anything is allocated and may refuse it.
TEST(OctomapImport, ChecksADerivedGridBeforeAllocatingIt) {
  const char* source = std::getenv("VANTAGE_SOURCE_DIR");
  const std::filesystem::path tree = std::filesystem::path(source != nullptr ? source : ".") /
                                     "fuzz/corpus/octomap/open-far-voxels.bt";
  ASSERT_TRUE(std::filesystem::exists(tree)) << tree;
  OctomapImportConfig config;
  std::size_t cells = 0;
  config.check_grid = [&](const GridSpec& spec) {
    cells = spec.num_cells();
    throw std::runtime_error("refused");
  };
  EXPECT_THROW(read_octomap(tree, config), std::runtime_error);
  EXPECT_GT(cells, std::size_t{1} << 24);  // what it would have allocated, at 4 B a cell

  // A small tree passes through the same check to the grid it derives.
  TempDir dir;
  write_octomap(dir / "map.bt", mixed_grid(aligned_spec(), 4));
  config.check_grid = [&](const GridSpec& spec) { cells = spec.num_cells(); };
  const OctomapImport read = read_octomap(dir / "map.bt", config);
  EXPECT_EQ(cells, read.grid.size());
}

// One line that names the file, and a std::runtime_error, for every kind of bad file.
void expect_error(const std::filesystem::path& path, const OctomapImportConfig& config,
                  const std::string& fragment) {
  try {
    read_octomap(path, config);
    ADD_FAILURE() << "no error for " << path << " (expected '" << fragment << "')";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(OctomapImport, BadFilesGiveOneLineNamingTheFile) {
  TempDir dir;
  const GridSpec spec = aligned_spec();
  write_octomap(dir / "map.bt", mixed_grid(spec, 5));
  write_octomap(dir / "map.ot", mixed_grid(spec, 5));
  const std::string bt = test::read_file(dir / "map.bt");
  const std::string ot = test::read_file(dir / "map.ot");
  OctomapImportConfig config;
  config.grid = spec;

  expect_error(dir / "missing.bt", config, "no such file");
  test::write_file(dir / "map.txt", bt);
  expect_error(dir / "map.txt", config, ".bt or .ot");
  test::write_file(dir / "swapped.bt", ot);
  expect_error(dir / "swapped.bt", config, "is an OctoMap .ot file but is named .bt");
  test::write_file(dir / "text.bt", "ply\nformat ascii 1.0\n");
  expect_error(dir / "text.bt", config, "not an OctoMap file");
  test::write_file(dir / "truncated.bt", bt.substr(0, bt.size() - 7));
  expect_error(dir / "truncated.bt", config, "truncated");
  test::write_file(dir / "truncated.ot", ot.substr(0, ot.size() - 3));
  expect_error(dir / "truncated.ot", config, "truncated");
  test::write_file(dir / "headless.ot", ot.substr(0, ot.find("data")));
  expect_error(dir / "headless.ot", config, "no 'data' line");
  test::write_file(dir / "trailing.ot", ot + "xyz");
  expect_error(dir / "trailing.ot", config, "unexpected bytes");
  std::string wrong_size = bt;
  wrong_size.replace(wrong_size.find("size "), 5, "size 1");
  test::write_file(dir / "size.bt", wrong_size);
  expect_error(dir / "size.bt", config, "nodes but the data holds");
  std::string counting = ot;
  counting.replace(counting.find("id OcTree"), 9, "id CountingOcTree");
  test::write_file(dir / "counting.ot", counting);
  expect_error(dir / "counting.ot", config, "not supported");

  OctomapImportConfig coarse = config;
  coarse.grid->resolution = 0.04;
  expect_error(dir / "map.bt", coarse, "does not match the grid's resolution");
  OctomapImportConfig shifted = config;
  shifted.grid->origin.x() += 1.0;
  expect_error(dir / "map.ot", shifted, "outside the grid");

  std::string nan = ot;
  const float bad = std::nanf("");
  nan.replace(nan.find("data\n") + 5, sizeof bad, reinterpret_cast<const char*>(&bad), sizeof bad);
  test::write_file(dir / "nan.ot", nan);
  expect_error(dir / "nan.ot", config, "non-finite");
}

// Corrupt bytes anywhere in the tree data never crash or hang the reader: either the file still
// parses as some tree, or one clear error comes out.
TEST(OctomapImport, SurvivesCorruptData) {
  TempDir dir;
  const GridSpec spec = aligned_spec();
  write_octomap(dir / "map.bt", mixed_grid(spec, 6));
  write_octomap(dir / "map.ot", mixed_grid(spec, 6));
  std::mt19937 rng(7);
  OctomapImportConfig config;
  config.grid = spec;
  config.crop = true;
  for (const char* name : {"map.bt", "map.ot"}) {
    const std::string original = test::read_file(dir / name);
    const std::size_t data = original.find("data\n") + 5;
    int errors = 0;
    for (int trial = 0; trial < 60; ++trial) {
      std::string bytes = original;
      for (int k = 0; k < 3; ++k) {
        const std::size_t at = data + rng() % (bytes.size() - data);
        bytes[at] = static_cast<char>(rng() & 0xff);
      }
      const auto path = dir / (std::string("corrupt") + (name + 3));
      test::write_file(path, bytes);
      try {
        read_octomap(path, config);
      } catch (const std::runtime_error& e) {
        ++errors;
        ASSERT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
      }
    }
    EXPECT_GT(errors, 0) << name;
  }
}

TEST(OctomapExport, RejectsOtherExtensionsAndFarGrids) {
  TempDir dir;
  const OccupancyGrid grid(aligned_spec());
  EXPECT_THROW(write_octomap(dir / "map.ply", grid), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "map.ply"));
  GridSpec far = aligned_spec();
  far.origin.x() = 1000.0;  // 50000 voxels of 2 cm from the origin: beyond OctoMap's keys
  EXPECT_THROW(write_octomap(dir / "far.bt", OccupancyGrid(far)), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "far.bt"));
}

TEST(OctomapExport, EmptyGridRoundTrips) {
  TempDir dir;
  const OccupancyGrid grid(aligned_spec());
  OctomapImportConfig config;
  config.grid = aligned_spec();
  for (const char* name : {"empty.bt", "empty.ot"}) {
    const OctomapExport written = write_octomap(dir / name, grid);
    EXPECT_EQ(written.tree_nodes, 0u);
    const OctomapImport read = read_octomap(dir / name, config);
    EXPECT_EQ(read.grid.counts().unobserved, grid.size());
    EXPECT_THROW(read_octomap(dir / name), std::runtime_error);  // nothing to derive a grid from
  }
}

// The results folder's map files: map.ot continues bit for bit, map.bt keeps the classes, and the
// top view counts each column's cells as a brute-force count over the grid does.
TEST(MapFiles, WritesTheLosslessMapTheViewerMapAndTheTopView) {
  TempDir dir;
  const GridSpec spec = centered_spec();
  const OccupancyGrid grid = mixed_grid(spec, 5);
  write_map_files(dir.path(), grid);

  OctomapImportConfig import;
  import.grid = spec;
  const OctomapImport ot = read_octomap(dir / "map.ot", import);
  const OctomapImport bt = read_octomap(dir / "map.bt", import);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(ot.grid.log_odds(i)),
              std::bit_cast<std::uint32_t>(grid.log_odds(i)))
        << "cell " << i;
    if (grid.state(i) != CellState::kUnobserved) {
      ASSERT_EQ(bt.grid.state(i), grid.state(i)) << "cell " << i;
    }
  }

  // Brute force: per column (x, y), the cells of each class and the highest occupied z.
  struct Column {
    int occupied = 0, unobserved = 0, top = -1;
  };
  std::map<std::pair<int, int>, Column> expected;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Index3 c = spec.unravel(i);
    if (grid.state(i) == CellState::kFree) continue;
    Column& column = expected[{c.x(), c.y()}];
    if (grid.state(i) == CellState::kOccupied) {
      ++column.occupied;
      column.top = std::max(column.top, c.z());
    } else {
      ++column.unobserved;
    }
  }
  std::istringstream csv(test::read_file(dir / "map_top.csv"));
  std::string line;
  std::getline(csv, line);
  {  // The grid, every number read back exactly.
    std::istringstream header(line);
    std::string hash, grid_word, origin_word, resolution_word, dims_word;
    Eigen::Vector3d origin;
    double resolution;
    Index3 dims;
    ASSERT_TRUE(header >> hash >> grid_word >> origin_word >> origin.x() >> origin.y() >>
                origin.z() >> resolution_word >> resolution >> dims_word >> dims.x() >> dims.y() >>
                dims.z())
        << line;
    EXPECT_EQ(origin, spec.origin);
    EXPECT_EQ(resolution, spec.resolution);
    EXPECT_EQ(dims, spec.dims);
  }
  std::getline(csv, line);
  EXPECT_EQ(line, "x,y,occupied,unobserved,top");
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    double x, y;
    int occupied, unobserved;
    char comma;
    std::istringstream row(line);
    ASSERT_TRUE(row >> x >> comma >> y >> comma >> occupied >> comma >> unobserved >> comma)
        << line;
    const Index3 cell = spec.index_of({x, y, spec.origin.z()});
    const auto it = expected.find({cell.x(), cell.y()});
    ASSERT_NE(it, expected.end()) << "a column without occupied or unobserved cells: " << line;
    EXPECT_EQ(occupied, it->second.occupied) << line;
    EXPECT_EQ(unobserved, it->second.unobserved) << line;
    double top = -1.0;
    if (it->second.top >= 0) {
      ASSERT_TRUE(row >> top) << line;
      EXPECT_DOUBLE_EQ(top, spec.center({cell.x(), cell.y(), it->second.top}).z()) << line;
    } else {
      EXPECT_FALSE(row >> top) << "a top height without occupied cells: " << line;
    }
  }
  EXPECT_EQ(rows, expected.size());
}

}  // namespace
}  // namespace vantage
