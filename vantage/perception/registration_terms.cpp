// The terms of the registration's cost (detail/registration_terms.hpp).

#include "vantage/perception/detail/registration_terms.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <optional>

namespace vantage::perception::detail {

Matrix6d prior_information(const PoseSigma& s) {
  Vector6d sigma;
  sigma << s.roll, s.pitch, s.yaw, s.x, s.y, s.z;
  return sigma.array().square().inverse().matrix().asDiagonal();
}

std::vector<Pair> pair_up(const PointCloud& points_world, const Correction& correction,
                          const Eigen::Vector3d& c, const VoxelMap& map, double distance) {
  std::vector<Pair> pairs(points_world.size());
  const Eigen::Vector3d sensor = c + correction.t;
  tbb::parallel_for(std::size_t{0}, points_world.size(), [&](std::size_t i) {
    const Eigen::Vector3d y = correction.apply(points_world[i], c);
    const std::optional<MapMatch> match = map.nearest(y, distance);
    // NOTE: a surface the sensor sees faces it; the nearest map point on a face turned away (the
    // far side of a box, seen by an earlier scan) is a parallel plane a box's depth away.
    if (!match || match->normal.dot(sensor - match->point) <= 0.0) return;
    Pair& pair = pairs[i];
    pair.valid = true;
    pair.residual = match->normal.dot(y - match->point);
    pair.jacobian << (y - sensor).cross(match->normal), match->normal;
  });
  return pairs;
}

Matrix6d constrained(const Matrix6d& H, const Eigen::Vector3d& m, const Eigen::Vector3d& s,
                     double radius, double ratio) {
  // x_m = A x_s: the same motion, turning about m: t_m = t_s + theta x (m - s).
  Matrix6d A = Matrix6d::Identity();
  const Eigen::Vector3d d = m - s;
  Eigen::Matrix3d cross;
  cross << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
  A.bottomLeftCorner<3, 3>() = -cross;
  Matrix6d A_inverse = Matrix6d::Identity();
  A_inverse.bottomLeftCorner<3, 3>() = cross;
  Vector6d scale;  // x' = x_m / scale
  scale << 1.0 / radius, 1.0 / radius, 1.0 / radius, 1.0, 1.0, 1.0;
  const Matrix6d scaled =
      scale.asDiagonal() * A_inverse.transpose() * H * A_inverse * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(scaled);
  const double strongest = eigen.eigenvalues().maxCoeff();
  Matrix6d keep = Matrix6d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (strongest > 0.0 && eigen.eigenvalues()(i) >= ratio * strongest) {
      keep += eigen.eigenvectors().col(i) * eigen.eigenvectors().col(i).transpose();
    }
  }
  return A_inverse * scale.asDiagonal() * keep * scale.cwiseInverse().asDiagonal() * A;
}

}  // namespace vantage::perception::detail
