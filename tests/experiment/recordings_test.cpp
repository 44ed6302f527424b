// issue 38: a robot's recordings in. The frames tests/data/make_recordings.py makes from the shared
// Kinect frame (ctest's recordings fixture writes them into the build tree), handed over as a
// TUM RGB-D folder of 16-bit depth PNGs, a ROS 1 bag (Debian's python3-rosbag) and an MCAP file
// (npm's @mcap/core, tests/data/make_mcap.js), give the map of the same frames as PCD clouds
// posed by a trajectory, cell for cell.

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "test_scene.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/depth_image.hpp"
#include "vantage/io/recording.hpp"

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

// A recording's frames come with their poses from tf (world -> base_link at each stamp, and the
// static base_link -> camera_depth_optical_frame), the same as the trajectory gives the PCDs.
void expect_recording_maps_as_pcds(const std::string& manifest) {
  const Manifest pcd = read_manifest(recordings() / "pcd.yaml");
  const Manifest recorded = read_manifest(recordings() / manifest);
  ASSERT_EQ(recorded.clouds.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(recorded.clouds[i].points);
    EXPECT_FALSE(recorded.clouds[i].pose_from_registration);
    EXPECT_EQ(recorded.clouds[i].T_world_cloud.matrix(), pcd.clouds[i].T_world_cloud.matrix());
    EXPECT_EQ(*recorded.clouds[i].stamp, *pcd.clouds[i].stamp);
  }
  expect_same_map(map_of(pcd), map_of(recorded));
}

TEST(Recordings, ARos1BagMapsAsTheManifestOfItsFrames) {
  expect_recording_maps_as_pcds("bag.yaml");
}

TEST(Recordings, AnMcapFileMapsAsTheManifestOfItsFrames) {
  expect_recording_maps_as_pcds("mcap.yaml");
}

// An image topic (sensor_msgs/Image 16UC1 with CameraInfo): each pixel one ray, as the PNGs.
TEST(Recordings, ABagsDepthImagesMapAsTheManifestOfItsFrames) {
  expect_recording_maps_as_pcds("bag_image.yaml");
}

TEST(Recordings, AnMcapFilesDepthImagesMapAsTheManifestOfItsFrames) {
  expect_recording_maps_as_pcds("mcap_image.yaml");
}

TEST(Recordings, DepthImagesWithoutCameraInfoAreRefused) {
  for (const char* file : {"kinect.bag", "kinect.mcap"}) {
    try {
      read_recording(recordings() / file, {.topic = "/camera/depth/image_raw",
                                           .camera_info = "/camera/rgb/camera_info"});
      ADD_FAILURE() << "images without camera info were read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(
                    "no sensor_msgs/CameraInfo on /camera/rgb/camera_info for the depth images of "
                    "/camera/depth/image_raw"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Recordings, TopicsEveryNthAndErrors) {
  for (const char* file : {"kinect.bag", "kinect.mcap"}) {
    const std::filesystem::path path = recordings() / file;
    EXPECT_EQ(read_recording(path, {.topic = "/camera/depth/points", .every = 2}).frames.size(),
              2u);
    try {
      read_recording(path, {.topic = "/camera/rgb/points"});
      ADD_FAILURE() << "an absent topic was read";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + ": no message on topic /camera/rgb/points (its topics: "
                                           "/camera/depth/camera_info (sensor_msgs/",
                           0),
                0u)
          << what;
    }
    try {
      read_recording(path, {.topic = "/tf"});
      ADD_FAILURE() << "a tf topic was read as clouds";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("not sensor_msgs/PointCloud2 or sensor_msgs/Image"),
                std::string::npos)
          << e.what();
    }
    // A fixed frame tf does not know is an error (issue 53: the frames were left unposed, and
    // placed by registration, without a word); tests/io/recording_damage_test.cpp has its line.
    EXPECT_THROW(read_recording(path, {.topic = "/camera/depth/points", .fixed_frame = "map"}),
                 std::runtime_error);
  }
  // The command line's topic and every win over the manifest's.
  EXPECT_EQ(read_manifest(recordings() / "bag.yaml", {.every = 3, .topic = "/camera/depth/points"})
                .clouds.size(),
            1u);
}

TEST(Recordings, BrokenRecordingsAreRefusedInOneLine) {
  const std::filesystem::path dir = testing::fresh_dir("broken_recordings");
  for (const char* file : {"kinect.bag", "kinect.mcap"}) {
    const std::string bytes = testing::read_text(recordings() / file);
    testing::write_text(dir / file, bytes.substr(0, bytes.size() / 2));
    try {
      read_recording(dir / file, {.topic = "/camera/depth/points"});
      ADD_FAILURE() << "half of " << file << " was read";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind((dir / file).string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find("runs past the file's end"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  testing::write_text(dir / "x.bag", "#ROSBAG V1.2\n");
  EXPECT_THROW(read_recording(dir / "x.bag", {.topic = "/a"}), std::runtime_error);
  testing::write_text(dir / "x.mcap", "not mcap");
  EXPECT_THROW(read_recording(dir / "x.mcap", {.topic = "/a"}), std::runtime_error);
}

TEST(Recordings, ATumManifestWritesBackAsItsDepthImagesABagsDoesNot) {
  const std::filesystem::path dir = testing::fresh_dir("tum_written_back");
  const Manifest tum = read_manifest(recordings() / "tum.yaml");
  write_manifest(dir / "back.yaml", tum);
  const Manifest back = read_manifest(dir / "back.yaml");
  ASSERT_EQ(back.clouds.size(), tum.clouds.size());
  for (std::size_t i = 0; i < tum.clouds.size(); ++i) {
    EXPECT_EQ(std::filesystem::canonical(back.clouds[i].file),
              std::filesystem::canonical(tum.clouds[i].file));
    EXPECT_EQ(back.clouds[i].T_world_cloud.matrix(), tum.clouds[i].T_world_cloud.matrix());
  }
  EXPECT_EQ(back.depth, tum.depth);
  EXPECT_THROW(write_manifest(dir / "bag.yaml", read_manifest(recordings() / "bag.yaml")),
               std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "bag.yaml"));
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
