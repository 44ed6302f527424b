#pragma once
// A synthetic table top for the perception tests: a table and boxes on it, sampled at random on
// their surfaces, optionally only the faces a sensor at a given position faces.

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception::testing {

/// An upright box standing on the table.
struct Box {
  Eigen::Vector2d center_xy;  // [m]
  Eigen::Vector3d size;       // [m] x, y, z extents before the yaw
  double yaw = 0.0;           // [rad]
};

struct Scene {
  double table_z = 0.75;                    // [m] height of the table's top
  Eigen::Vector2d table_half = {0.5, 0.5};  // [m] half extents, centred on the origin
  std::vector<Box> boxes = {
      {{0.15, 0.10}, {0.10, 0.06, 0.20}, 0.3},  {{-0.20, 0.15}, {0.08, 0.08, 0.12}, -0.5},
      {{0.05, -0.25}, {0.20, 0.05, 0.08}, 1.1}, {{-0.25, -0.20}, {0.06, 0.12, 0.30}, 0.0},
      {{0.30, -0.05}, {0.05, 0.05, 0.05}, 0.7},
  };
};

/// A planar patch: origin corner, two edge vectors, and the outward normal.
struct Patch {
  Eigen::Vector3d corner, u, v, normal;
};

inline std::vector<Patch> box_faces(const Box& box, double table_z) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(box.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d ex = R.col(0) * box.size.x(), ey = R.col(1) * box.size.y(),
                        ez = Eigen::Vector3d::UnitZ() * box.size.z();
  const Eigen::Vector3d c0 =
      Eigen::Vector3d(box.center_xy.x(), box.center_xy.y(), table_z) - 0.5 * ex - 0.5 * ey;
  return {
      {c0 + ez, ex, ey, Eigen::Vector3d::UnitZ()},  // top
      {c0, ex, ez, -R.col(1)},                      // -y side
      {c0 + ey, ex, ez, R.col(1)},                  // +y side
      {c0, ey, ez, -R.col(0)},                      // -x side
      {c0 + ex, ey, ez, R.col(0)},                  // +x side
  };
}

inline bool inside_box_footprint(const Box& box, const Eigen::Vector2d& xy) {
  const Eigen::Rotation2Dd R(box.yaw);
  const Eigen::Vector2d local = R.inverse() * (xy - box.center_xy);
  return std::abs(local.x()) <= 0.5 * box.size.x() && std::abs(local.y()) <= 0.5 * box.size.y();
}

/// Uniform random points on the patch, `density` per m², with Gaussian noise of `sigma` [m].
inline void sample_patch(const Patch& patch, double density, double sigma, std::mt19937& rng,
                         PointCloud& out) {
  const double area = patch.u.cross(patch.v).norm();
  const auto n = static_cast<int>(std::lround(area * density));
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = patch.corner + u01(rng) * patch.u + u01(rng) * patch.v;
    out.push_back(
        sigma > 0.0 ? Eigen::Vector3d(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))) : p);
  }
}

/// Points on the boxes' top and side faces, in the world frame.
inline PointCloud sample_objects(const Scene& scene, double density, double sigma,
                                 std::uint32_t seed,
                                 const std::optional<Eigen::Vector3d>& seen_from = {}) {
  std::mt19937 rng(seed);
  PointCloud out;
  for (const Box& box : scene.boxes) {
    for (const Patch& face : box_faces(box, scene.table_z)) {
      const Eigen::Vector3d middle = face.corner + 0.5 * (face.u + face.v);
      if (seen_from && face.normal.dot(*seen_from - middle) <= 0.0) continue;
      sample_patch(face, density, sigma, rng, out);
    }
  }
  return out;
}

/// Points on the table's top outside the boxes' footprints, in the world frame.
inline PointCloud sample_table(const Scene& scene, double density, double sigma,
                               std::uint32_t seed) {
  std::mt19937 rng(seed);
  PointCloud raw;
  const Eigen::Vector3d corner(-scene.table_half.x(), -scene.table_half.y(), scene.table_z);
  sample_patch({corner,
                {2 * scene.table_half.x(), 0, 0},
                {0, 2 * scene.table_half.y(), 0},
                Eigen::Vector3d::UnitZ()},
               density, sigma, rng, raw);
  PointCloud out;
  for (const Eigen::Vector3d& p : raw) {
    bool covered = false;
    for (const Box& box : scene.boxes) covered = covered || inside_box_footprint(box, p.head<2>());
    if (!covered) out.push_back(p);
  }
  return out;
}

/// A rigid transform from a rotation vector [rad] and a translation [m].
inline Eigen::Isometry3d make_pose(const Eigen::Vector3d& rotation, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (rotation.norm() > 0)
    T.linear() = Eigen::AngleAxisd(rotation.norm(), rotation.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

}  // namespace vantage::perception::testing
