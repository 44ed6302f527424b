#include "vantage/views/sphere.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "vantage/views/frustum.hpp"

namespace vantage {
namespace {

TEST(Sphere, ViewsLieOnTheBandAndLookAtTheCentre) {
  SphereConfig sphere;
  sphere.center = {0.2, -0.1, 0.9};
  sphere.radius = 1.5;
  sphere.views = 64;
  sphere.min_elevation = deg2rad(10);
  sphere.max_elevation = deg2rad(70);
  const auto poses = sphere_poses(sphere);
  ASSERT_EQ(poses.size(), 64u);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Isometry3d& pose : poses) {
    const Eigen::Vector3d offset = pose.translation() - sphere.center;
    EXPECT_NEAR(offset.norm(), 1.5, 1e-12);
    const double elevation = std::asin(offset.z() / 1.5);
    EXPECT_GE(elevation, deg2rad(10) - 1e-12);
    EXPECT_LE(elevation, deg2rad(70) + 1e-12);
    EXPECT_NEAR(pose.linear().col(0).dot(-offset.normalized()), 1.0, 1e-12);
    mean += offset;
  }
  // Spread evenly in azimuth: the horizontal mean is near the axis.
  EXPECT_LT((mean / 64.0).head<2>().norm(), 0.1);
  sphere.views = 0;
  EXPECT_THROW(sphere_poses(sphere), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
