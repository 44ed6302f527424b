#include "vantage/io/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "temp_dir.hpp"

namespace vantage {
namespace {

using test::TempDir;

TEST(RigidTransform, AcceptsRotationsAndNamesEachProblem) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  m.topRightCorner<3, 1>() << 1, -2, 3;
  EXPECT_EQ(rigid_transform_problem(m), "");
  Eigen::Matrix4d near = m;
  near(0, 0) += 1e-7;  // within the tolerance
  EXPECT_EQ(rigid_transform_problem(near), "");

  Eigen::Matrix4d nan = m;
  nan(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(rigid_transform_problem(nan), "entry [1][3] is NaN");
  Eigen::Matrix4d scaled = m;
  scaled.topLeftCorner<3, 3>() *= 1.01;
  EXPECT_NE(rigid_transform_problem(scaled).find("not orthonormal"), std::string::npos);
  Eigen::Matrix4d reflection = m;
  reflection.col(2) *= -1.0;
  EXPECT_NE(rigid_transform_problem(reflection).find("reflection"), std::string::npos);
  Eigen::Matrix4d projective = m;
  projective(3, 0) = 0.1;
  EXPECT_NE(rigid_transform_problem(projective).find("bottom row"), std::string::npos);
}

TEST(TumTrajectory, ReadsPosesSkippingCommentsAndNormalisingQuaternions) {
  TempDir dir;
  const double s = std::sqrt(0.5);
  test::write_file(dir / "poses.txt",
                   "# timestamp tx ty tz qx qy qz qw\n"
                   "\n"
                   "1305031102.175304 1.0 2.0 3.0 0 0 0 1\n"
                   "1305031102.211214 -1 +0.5 0 0 0 " +
                       std::to_string(s * 1.0005) + " " + std::to_string(s * 1.0005) + "\n");
  const std::vector<StampedPose> poses = read_tum_trajectory(dir / "poses.txt");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses[0].stamp, 1305031102.175304);
  EXPECT_TRUE(poses[0].T_world_frame.isApprox(Eigen::Translation3d(1, 2, 3) *
                                              Eigen::Isometry3d::Identity()));
  // 90 degrees about z: the frame's x axis points along world y.
  EXPECT_TRUE((poses[1].T_world_frame.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY(), 1e-6));
  EXPECT_TRUE(poses[1].T_world_frame.translation().isApprox(Eigen::Vector3d(-1, 0.5, 0)));
  EXPECT_NEAR((poses[1].T_world_frame.linear().transpose() * poses[1].T_world_frame.linear() -
               Eigen::Matrix3d::Identity())
                  .norm(),
              0.0, 1e-12);
}

void expect_tum_error(const std::string& line, const std::string& fragment) {
  TempDir dir;
  test::write_file(dir / "bad.txt", "# header\n0 0 0 0 0 0 0 1\n" + line + "\n");
  try {
    read_tum_trajectory(dir / "bad.txt");
    ADD_FAILURE() << "no error for '" << line << "'";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "bad.txt").string() + ":3: "), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(TumTrajectory, BadLinesNameFileAndLine) {
  expect_tum_error("1 0 0 0 0 0 1", "7 fields");
  expect_tum_error("1 0 0 0 0 0 0 1 5", "more than 8");
  expect_tum_error("1 0 abc 0 0 0 0 1", "ty 'abc' is not a number");
  expect_tum_error("1 0 0 nan 0 0 0 1", "tz is NaN");
  expect_tum_error("1 0 0 0 0 0 0 0.5", "quaternion norm 0.5");
  expect_tum_error("1 0 0 0 0 0 0 0", "quaternion norm 0");
}

TEST(TumTrajectory, WriteThenReadGivesThePoses) {
  TempDir dir;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  std::vector<StampedPose> poses;
  for (int i = 0; i < 20; ++i) {
    StampedPose pose;
    pose.stamp = 1000.0 + 0.033 * i;
    pose.T_world_frame.linear() =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
            .normalized()
            .matrix();
    pose.T_world_frame.translation() << normal(rng), normal(rng), normal(rng);
    poses.push_back(pose);
  }
  write_tum_trajectory(dir / "out.txt", poses);
  const std::vector<StampedPose> read = read_tum_trajectory(dir / "out.txt");
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].stamp, poses[i].stamp);
    EXPECT_TRUE(read[i].T_world_frame.matrix().isApprox(poses[i].T_world_frame.matrix(), 1e-12));
  }
}

}  // namespace
}  // namespace vantage
