// issue 38: a sequence without poses. The first cloud is placed from the table (or a given pose),
// each next one by registering it to the map so far (frame to model). Three frames made from the
// shared Kinect frame (tests/data/real/) by moving it by known small motions give the map of the
// same frames at their true poses, to within a cell.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_scene.hpp"
#include "vantage/experiment/recorded.hpp"
#include "vantage/io/cloud_io.hpp"

namespace vantage {
namespace {

Eigen::Isometry3d motion(const Eigen::Vector3d& t, const Eigen::Vector3d& axis, double deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

class UnposedSequence : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_dir("unposed");
    kinect_ = read_manifest(testing::source_dir() / "tests/data/real/milk.yaml");
    // The first frame's pose, from the table as `vantage plan` takes it.
    Mapper first(kinect_.grid, mapper_config_for(kinect_));
    map_recorded(kinect_, first, [&](const RecordedCloud& c) {
      T_world_cloud0_ = c.update.T_world_sensor;
      T_world_cloud0_.linear() =
          c.update.T_world_sensor.linear() * R_cloud_sensor(kinect_.frame).transpose();
    });
    points_ = read_point_cloud(kinect_.clouds[0].file, {.skip_non_finite = true});
    // The camera moves by these, in its own optical frame: about 1 cm and 1-2 degrees a frame.
    motions_ = {Eigen::Isometry3d::Identity(), motion({0.012, -0.004, 0.006}, {0.2, 1.0, 0.1}, 1.5),
                motion({0.020, -0.010, 0.004}, {0.1, 1.0, -0.3}, 3.0)};
  }

  /// Writes frame `k` (the Kinect frame seen from the first frame's pose moved by `D`).
  std::filesystem::path write_frame(const std::string& name, const Eigen::Isometry3d& D) const {
    const std::filesystem::path file = dir_ / name;
    write_point_cloud(file, transform(D.inverse(), points_));
    return file;
  }

  /// The Kinect manifest's settings with these clouds.
  Manifest manifest(std::vector<ManifestCloud> clouds) const {
    Manifest m = kinect_;
    m.clouds = std::move(clouds);
    Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();
    T_cloud_sensor.linear() = R_cloud_sensor(m.frame);
    for (ManifestCloud& c : m.clouds) c.T_world_sensor = c.T_world_cloud * T_cloud_sensor;
    return m;
  }

  std::filesystem::path dir_;
  Manifest kinect_;
  Eigen::Isometry3d T_world_cloud0_ = Eigen::Isometry3d::Identity();
  PointCloud points_;
  std::vector<Eigen::Isometry3d> motions_;
};

TEST_F(UnposedSequence, MapsAsThePosedRunToWithinACell) {
  std::vector<ManifestCloud> posed, unposed;
  for (std::size_t k = 0; k < motions_.size(); ++k) {
    ManifestCloud c;
    c.file = write_frame("frame" + std::to_string(k) + ".pcd", motions_[k]);
    c.T_world_cloud = T_world_cloud0_ * motions_[k];
    posed.push_back(c);
    c.T_world_cloud = Eigen::Isometry3d::Identity();
    c.pose_from_registration = k > 0;
    c.pose_from_table = k == 0;  // the first frame's pose from the table, as `plan` takes it
    unposed.push_back(c);
  }
  const Manifest with_poses = manifest(posed);
  const Manifest without = manifest(unposed);
  MapperConfig posed_config = mapper_config_for(with_poses);
  ASSERT_FALSE(posed_config.register_scans);  // the true poses, as they are
  ASSERT_TRUE(mapper_config_for(without).register_scans);
  Mapper truth(with_poses.grid, posed_config);
  map_recorded(with_poses, truth);
  Mapper mapped(without.grid, mapper_config_for(without));
  std::vector<Eigen::Isometry3d> found;
  map_recorded(without, mapped, [&](const RecordedCloud& c) {
    found.push_back(c.update.T_world_sensor);
    EXPECT_EQ(c.update.registered, c.index > 0) << "cloud " << c.index;
  });
  ASSERT_EQ(found.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Isometry3d error = with_poses.clouds[k].T_world_sensor.inverse() * found[k];
    EXPECT_LT(error.translation().norm(), 0.003) << "frame " << k;
    EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle(), 0.2 * M_PI / 180.0) << "frame " << k;
  }

  // Every occupied cell of the posed run, and one of the run without poses within one cell.
  const OccupancyGrid& a = truth.grid();
  const OccupancyGrid& b = mapped.grid();
  const GridSpec& spec = a.spec();
  std::size_t occupied = 0, matched = 0;
  for (std::size_t i = 0; i < spec.num_cells(); ++i) {
    if (a.state(i) != CellState::kOccupied) continue;
    ++occupied;
    const Index3 c = spec.unravel(i);
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx) {
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const Index3 n = c + Index3(dx, dy, dz);
          near = spec.contains(n) && b.state(spec.linear(n)) == CellState::kOccupied;
        }
      }
    }
    matched += near ? 1 : 0;
  }
  ASSERT_GT(occupied, 1000u);
  const double share = static_cast<double>(matched) / static_cast<double>(occupied);
  RecordProperty("occupied_cells", static_cast<int>(occupied));
  RecordProperty("matched_within_one_cell_permille", static_cast<int>(share * 1000.0));
  EXPECT_GE(share, 0.95) << matched << " of " << occupied << " occupied cells";
}

TEST_F(UnposedSequence, AFrameThatDoesNotRegisterIsNamed) {
  // The third frame jumps 40 cm sideways and turns 30 degrees: no frame's motion.
  std::vector<ManifestCloud> clouds;
  const std::vector<Eigen::Isometry3d> moves = {motions_[0], motions_[1],
                                                motion({0.4, 0.0, 0.0}, {0.0, 1.0, 0.0}, 30.0)};
  for (std::size_t k = 0; k < moves.size(); ++k) {
    ManifestCloud c;
    c.file = write_frame("step" + std::to_string(k) + ".pcd", moves[k]);
    c.T_world_cloud = T_world_cloud0_;
    c.pose_from_registration = k > 0;
    clouds.push_back(c);
  }
  const Manifest m = manifest(clouds);
  Mapper mapper(m.grid, mapper_config_for(m));
  std::size_t mapped = 0;
  try {
    map_recorded(m, mapper, [&](const RecordedCloud&) { ++mapped; });
    FAIL() << "a frame 40 cm and 30 degrees from the one before it was registered";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    RecordProperty("error", what);
    EXPECT_NE(what.find("step2.pcd: no pose given"), std::string::npos) << what;
    EXPECT_NE(what.find("(cloud 3 of 3, registered to the map of clouds 1 to 2)"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_EQ(mapped, 2u);
  EXPECT_EQ(mapper.scans(), 2u);  // the frame refused left the map as it was
}

TEST(UnposedScan, NeedsAScanBeforeItAndRegistration) {
  const GridSpec grid = grid_for_roi({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)}, 0.1);
  const PointCloud points = {Eigen::Vector3d(1, 0, 0)};
  MapperConfig config;
  Mapper mapper(grid, config);
  EXPECT_THROW(
      mapper.add_scan(points, Eigen::Isometry3d::Identity(), SensorFov{}, PoseGuess::kPreviousScan),
      RegistrationFailed);
  config.register_scans = false;
  Mapper no_icp(grid, config);
  no_icp.add_scan(points, Eigen::Isometry3d::Identity(), SensorFov{});
  EXPECT_THROW(
      no_icp.add_scan(points, Eigen::Isometry3d::Identity(), SensorFov{}, PoseGuess::kPreviousScan),
      RegistrationFailed);
  EXPECT_EQ(no_icp.scans(), 1u);
}

}  // namespace
}  // namespace vantage
