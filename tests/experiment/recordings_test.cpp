// issue 38: a robot's recordings in. The frames tests/data/make_recordings.py makes from the shared
// Kinect frame (ctest's recordings fixture writes them into the build tree), handed over as a
// TUM RGB-D folder of 16-bit depth PNGs, give the map of the same frames as PCD clouds, cell for
// cell.

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "test_scene.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/depth_image.hpp"

namespace vantage {
namespace {

std::filesystem::path recordings() { return VANTAGE_RECORDINGS; }

/// The map of a manifest's clouds, mapped as `vantage plan` maps them.
OccupancyGrid map_of(const Manifest& manifest) {
  Mapper mapper(manifest.grid, mapper_config_for(manifest));
  map_recorded(manifest, mapper);
  return mapper.grid();
}

void expect_same_map(const OccupancyGrid& expected, const OccupancyGrid& got) {
  ASSERT_EQ(got.spec().num_cells(), expected.spec().num_cells());
  const std::span<const float> a = expected.log_odds(), b = got.log_odds();
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size_bytes()), 0) << "the maps differ";
  std::size_t occupied = 0;
  for (std::size_t i = 0; i < a.size(); ++i) occupied += got.state(i) == CellState::kOccupied;
  EXPECT_GT(occupied, 1000u);  // a map of the objects, not an empty one
}

TEST(Recordings, ATumFolderMapsAsTheManifestOfItsFrames) {
  const Manifest pcd = read_manifest(recordings() / "pcd.yaml");
  const Manifest tum = read_manifest(recordings() / "tum.yaml");
  ASSERT_EQ(tum.clouds.size(), 3u);
  ASSERT_EQ(pcd.clouds.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(tum.clouds[i].file.extension(), ".png");
    EXPECT_FALSE(tum.clouds[i].pose_from_registration);
    EXPECT_EQ(tum.clouds[i].T_world_cloud.matrix(), pcd.clouds[i].T_world_cloud.matrix());
  }
  EXPECT_EQ(tum.depth, (DepthEncoding{.units_per_metre = 5000.0, .invalid = 0}));
  expect_same_map(map_of(pcd), map_of(tum));
}

TEST(Recordings, EveryNthFrame) {
  const Manifest every2 = read_manifest(recordings() / "tum.yaml", {.every = 2});
  ASSERT_EQ(every2.clouds.size(), 2u);
  EXPECT_EQ(every2.clouds[0].file.filename(), "1305031102.175304.png");
  EXPECT_EQ(every2.clouds[1].file.filename(), "1305031102.243211.png");
  EXPECT_EQ(read_manifest(recordings() / "tum.yaml", {.every = 5}).clouds.size(), 1u);
}

TEST(Recordings, ATumFolderWithoutGroundTruthIsASequenceWithoutPoses) {
  const std::filesystem::path dir = testing::fresh_dir("tum_no_truth");
  std::filesystem::copy(recordings() / "tum", dir / "tum",
                        std::filesystem::copy_options::recursive);
  std::filesystem::remove(dir / "tum/groundtruth.txt");
  std::filesystem::copy(recordings() / "tum.yaml", dir / "tum.yaml");
  const Manifest m = read_manifest(dir / "tum.yaml");
  ASSERT_EQ(m.clouds.size(), 3u);
  EXPECT_TRUE(m.clouds[0].pose_from_table);
  EXPECT_TRUE(m.clouds[1].pose_from_registration);
  EXPECT_TRUE(m.clouds[2].pose_from_registration);
}

TEST(Recordings, BadDepthImagesAreRefusedNamingTheFile) {
  const auto error_of = [](const std::filesystem::path& file) -> std::string {
    try {
      read_depth_png(file);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no error";
  };
  const std::filesystem::path bad = recordings() / "bad";
  EXPECT_EQ(error_of(bad / "eight_bit.png"),
            (bad / "eight_bit.png").string() +
                ": has 8-bit greyscale pixels, not a depth image's 16-bit greyscale");
  const std::string truncated = error_of(bad / "truncated.png");
  EXPECT_EQ(truncated.rfind((bad / "truncated.png").string() + ": a broken PNG: ", 0), 0u)
      << truncated;
  EXPECT_EQ(error_of(bad), bad.string() + ": is a directory, not a file");
}

}  // namespace
}  // namespace vantage
