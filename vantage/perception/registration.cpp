#include "vantage/perception/registration.hpp"

#include <pcl/console/print.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "vantage/perception/voxel_filter.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// A correction of the guess: rotation `R` about the guess's sensor position `c`, then the
/// translation `t`, so p -> R (p - c) + c + t. Its coordinates x = (rotation vector, t) are what
/// the prior weighs: the odometry's error is a rotation about the sensor and a shift.
struct Correction {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Vector6d coordinates() const {
    const Eigen::AngleAxisd aa(R);
    Vector6d x;
    x << aa.angle() * aa.axis(), t;
    return x;
  }
  Eigen::Vector3d apply(const Eigen::Vector3d& p, const Eigen::Vector3d& c) const {
    return R * (p - c) + c + t;
  }
};

/// One scan point's pairing at the current correction: residual along the map's normal and its
/// Jacobian with respect to (rotation about the current sensor position, translation).
struct Pair {
  bool valid = false;
  double residual = 0.0;
  Vector6d jacobian = Vector6d::Zero();
};

Matrix6d prior_information(const PoseSigma& s) {
  Vector6d sigma;
  sigma << s.roll, s.pitch, s.yaw, s.x, s.y, s.z;
  return sigma.array().square().inverse().matrix().asDiagonal();
}

/// Pairs every point of `points_world` (at the guess) moved by `correction` with the map.
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

/// The projection onto the directions the data constrains. A scene without structure along a
/// direction (a plane: the shift along it, the turn about its normal) still gives its points'
/// noisy normals a small component there, and Gauss-Newton would follow that noise by as much as
/// residual / (normal tilt × lever): degrees. Directions whose information is below `ratio` of
/// the strongest are left to the prior. They are judged as motions about the scan's centroid
/// `m` (the Jacobians turn about the sensor `s`), rotations measured at the scan's radius
/// `radius` about it, so that a turn the objects' spread pins compares with a shift.
/// NOTE: the idea of Zhang, Kaess and Singh (ICRA 2016), "On degeneracy of optimization-based
/// state estimation problems".
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

std::size_t count(const std::vector<Pair>& pairs) {
  return static_cast<std::size_t>(
      std::count_if(pairs.begin(), pairs.end(), [](const Pair& p) { return p.valid; }));
}

/// The weight of each of `pairs` pairs. NOTE: neighbouring points share their map points,
/// normals and the scan's systematic errors: together they count as at most
/// `independent_points` independent measurements.
double independent_share(std::size_t pairs, const RegistrationConfig& config) {
  return pairs > config.independent_points
             ? static_cast<double>(config.independent_points) / static_cast<double>(pairs)
             : 1.0;
}

}  // namespace

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

RegistrationResult register_scan(const PointCloud& points_sensor,
                                 const Eigen::Isometry3d& T_world_sensor_guess, const VoxelMap& map,
                                 const RegistrationConfig& config) {
  config.validate();
  if (!T_world_sensor_guess.matrix().allFinite()) {
    throw std::invalid_argument("register_scan: the pose guess is not finite");
  }
  for (std::size_t i = 0; i < points_sensor.size(); ++i) {
    if (!points_sensor[i].allFinite()) {
      throw std::invalid_argument(cat("register_scan: scan point ", i, " is not finite"));
    }
  }
  RegistrationResult result;
  result.T_world_sensor = T_world_sensor_guess;
  result.T_world_sensor_solved = T_world_sensor_guess;
  if (map.empty() || points_sensor.empty()) return result;

  const Eigen::Vector3d c = T_world_sensor_guess.translation();
  const PoseSigma& s = config.prior;
  double range = 0.0;
  for (const Eigen::Vector3d& p : points_sensor) range = std::max(range, p.norm());
  // NOTE: how far the prior's 1-sigma error moves the farthest point: the shift, plus the turn
  // about the sensor at that range (KISS-ICP's model error, from the noise model, not learnt).
  const double displacement =
      std::hypot(s.x, s.y, s.z) + range * std::hypot(s.roll, s.pitch, s.yaw);
  result.first_distance =
      std::max(config.min_distance, config.sigmas * (displacement + config.sensor_sigma));
  std::vector<double> stages;
  for (double d = result.first_distance; d > config.min_distance; d /= 2.0) stages.push_back(d);
  stages.push_back(config.min_distance);

  const Matrix6d prior = prior_information(s);
  // The scan's centroid and spread (world, at the guess), for judging degenerate directions.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points_sensor) centroid += p;
  centroid = T_world_sensor_guess * (centroid / static_cast<double>(points_sensor.size()));
  double spread = 0.0;
  for (const Eigen::Vector3d& p : points_sensor) {
    spread += (T_world_sensor_guess * p - centroid).squaredNorm();
  }
  const double radius =
      std::max(std::sqrt(spread / static_cast<double>(points_sensor.size())), 0.01);
  const double data_weight = 1.0 / (config.sensor_sigma * config.sensor_sigma);
  Correction correction;
  run_with_threads(config.num_threads, [&] {
    for (const double distance : stages) {
      // NOTE: a coarse stage pairs within `distance`, so a scan thinned to a quarter of it
      // guides it as well at far less cost.
      const PointCloud points_world =
          transform(T_world_sensor_guess,
                    voxel_downsample(points_sensor, std::max(config.voxel_size, distance / 4.0)));
      const double kernel = distance / 3.0;
      for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
        const std::vector<Pair> pairs = pair_up(points_world, correction, c, map, distance);
        ++result.iterations;
        // Gauss-Newton on the robust point-to-plane cost plus the prior (summed in point order,
        // so the result does not depend on the thread count).
        Matrix6d H = Matrix6d::Zero();
        Vector6d g = Vector6d::Zero();
        const double share = independent_share(count(pairs), config);
        for (const Pair& pair : pairs) {
          if (!pair.valid) continue;
          const double u = pair.residual / kernel;
          const double w = share * data_weight / ((1.0 + u * u) * (1.0 + u * u));  // Geman-McClure
          H += w * pair.jacobian * pair.jacobian.transpose();
          g += w * pair.residual * pair.jacobian;
        }
        const Matrix6d P = constrained(H, correction.apply(centroid, c), c + correction.t, radius,
                                       config.degenerate_ratio);
        H = prior + P.transpose() * H * P;
        g = prior * correction.coordinates() + P.transpose() * g;
        const Vector6d dx = H.ldlt().solve(-g);
        // The sensor's position as the posterior knows it: the largest standard deviation.
        const Eigen::Matrix3d position = H.inverse().bottomRightCorner<3, 3>();
        result.position_sigma = std::sqrt(
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(position).eigenvalues().maxCoeff());
        result.constrained_directions = static_cast<int>(std::lround(P.trace()));
        const Eigen::Vector3d w = dx.head<3>();
        const Eigen::Matrix3d dR =
            w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                           : Eigen::Matrix3d::Identity();
        // The increment turns about the current sensor position c + t, which leaves t as is.
        correction.R = dR * correction.R;
        correction.t += dx.tail<3>();
        if (dx.norm() < config.convergence) break;
      }
    }
    // The check, on the last stage's pairing of the full-resolution (voxel_size) scan: the
    // posterior's cost at the solution against the prior's own (at the guess).
    const PointCloud points_world =
        transform(T_world_sensor_guess, voxel_downsample(points_sensor, config.voxel_size));
    const std::vector<Pair> solved = pair_up(points_world, correction, c, map, config.min_distance);
    const std::vector<Pair> guessed =
        pair_up(points_world, Correction{}, c, map, config.min_distance);
    result.correspondences = count(solved);
    result.guess_correspondences = count(guessed);
    const double share =
        independent_share(std::max(result.correspondences, result.guess_correspondences), config);
    const double kernel = config.min_distance / 3.0;
    const auto data_cost = [&](const std::vector<Pair>& pairs) {
      // Geman-McClure, and an unpaired point costs what a pair at the distance limit would.
      const double limit = 9.0 / (1.0 + 9.0);
      double cost = 0.0;
      for (const Pair& pair : pairs) {
        const double u = pair.residual / kernel;
        cost += pair.valid ? u * u / (1.0 + u * u) : limit;
      }
      return 0.5 * share * data_weight * kernel * kernel * cost;
    };
    const Vector6d x = correction.coordinates();
    result.cost = data_cost(solved) + 0.5 * x.dot(prior * x);
    result.guess_cost = data_cost(guessed);
  });

  const Vector6d x = correction.coordinates();
  result.mahalanobis2 = x.dot(prior * x);
  Eigen::Isometry3d solved = Eigen::Isometry3d::Identity();
  solved.linear() = correction.R * T_world_sensor_guess.linear();
  solved.translation() = c + correction.t;
  // NOTE: many small rotations drift from orthonormal by ~1e-16 each; project back.
  solved.linear() = Eigen::Quaterniond(solved.linear()).normalized().toRotationMatrix();
  result.T_world_sensor_solved = solved;
  if (result.correspondences < config.min_correspondences) {
    result.outcome = RegistrationOutcome::kTooFewMatches;
  } else if (result.mahalanobis2 > config.max_mahalanobis2) {
    result.outcome = RegistrationOutcome::kOutsidePrior;
  } else if (result.position_sigma > config.max_position_sigma) {
    result.outcome = RegistrationOutcome::kUncertain;
  } else if (!(result.cost < result.guess_cost)) {
    result.outcome = RegistrationOutcome::kWorseThanPrior;
  } else {
    result.outcome = RegistrationOutcome::kAccepted;
    result.T_world_sensor = solved;
  }
  return result;
}

void silence_pcl_console() { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }

PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::AngleAxisd relative(a.linear().transpose() * b.linear());
  return {(a.translation() - b.translation()).norm(), relative.angle()};
}

}  // namespace vantage::perception
