#include "vantage/views/ring.hpp"

#include <gtest/gtest.h>

#include <string>

#include "vantage/views/sphere.hpp"

namespace vantage {
namespace {

TEST(Ring, PaperRingHasThirtyViewsLookingAtTheCentre) {
  RingConfig ring;
  ring.center = {0.1, -0.2, 0.8};
  ring.radius = 1.2;
  ring.height = 1.3;
  const auto poses = ring_poses(ring);
  ASSERT_EQ(poses.size(), 30u);
  for (std::size_t k = 0; k < 10; ++k) {
    const Eigen::Isometry3d& centred = poses[3 * k + 1];  // offset 0
    const Eigen::Vector3d to_center = (ring.center - centred.translation()).normalized();
    EXPECT_NEAR(centred.linear().col(0).dot(to_center), 1.0, 1e-12);
    EXPECT_NEAR((centred.translation() - ring.center).head<2>().norm(), 1.2, 1e-12);
    EXPECT_NEAR(centred.translation().z(), 1.3, 1e-12);
    EXPECT_NEAR(centred.linear().determinant(), 1.0, 1e-12);
    // The offsets turn about the world z axis by -15 and +15 degrees.
    const Eigen::Vector2d f0 = centred.linear().col(0).head<2>().normalized();
    const Eigen::Vector2d fl = poses[3 * k].linear().col(0).head<2>().normalized();
    EXPECT_NEAR(std::atan2(f0.x() * fl.y() - f0.y() * fl.x(), f0.dot(fl)), deg2rad(-15), 1e-12);
  }
}

TEST(Ring, FrustumContainsWhatItLooksAt) {
  const Frustum view(look_at({2, 0, 1}, {0, 0, 0}), SensorFov{});
  EXPECT_TRUE(view.contains({0, 0, 0}));
  EXPECT_FALSE(view.contains({3, 0, 1}));       // behind
  EXPECT_FALSE(view.contains({1.9, 0, 0.95}));  // closer than min_range
  EXPECT_FALSE(view.contains({0, 2, 0}));       // outside the horizontal field of view
  const Eigen::AlignedBox3d box = view.bounds();
  EXPECT_TRUE(box.contains(Eigen::Vector3d(0, 0, 0)));
}

TEST(Ring, RejectsBadConfig) {
  RingConfig ring;
  ring.positions = 0;
  EXPECT_THROW(ring_poses(ring), std::invalid_argument);
  ring = {};
  ring.radius = -1;
  EXPECT_THROW(ring_poses(ring), std::invalid_argument);
  SensorFov fov;
  fov.max_range = fov.min_range;
  EXPECT_THROW(fov.validate(), std::invalid_argument);
}

// issue 39: the candidate limit is the ring's own, so a scene's ring, `plan --views` and Python
// meet the same refusal before a view is made.
TEST(Ring, MoreViewsThanADecisionScoresAreRefusedByCount) {
  RingConfig ring;
  ring.positions = 33'334;  // x 3 yaw offsets: 100 002 views
  try {
    ring_poses(ring);
    ADD_FAILURE() << "100002 views were made";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("make 100002 views, more than the 100000"),
              std::string::npos)
        << e.what();
  }
  ring.positions = 33'333;
  EXPECT_EQ(ring_poses(ring).size(), 99'999u);
  SphereConfig sphere;
  sphere.views = 100'001;
  EXPECT_THROW(sphere_poses(sphere), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
