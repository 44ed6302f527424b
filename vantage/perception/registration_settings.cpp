// The registration's settings, its outcomes' names, and the measures of a pose's error that
// exploration and the benchmarks report (registration.hpp); the algorithm is registration.cpp's.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/perception/registration.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {

void PoseSigma::validate() const {
  const double values[] = {x, y, z, roll, pitch, yaw};
  const char* names[] = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (int i = 0; i < 6; ++i) {
    if (!(values[i] > 0.0 && std::isfinite(values[i]))) {
      throw std::invalid_argument(
          cat("registration.prior.", names[i], " must be > 0, got ", values[i]));
    }
  }
}

void RegistrationConfig::validate() const {
  prior.validate();
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(sensor_sigma)) {
    throw std::invalid_argument(cat("registration.sensor_sigma must be > 0 m, got ", sensor_sigma));
  }
  if (!positive(sigmas)) {
    throw std::invalid_argument(cat("registration.sigmas must be > 0, got ", sigmas));
  }
  if (!positive(min_distance)) {
    throw std::invalid_argument(cat("registration.min_distance must be > 0 m, got ", min_distance));
  }
  if (!(voxel_size >= 0.0 && std::isfinite(voxel_size))) {
    throw std::invalid_argument(cat("registration.voxel_size must be >= 0 m, got ", voxel_size));
  }
  if (!(degenerate_ratio >= 0.0 && degenerate_ratio < 1.0)) {
    throw std::invalid_argument(
        cat("registration.degenerate_ratio must be in [0, 1), got ", degenerate_ratio));
  }
  if (!(convergence > 0.0 && std::isfinite(convergence))) {
    throw std::invalid_argument(cat("registration.convergence must be > 0, got ", convergence));
  }
  if (max_iterations < 1) {
    throw std::invalid_argument(
        cat("registration.max_iterations must be >= 1, got ", max_iterations));
  }
  if (!positive(max_mahalanobis2)) {
    throw std::invalid_argument(
        cat("registration.max_mahalanobis2 must be > 0, got ", max_mahalanobis2));
  }
  if (!(start_sigmas >= 0.0 && std::isfinite(start_sigmas))) {
    throw std::invalid_argument(cat("registration.start_sigmas must be >= 0, got ", start_sigmas));
  }
  if (!(ambiguity_cost >= 0.0 && std::isfinite(ambiguity_cost))) {
    throw std::invalid_argument(
        cat("registration.ambiguity_cost must be >= 0, got ", ambiguity_cost));
  }
  if (!(prune_cost >= ambiguity_cost && std::isfinite(prune_cost))) {
    throw std::invalid_argument(
        cat("registration.prune_cost must be >= registration.ambiguity_cost (", ambiguity_cost,
            "), got ", prune_cost));
  }
  if (!(min_overlap >= 0.0 && min_overlap <= 1.0)) {
    throw std::invalid_argument(
        cat("registration.min_overlap must be in [0, 1], got ", min_overlap));
  }
  if (!positive(max_position_sigma)) {
    throw std::invalid_argument(
        cat("registration.max_position_sigma must be > 0 m, got ", max_position_sigma));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("registration.num_threads must be >= 0, got ", num_threads));
  }
}

std::string_view to_string(RegistrationOutcome outcome) {
  switch (outcome) {
    case RegistrationOutcome::kAccepted:
      return "accepted";
    case RegistrationOutcome::kEmptyMap:
      return "empty_map";
    case RegistrationOutcome::kTooFewMatches:
      return "too_few_matches";
    case RegistrationOutcome::kOutsidePrior:
      return "outside_prior";
    case RegistrationOutcome::kUncertain:
      return "uncertain";
    case RegistrationOutcome::kWorseThanPrior:
      return "worse_than_prior";
  }
  return "unknown";
}

PointSpread point_spread(const PointCloud& points) {
  PointSpread s;
  if (points.empty()) return s;
  for (const Eigen::Vector3d& p : points) s.mean += p;
  s.mean /= static_cast<double>(points.size());
  for (const Eigen::Vector3d& p : points) s.covariance += (p - s.mean) * (p - s.mean).transpose();
  s.covariance /= static_cast<double>(points.size());
  return s;
}

PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::AngleAxisd relative(a.linear().transpose() * b.linear());
  return {(a.translation() - b.translation()).norm(), relative.angle()};
}

PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                     const PointSpread& points_at_b) {
  PoseError error = pose_error(a, b);
  // NOTE: a pose is no error of itself; a b^-1 rounds to a hair off the identity (2e-16 m).
  if (a.matrix() == b.matrix()) return {0.0, 0.0, 0.0};
  // A point q placed by b lands at E q = R q + t under a, E = a b^-1, so E q - q = A q + t with
  // A = R - I, whose mean square over the points is tr(A Σ Aᵀ) + |A μ + t|².
  const Eigen::Isometry3d E = a * b.inverse();
  const Eigen::Matrix3d A = E.linear() - Eigen::Matrix3d::Identity();
  const double mean_square = (A * points_at_b.covariance * A.transpose()).trace() +
                             (A * points_at_b.mean + E.translation()).squaredNorm();
  error.displacement = std::sqrt(std::max(mean_square, 0.0));
  return error;
}

}  // namespace vantage::perception
