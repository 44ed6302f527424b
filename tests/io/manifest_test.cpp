#include "vantage/io/manifest.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "temp_dir.hpp"
#include "vantage/io/trajectory.hpp"

namespace vantage {
namespace {

using test::TempDir;

const std::string kSensor = R"(sensor:
  frame: optical
  intrinsics: {fx: 525, fy: 525, cx: 319.5, cy: 239.5, width: 640, height: 480}
  min_range: 0.3
  max_range: 3.5
)";
const std::string kRegion = R"(roi:
  min: [-0.5, -0.5, 0.0]
  max: [0.5, 0.5, 0.5]
resolution: 0.01
)";
const std::string kClouds = R"(clouds:
  - file: scans/a.pcd
    pose: [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]]
  - file: scans/b.PLY
    pose: [0, -1, 0, 0,  1, 0, 0, 1,  0, 0, 1, 0.5,  0, 0, 0, 1]
    stamp: 12.5
)";

/// A PCD file of one point whose VIEWPOINT is `viewpoint` (the identity: no pose recorded).
std::string pcd_with_viewpoint(const std::string& viewpoint = "0 0 0 1 0 0 0") {
  return "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
         "VIEWPOINT " +
         viewpoint + "\nPOINTS 1\nDATA ascii\n1 2 3\n";
}

// A folder with the clouds the manifests name (only a PCD's header is read here, for its
// VIEWPOINT, when the manifest gives the cloud no pose).
class ManifestTest : public ::testing::Test {
 protected:
  ManifestTest() {
    test::write_file(dir_ / "scans/a.pcd", pcd_with_viewpoint());
    test::write_file(dir_ / "scans/b.PLY", "not read");
  }

  std::filesystem::path write(const std::string& yaml, const std::string& name = "manifest.yaml") {
    test::write_file(dir_ / name, yaml);
    return dir_ / name;
  }

  // The manifest must fail with one line "file:line: key: ..." holding `fragment`.
  void expect_error(const std::string& yaml, const std::string& key, const std::string& fragment) {
    const auto path = write(yaml);
    try {
      read_manifest(path);
      ADD_FAILURE() << "no error; expected " << key << ": " << fragment;
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path.string() + ":", 0), 0u) << message;
      EXPECT_NE(message.find(key), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  static std::string replace(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  }

  TempDir dir_;
};

TEST_F(ManifestTest, ReadsCloudsPosesSensorRegionAndOptions) {
  const Manifest m = read_manifest(write(kSensor + kRegion + kClouds + R"(options:
  table_segmentation: true
  icp: yes
  integration: endpoint
)"));
  ASSERT_EQ(m.clouds.size(), 2u);
  EXPECT_EQ(m.clouds[0].file, dir_ / "scans/a.pcd");
  EXPECT_EQ(m.clouds[1].file, dir_ / "scans/b.PLY");
  EXPECT_FALSE(m.clouds[0].stamp);
  EXPECT_EQ(m.clouds[1].stamp, 12.5);
  EXPECT_TRUE(m.clouds[0].T_world_cloud.translation().isApprox(Eigen::Vector3d(1, 0, 0.5)));
  EXPECT_TRUE(m.clouds[1].T_world_cloud.translation().isApprox(Eigen::Vector3d(0, 1, 0.5)));
  EXPECT_TRUE((m.clouds[1].T_world_cloud.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY()));
  // Optical clouds: the sensor looks along the cloud's z, its left is the cloud's -x and its up
  // the cloud's -y.
  for (const ManifestCloud& c : m.clouds) {
    const Eigen::Matrix3d R = c.T_world_cloud.linear();
    EXPECT_TRUE(c.T_world_sensor.linear().col(0).isApprox(R.col(2)));
    EXPECT_TRUE(c.T_world_sensor.linear().col(1).isApprox(-R.col(0)));
    EXPECT_TRUE(c.T_world_sensor.linear().col(2).isApprox(-R.col(1)));
    EXPECT_TRUE(c.T_world_sensor.translation().isApprox(c.T_world_cloud.translation()));
  }
  EXPECT_EQ(m.frame, CloudFrame::kOptical);
  ASSERT_TRUE(m.intrinsics);
  EXPECT_EQ(m.intrinsics->width, 640);
  EXPECT_NEAR(m.fov.h_fov, 2.0 * std::atan(320.0 / 525.0), 1e-12);
  EXPECT_NEAR(m.fov.v_fov, 2.0 * std::atan(240.0 / 525.0), 1e-12);
  EXPECT_EQ(m.fov.min_range, 0.3);
  EXPECT_EQ(m.fov.max_range, 3.5);
  EXPECT_EQ(m.grid.dims, Index3(100, 100, 50));
  EXPECT_TRUE(m.grid.origin.isApprox(Eigen::Vector3d(-0.5, -0.5, 0.0)));
  EXPECT_EQ(m.grid.resolution, 0.01);
  EXPECT_TRUE(m.options.table_segmentation);
  EXPECT_TRUE(m.options.icp);
  EXPECT_EQ(m.options.integration, IntegrationMode::kEndpoint);
  EXPECT_FALSE(m.trajectory);
}

// The example in docs/manifest.md is a valid manifest and means what the page says.
TEST_F(ManifestTest, DocumentedExampleReads) {
  const char* source = std::getenv("VANTAGE_SOURCE_DIR");
  ASSERT_NE(source, nullptr);
  const std::string page = test::read_file(std::filesystem::path(source) / "docs/manifest.md");
  const std::size_t begin = page.find("```yaml\n");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = page.find("```", begin + 8);
  test::write_file(dir_ / "scans/000.pcd", "");
  test::write_file(dir_ / "scans/001.ply", "");
  const Manifest m = read_manifest(write(page.substr(begin + 8, end - begin - 8)));
  ASSERT_EQ(m.clouds.size(), 2u);
  for (const ManifestCloud& c : m.clouds) {
    const Eigen::Vector3d eye = c.T_world_sensor.translation();
    EXPECT_NEAR(eye.head<2>().norm(), 0.9, 1e-12);
    EXPECT_NEAR(eye.z(), 0.75, 1e-12);
    const Eigen::Vector3d forward = c.T_world_sensor.linear().col(0);  // towards the z axis
    EXPECT_TRUE(forward.isApprox(-Eigen::Vector3d(eye.x(), eye.y(), 0).normalized()));
    EXPECT_TRUE(c.T_world_sensor.linear().col(2).isApprox(Eigen::Vector3d::UnitZ()));  // up
  }
  EXPECT_EQ(m.grid.dims, Index3(128, 128, 64));
  EXPECT_EQ(m.options, ManifestOptions{});
}

TEST_F(ManifestTest, DefaultsOptionsAndTakesFovInDegrees) {
  const std::string sensor = R"(sensor:
  frame: x_forward
  fov_deg: {horizontal: 60, vertical: 45}
  min_range: 0.5
  max_range: 4
)";
  const Manifest m = read_manifest(write(sensor + kRegion + kClouds));
  EXPECT_EQ(m.frame, CloudFrame::kXForward);
  EXPECT_FALSE(m.intrinsics);
  EXPECT_DOUBLE_EQ(m.fov.h_fov, deg2rad(60));
  EXPECT_DOUBLE_EQ(m.fov.v_fov, deg2rad(45));
  EXPECT_TRUE(m.clouds[1].T_world_sensor.isApprox(m.clouds[1].T_world_cloud));
  EXPECT_EQ(m.options, ManifestOptions{});
}

TEST(FovFromIntrinsics, StaysInsideAnOffCentreImage) {
  PinholeIntrinsics k{500, 400, 300, 200, 640, 480};
  const SensorFov fov = fov_from_intrinsics(k, 0.1, 2.0);
  EXPECT_DOUBLE_EQ(fov.h_fov, 2.0 * std::atan(300.5 / 500.0));  // left edge is nearer
  EXPECT_DOUBLE_EQ(fov.v_fov, 2.0 * std::atan(200.5 / 400.0));
  k.cx = 700;
  EXPECT_THROW(fov_from_intrinsics(k, 0.1, 2.0), std::invalid_argument);
}

TEST(GridForRoi, CoversTheRoiWithWholeCellsOnTheWorldLattice) {
  const GridSpec spec = grid_for_roi(
      Eigen::AlignedBox3d(Eigen::Vector3d(-0.505, 0.2, 0.0), Eigen::Vector3d(0.3, 0.2001, 0.1)),
      0.01);
  EXPECT_TRUE(spec.origin.isApprox(Eigen::Vector3d(-0.51, 0.2, 0.0)));
  EXPECT_EQ(spec.dims, Index3(81, 1, 10));
  EXPECT_THROW(
      grid_for_roi(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)), 0.0),
      std::invalid_argument);
}

TEST_F(ManifestTest, FolderWithTrajectoryMatchedByOrder) {
  test::write_file(dir_ / "scans/c.pcd", "");
  test::write_file(dir_ / "scans/notes.txt", "");
  std::vector<StampedPose> poses(3);
  for (int i = 0; i < 3; ++i) {
    poses[static_cast<std::size_t>(i)].stamp = i;
    poses[static_cast<std::size_t>(i)].T_world_frame.translation() << i, 0, 1;
  }
  write_tum_trajectory(dir_ / "scans/poses.txt", poses);
  write(kSensor + kRegion + "trajectory:\n  file: poses.txt\n", "scans/manifest.yaml");
  const Manifest m = read_manifest(dir_ / "scans");
  EXPECT_EQ(m.file, dir_ / "scans/manifest.yaml");
  ASSERT_EQ(m.clouds.size(), 3u);  // sorted by name, .txt skipped
  EXPECT_EQ(m.clouds[0].file.filename(), "a.pcd");
  EXPECT_EQ(m.clouds[1].file.filename(), "b.PLY");
  EXPECT_EQ(m.clouds[2].file.filename(), "c.pcd");
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(m.clouds[static_cast<std::size_t>(i)].T_world_cloud.translation().isApprox(
        Eigen::Vector3d(i, 0, 1)));
  }
  EXPECT_EQ(m.trajectory, dir_ / "scans/poses.txt");
  EXPECT_EQ(m.match, PoseMatch::kOrder);
}

TEST_F(ManifestTest, TrajectoryMatchedByTimestamp) {
  test::write_file(dir_ / "scans/100.25.pcd", "");
  test::write_file(dir_ / "poses.txt",
                   "10.00 0 0 0 0 0 0 1\n12.49 1 0 0 0 0 0 1\n12.51 2 0 0 0 0 0 1\n"
                   "100.2 3 0 0 0 0 0 1\n100.3 4 0 0 0 0 0 1\n");
  const std::string clouds = R"(clouds:
  - {file: scans/b.PLY, stamp: 12.5}
  - {file: scans/100.25.pcd}
  - {file: scans/a.pcd, stamp: 9.99}
trajectory:
  file: poses.txt
  match: timestamp
  max_time_difference: 0.06
)";
  const Manifest m = read_manifest(write(kSensor + kRegion + clouds));
  ASSERT_EQ(m.clouds.size(), 3u);
  EXPECT_EQ(m.match, PoseMatch::kTimestamp);
  EXPECT_DOUBLE_EQ(m.max_time_difference, 0.06);
  // 12.5 lies 0.01 from both neighbours (up to rounding); 100.25 exactly between two: earlier.
  EXPECT_NEAR(m.clouds[0].T_world_cloud.translation().x(), 1.5, 0.5);
  EXPECT_EQ(m.clouds[1].stamp, 100.25);
  EXPECT_EQ(m.clouds[1].T_world_cloud.translation().x(), 3.0);
  EXPECT_EQ(m.clouds[2].T_world_cloud.translation().x(), 0.0);

  expect_error(kSensor + kRegion + replace(clouds, "0.06", "0.02"), "clouds[1]",
               "no pose in poses.txt within 0.02 s of stamp 100.25");
  expect_error(kSensor + kRegion +
                   replace(clouds, "{file: scans/a.pcd, stamp: 9.99}", "{file: scans/a.pcd}"),
               "clouds[2]", "no stamp to match the trajectory by");
}

TEST_F(ManifestTest, WriteThenReadGivesTheSameManifest) {
  const Manifest m = read_manifest(write(kSensor + kRegion + kClouds + "options: {icp: true}\n"));
  write_manifest(dir_ / "copy/manifest.yaml", m);
  const Manifest back = read_manifest(dir_ / "copy");
  ASSERT_EQ(back.clouds.size(), m.clouds.size());
  for (std::size_t i = 0; i < m.clouds.size(); ++i) {
    EXPECT_EQ(back.clouds[i].file, m.clouds[i].file);
    EXPECT_EQ(back.clouds[i].T_world_cloud.matrix(), m.clouds[i].T_world_cloud.matrix());
    EXPECT_EQ(back.clouds[i].T_world_sensor.matrix(), m.clouds[i].T_world_sensor.matrix());
    EXPECT_EQ(back.clouds[i].stamp, m.clouds[i].stamp);
  }
  EXPECT_EQ(back.fov, m.fov);
  EXPECT_EQ(back.intrinsics, m.intrinsics);
  EXPECT_EQ(back.frame, m.frame);
  EXPECT_EQ(back.grid, m.grid);
  EXPECT_EQ(back.options, m.options);
}

// Issue 38: only the first cloud needs a pose; a later one without is registered to the map.
TEST_F(ManifestTest, MissingPoseForACloud) {
  expect_error(
      kSensor + kRegion +
          replace(kClouds, "    pose: [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]]\n",
                  ""),
      "clouds[0].pose", "the first cloud a.pcd has no pose");
  const Manifest m = read_manifest(write(
      kSensor + kRegion +
      replace(kClouds, "    pose: [0, -1, 0, 0,  1, 0, 0, 1,  0, 0, 1, 0.5,  0, 0, 0, 1]\n", "")));
  EXPECT_FALSE(m.clouds[0].pose_from_registration);
  EXPECT_TRUE(m.clouds[1].pose_from_registration);
  EXPECT_TRUE(m.clouds[1].T_world_cloud.matrix().isIdentity());
}

TEST_F(ManifestTest, APcdViewpointIsTheCloudsPoseWhenTheManifestGivesNone) {
  // A quarter turn about z and a translation, as strands-style recordings carry their poses.
  test::write_file(dir_ / "scans/a.pcd",
                   pcd_with_viewpoint("1 2 0.5 0.70710678118654757 0 0 0.70710678118654746"));
  const std::string clouds = "clouds:\n  - file: scans/a.pcd\n";
  const Manifest m = read_manifest(write(kSensor + kRegion + clouds));
  ASSERT_EQ(m.clouds.size(), 1u);
  EXPECT_TRUE(m.clouds[0].pose_from_viewpoint);
  Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
  expected.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  expected.translation() = Eigen::Vector3d(1, 2, 0.5);
  EXPECT_TRUE(m.clouds[0].T_world_cloud.isApprox(expected, 1e-12))
      << m.clouds[0].T_world_cloud.matrix();
  // A pose in the manifest wins over the file's.
  const Manifest given = read_manifest(write(kSensor + kRegion + kClouds));
  EXPECT_FALSE(given.clouds[0].pose_from_viewpoint);
  EXPECT_TRUE(given.clouds[0].T_world_cloud.translation().isApprox(Eigen::Vector3d(1, 0, 0.5)));
  // A VIEWPOINT that is no rotation is an error naming the file.
  test::write_file(dir_ / "scans/a.pcd", pcd_with_viewpoint("0 0 0 2 0 0 0"));
  try {
    read_manifest(write(kSensor + kRegion + clouds));
    ADD_FAILURE() << "a VIEWPOINT quaternion of norm 2 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a.pcd: line 8: the VIEWPOINT quaternion"),
              std::string::npos)
        << e.what();
  }
}

// issue 27: a frame from a depth camera on no robot has no pose; with table segmentation on, the
// pose comes from the table when the cloud is read. Issue 38: every later cloud may lack one too,
// and is then registered to the map so far.
TEST_F(ManifestTest, ACloudWithoutAPoseTakesOneFromTheTable) {
  const std::string clouds = "clouds:\n  - file: scans/a.pcd\n";
  const std::string options = "options: {table_segmentation: true, table_height: 0.9}\n";
  const Manifest m = read_manifest(write(kSensor + kRegion + clouds + options));
  ASSERT_EQ(m.clouds.size(), 1u);
  EXPECT_TRUE(m.clouds[0].pose_from_table);
  EXPECT_FALSE(m.clouds[0].pose_from_viewpoint);
  EXPECT_EQ(m.options.table_height, 0.9);
  EXPECT_EQ(
      read_manifest(write(kSensor + kRegion + clouds + "options: {table_segmentation: true}\n"))
          .options.table_height,
      0.75);
  // PCL's stereo test frame: a half turn about x at the origin is no pose either.
  test::write_file(dir_ / "scans/a.pcd", pcd_with_viewpoint("0 0 0 0 1 0 0"));
  EXPECT_TRUE(read_manifest(write(kSensor + kRegion + clouds + options)).clouds[0].pose_from_table);
  // Written back without a pose, it is estimated again.
  write_manifest(dir_ / "back.yaml", m);
  const Manifest back = read_manifest(dir_ / "back.yaml");
  EXPECT_TRUE(back.clouds[0].pose_from_table);
  EXPECT_EQ(back.options, m.options);
  // Two clouds without poses: the table places the first, registration the second.
  test::write_file(dir_ / "scans/c.pcd", pcd_with_viewpoint());
  const Manifest two =
      read_manifest(write(kSensor + kRegion + clouds + "  - file: scans/c.pcd\n" + options));
  ASSERT_EQ(two.clouds.size(), 2u);
  EXPECT_TRUE(two.clouds[0].pose_from_table);
  EXPECT_FALSE(two.clouds[0].pose_from_registration);
  EXPECT_FALSE(two.clouds[1].pose_from_table);
  EXPECT_TRUE(two.clouds[1].pose_from_registration);
  // Written back, the second is still without a pose.
  write_manifest(dir_ / "back2.yaml", two);
  EXPECT_TRUE(read_manifest(dir_ / "back2.yaml").clouds[1].pose_from_registration);
  // Without segmentation, the first cloud needs a pose; the second never does.
  const std::string first_posed =
      "clouds:\n  - file: scans/a.pcd\n    pose: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\n"
      "  - file: scans/c.pcd\n";
  const Manifest posed_first = read_manifest(write(kSensor + kRegion + first_posed));
  EXPECT_FALSE(posed_first.clouds[0].pose_from_registration);
  EXPECT_TRUE(posed_first.clouds[1].pose_from_registration);
  expect_error(kSensor + kRegion + clouds + "options: {table_height: .nan}\n",
               "options.table_height", "is NaN");
  // Without segmentation the error says how to get one.
  expect_error(kSensor + kRegion + clouds, "clouds[0].pose",
               "options.table_segmentation: true for a pose from the table");
}

TEST_F(ManifestTest, FolderWithoutPoses) {
  write(kSensor + kRegion, "scans/manifest.yaml");
  try {
    read_manifest(dir_ / "scans");
    ADD_FAILURE() << "no error for a folder without poses";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(
        std::string(e.what()).find("clouds[0].pose: missing: the first cloud a.pcd has no pose"),
        std::string::npos)
        << e.what();
  }
  write(kSensor + kRegion);  // beside it, no cloud at all
  expect_error(kSensor + kRegion, "clouds", "holds no .pcd or .ply file");
}

// issue 53: a folder whose .pcd entry is a folder or a FIFO was said as "2 poses but 1 clouds",
// the entry unnamed.
TEST_F(ManifestTest, AFolderEntryNamedAsACloudThatIsNoFileIsNamed) {
  std::filesystem::create_directories(dir_ / "odd/b.pcd");
  test::write_file(dir_ / "odd/a.pcd", pcd_with_viewpoint());
  test::write_file(dir_ / "odd/manifest.yaml", kSensor + kRegion);
  try {
    read_manifest(dir_ / "odd");
    ADD_FAILURE() << "a folder named b.pcd was skipped";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(
        std::string(e.what()).find("clouds: missing, so the folder's .pcd and .ply files "
                                   "are taken, and " +
                                   (dir_ / "odd/b.pcd").string() + " is a directory, not a file"),
        std::string::npos)
        << e.what();
  }
  std::filesystem::remove(dir_ / "odd/b.pcd");
  ASSERT_EQ(::mkfifo((dir_ / "odd/c.pcd").c_str(), 0600), 0);
  try {
    read_manifest(dir_ / "odd");
    ADD_FAILURE() << "a FIFO named c.pcd was skipped";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("c.pcd is a FIFO, not a regular file"), std::string::npos)
        << e.what();
  }
}

TEST_F(ManifestTest, CloudCountDiffersFromPoseCount) {
  test::write_file(dir_ / "poses.txt", "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n");
  expect_error(
      kSensor + kRegion +
          "clouds: [{file: scans/a.pcd}, {file: scans/b.PLY}]\ntrajectory: {file: poses.txt}\n",
      "trajectory", "poses.txt holds 3 poses but there are 2 clouds");
}

TEST_F(ManifestTest, NaNs) {
  expect_error(kSensor + kRegion + replace(kClouds, "[0, 0, 1, 0.5]", "[0, 0, 1, .nan]"),
               "clouds[0].pose[2][3]", "is NaN");
  expect_error(kSensor + replace(kRegion, "0.5]", "nan]"), "roi.max[2]", "is NaN");
  test::write_file(dir_ / "poses.txt", "0 0 0 0 0 0 0 1\n1 nan 0 0 0 0 0 1\n");
  try {
    read_manifest(write(
        kSensor + kRegion +
        "clouds: [{file: scans/a.pcd}, {file: scans/b.PLY}]\ntrajectory: {file: poses.txt}\n"));
    ADD_FAILURE() << "no error for a NaN in the trajectory";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("poses.txt:2: tx is NaN"), std::string::npos) << e.what();
  }
}

TEST_F(ManifestTest, NonRigidMatrices) {
  expect_error(
      kSensor + kRegion +
          replace(kClouds, "[[1, 0, 0, 1], [0, 1, 0, 0]", "[[1.001, 0, 0, 1], [0, 1, 0, 0]"),
      "clouds[0].pose", "not a rigid transform: rotation is not orthonormal");
  expect_error(
      kSensor + kRegion +
          replace(kClouds, "[0, 0, 1, 0.5], [0, 0, 0, 1]]", "[0, 0, -1, 0.5], [0, 0, 0, 1]]"),
      "clouds[0].pose", "reflection");
  expect_error(
      kSensor + kRegion + replace(kClouds, "0, 0, 0, 1]\n    stamp", "0, 0, 0, 2]\n    stamp"),
      "clouds[1].pose", "bottom row");
  expect_error(kSensor + kRegion + replace(kClouds, "[0, 0, 0, 1]]", "[0, 0, 0]]"),
               "clouds[0].pose[3]", "row of 4 numbers");
}

TEST_F(ManifestTest, BadRegionAndResolution) {
  expect_error(kSensor + replace(kRegion, "max: [0.5, 0.5, 0.5]", "max: [0.5, 0.5, 0.0]") + kClouds,
               "roi", "zero or negative size: max.z (0) must exceed min.z (0)");
  expect_error(
      kSensor + replace(kRegion, "max: [0.5, 0.5, 0.5]", "max: [-0.6, 0.5, 0.5]") + kClouds, "roi",
      "zero or negative size: max.x");
  expect_error(kSensor + replace(kRegion, "resolution: 0.01", "resolution: 0") + kClouds,
               "resolution", "must be positive");
  expect_error(kSensor + replace(kRegion, "resolution: 0.01", "resolution: -0.01") + kClouds,
               "resolution", "must be positive");
  expect_error(kSensor + replace(kRegion, "resolution: 0.01", "resolution: 0.0001") + kClouds,
               "roi", "grid too large");
}

// yaml-cpp alone would take the first of two values, or read the first document only.
TEST_F(ManifestTest, DuplicateKeysAndSecondDocumentsAreRefused) {
  expect_error(kSensor + kRegion + kClouds + "resolution: 0.02\n", "resolution",
               "duplicate key 'resolution' (first at line 9)");
  expect_error(replace(kSensor, "fx: 525,", "fx: 525, fx: 500,") + kRegion + kClouds,
               "sensor.intrinsics.fx", "duplicate key 'fx'");
  expect_error(kSensor + kRegion + kClouds + "---\nresolution: 0.02\n", "",
               "a second YAML document");
}

TEST_F(ManifestTest, OtherMistakesAreNamed) {
  expect_error(kSensor + kRegion + kClouds + "option: {icp: true}\n", "option", "unknown key");
  expect_error(kSensor + kRegion + kClouds + "options: {icp: maybe}\n", "options.icp",
               "true or false");
  expect_error(kSensor + kRegion + kClouds + "options: {integration: fancy}\n",
               "options.integration", "fancy");
  expect_error(replace(kSensor, "  frame: optical\n", "") + kRegion + kClouds, "sensor",
               "missing key 'frame'");
  expect_error(replace(kSensor, "frame: optical", "frame: camera") + kRegion + kClouds,
               "sensor.frame", "optical or x_forward");
  // A value that spans lines (a quoted escape, or a plain scalar folded over blank lines, as
  // the fuzzer found) is echoed escaped: the message stays one line.
  expect_error(replace(kSensor, "frame: optical", "frame: \"x_\\n\\nforward\"") + kRegion + kClouds,
               "sensor.frame", "'x_\\x0a\\x0aforward'");
  expect_error(replace(kSensor, "  min_range: 0.3\n",
                       "  fov_deg: {horizontal: 60, vertical: 45}\n  min_range: 0.3\n") +
                   kRegion + kClouds,
               "sensor", "not both");
  expect_error(replace(kSensor, "cx: 319.5", "cx: 719.5") + kRegion + kClouds, "sensor",
               "intrinsics.cx must lie inside the image");
  expect_error(replace(kSensor, "max_range: 3.5", "max_range: 0.2") + kRegion + kClouds, "sensor",
               "range");
  expect_error(kSensor + kRegion + replace(kClouds, "scans/a.pcd", "scans/missing.pcd"),
               "clouds[0].file", "no such file");
  expect_error(kSensor + kRegion + replace(kClouds, "scans/a.pcd", "scans/a.xyz"), "clouds[0].file",
               "not a .pcd, .ply or .png file");
  expect_error(kSensor + kRegion + "clouds: []\n", "clouds", "is empty");
  expect_error(kSensor + kRegion + kClouds + "trajectory: {file: poses.txt}\n", "clouds[0].pose",
               "not both");
  expect_error(kSensor + kRegion + kClouds + "version: 2\n", "version", "only version 1");
  expect_error("sensor: [1, 2\n", "", "end of sequence");
}

}  // namespace
}  // namespace vantage
