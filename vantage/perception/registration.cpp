#include "vantage/perception/registration.hpp"

#include <pcl/console/print.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "vantage/perception/detail/registration_terms.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {
namespace {

using detail::Correction;
using detail::count;
using detail::independent_share;
using detail::Matrix6d;
using detail::Pair;
using detail::Vector6d;

/// A stage of the coarse-to-fine schedule: the scan thinned for it and its correspondence
/// distance.
struct Stage {
  double distance = 0.0;    ///< [m]
  PointCloud points_world;  ///< the scan at the guess, thinned to max(voxel_size, distance / 4)
};

/// A correction's fit on the last stage's pairing of the full-resolution scan.
struct Score {
  double robust = 0.0;  ///< the Geman-McClure sum, in units of the kernel's square
  double prior = 0.0;   ///< the prior's cost of the correction
  std::size_t correspondences = 0;
};

/// Where one start's Gauss-Newton ended.
struct Solution {
  Correction correction;
  std::size_t first_stage = 0;  ///< the stage it starts at
  int constrained_directions = 0;
  double position_sigma = 0.0;  ///< [m] the posterior's, along its worst axis
  Score score;                  ///< at the end
};

/// One registration's data, shared by its starts.
class Problem {
 public:
  Problem(const PointCloud& points_sensor, const Eigen::Isometry3d& T_world_sensor_guess,
          const VoxelMap& map, const RegistrationConfig& config)
      : prior(detail::prior_information(config.prior)),
        guess_(T_world_sensor_guess),
        c_(T_world_sensor_guess.translation()),
        map_(map),
        config_(config),
        data_weight_(1.0 / (config.sensor_sigma * config.sensor_sigma)) {
    const PoseSigma& s = config.prior;
    double range = 0.0;
    for (const Eigen::Vector3d& p : points_sensor) range = std::max(range, p.norm());
    range_ = range;
    // NOTE: how far the prior's 1-sigma error moves the farthest point: the shift, plus the turn
    // about the sensor at that range (KISS-ICP's model error, from the noise model, not learnt).
    const double displacement =
        std::hypot(s.x, s.y, s.z) + range * std::hypot(s.roll, s.pitch, s.yaw);
    const double first =
        std::max(config.min_distance, config.sigmas * (displacement + config.sensor_sigma));
    std::vector<double> distances;
    for (double d = first; d > config.min_distance; d /= 2.0) distances.push_back(d);
    distances.push_back(config.min_distance);
    for (const double d : distances) {
      // NOTE: a coarse stage pairs within `distance`, so a scan thinned to a quarter of it
      // guides it as well at far less cost.
      stages.push_back(
          {d, transform(guess_,
                        voxel_downsample(points_sensor, std::max(config.voxel_size, d / 4.0)))});
    }
    full_ = transform(guess_, voxel_downsample(points_sensor, config.voxel_size));
    // The scan's centroid and spread (world, at the guess), for judging degenerate directions.
    centroid_ = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points_sensor) centroid_ += p;
    centroid_ = guess_ * (centroid_ / static_cast<double>(points_sensor.size()));
    double spread = 0.0;
    for (const Eigen::Vector3d& p : points_sensor) {
      spread += (guess_ * p - centroid_).squaredNorm();
    }
    radius_ = std::max(std::sqrt(spread / static_cast<double>(points_sensor.size())), 0.01);
  }

  /// The starts: the guess, then the guess turned about the vertical through the sensor by plus
  /// and minus start_sigmas of the prior's yaw sigma.
  std::vector<Correction> starts() const {
    std::vector<Correction> out(1);
    const double k = config_.start_sigmas;
    if (k == 0.0) return out;
    for (const double sign : {-1.0, 1.0}) {
      Correction turned;
      turned.R = Eigen::AngleAxisd(sign * k * config_.prior.yaw, Eigen::Vector3d::UnitZ())
                     .toRotationMatrix();
      out.push_back(turned);
    }
    return out;
  }

  /// Gauss-Newton from each of `starts` (the guess first), stage by stage, on the robust
  /// point-to-plane cost plus the prior. Starts that reach the same pose in a stage (closer than
  /// the sensor's noise) go on as one. Each solution is scored at the end.
  std::vector<Solution> solve(const std::vector<Correction>& starts, int& iterations) const {
    // NOTE: the guess starts at the coarsest stage, which pairs across the prior's whole reach.
    // That smooths away what lies closer together (a row of like objects), so each further start
    // joins at the first stage that pairs within its own reach, half the turn between starts at
    // the scan's range: a basin the guess's start was led past is found there.
    const double reach = 0.5 * config_.start_sigmas * config_.prior.yaw * range_;
    std::size_t join = 0;
    while (join + 1 < stages.size() && stages[join].distance > reach) ++join;
    std::vector<Solution> solutions;
    for (const Correction& start : starts) {
      Solution& solution = solutions.emplace_back();
      solution.correction = start;
      solution.first_stage = solutions.size() == 1 ? 0 : join;
    }
    for (std::size_t i = 0; i < stages.size(); ++i) {
      std::vector<Solution> merged;
      for (Solution& solution : solutions) {
        if (i < solution.first_stage) {
          merged.push_back(solution);
          continue;
        }
        iterations += refine(stages[i], i + 1 == stages.size(), solution);
        const bool known = std::any_of(merged.begin(), merged.end(), [&](const Solution& other) {
          return separation(solution, other) < config_.sensor_sigma;
        });
        if (!known) merged.push_back(solution);
      }
      solutions = std::move(merged);
      if (i == join) prune(solutions);
    }
    for (Solution& solution : solutions) solution.score = score(solution.correction);
    return solutions;
  }

  /// Drops the solutions whose posterior cost on the last stage's pairing exceeds the lowest by
  /// more than prune_cost.
  void prune(std::vector<Solution>& solutions) const {
    if (solutions.size() < 2) return;
    std::vector<Score> scores;
    std::size_t most = 0;
    for (const Solution& solution : solutions) {
      scores.push_back(score(solution.correction));
      most = std::max(most, scores.back().correspondences);
    }
    const double share = independent_share(most, config_);
    double lowest = INFINITY;
    for (const Score& s : scores) lowest = std::min(lowest, cost(s, share));
    std::vector<Solution> kept;
    for (std::size_t k = 0; k < solutions.size(); ++k) {
      if (cost(scores[k], share) <= lowest + config_.prune_cost) kept.push_back(solutions[k]);
    }
    solutions = std::move(kept);
  }

  /// Gauss-Newton iterations of one stage from `solution`'s correction; returns how many.
  int refine(const Stage& stage, bool last, Solution& solution) const {
    Correction& correction = solution.correction;
    const double kernel = stage.distance / 3.0;
    // NOTE: in a coarse stage a pair's residual is the pose's own error more than the sensor's
    // noise. Weighed by the sensor alone, the data overruled the prior by (kernel /
    // sensor_sigma)^2 (~150^2 in the first stage) and Gauss-Newton strode into a neighbouring
    // basin; weighed by the kernel alone, the prior held a guess 70 mm off (3.5 sigma) short of
    // its own. The geometric mean of the two did neither on the measured runs.
    const double weight =
        last ? data_weight_ : 1.0 / std::max(kernel * config_.sensor_sigma, 1.0 / data_weight_);
    int iteration = 0;
    while (iteration < config_.max_iterations) {
      const std::vector<Pair> pairs =
          detail::pair_up(stage.points_world, correction, c_, map_, stage.distance);
      ++iteration;
      // Summed in point order, so the result does not depend on the thread count.
      Matrix6d H = Matrix6d::Zero();
      Vector6d g = Vector6d::Zero();
      const double share = independent_share(count(pairs), config_);
      for (const Pair& pair : pairs) {
        if (!pair.valid) continue;
        const double u = pair.residual / kernel;
        const double w = share * weight / ((1.0 + u * u) * (1.0 + u * u));  // Geman-McClure
        H += w * pair.jacobian * pair.jacobian.transpose();
        g += w * pair.residual * pair.jacobian;
      }
      const Matrix6d P = detail::constrained(H, correction.apply(centroid_, c_), c_ + correction.t,
                                             radius_, config_.degenerate_ratio);
      H = prior + P.transpose() * H * P;
      g = prior * correction.coordinates() + P.transpose() * g;
      const Vector6d dx = H.ldlt().solve(-g);
      // The sensor's position as the posterior knows it: the largest standard deviation.
      const Eigen::Matrix3d position = H.inverse().bottomRightCorner<3, 3>();
      solution.position_sigma = std::sqrt(
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(position).eigenvalues().maxCoeff());
      solution.constrained_directions = static_cast<int>(std::lround(P.trace()));
      const Eigen::Vector3d w = dx.head<3>();
      const Eigen::Matrix3d dR =
          w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                         : Eigen::Matrix3d::Identity();
      // The increment turns about the current sensor position c + t, which leaves t as is.
      correction.R = dR * correction.R;
      correction.t += dx.tail<3>();
      if (dx.norm() < config_.convergence) break;
    }
    return iteration;
  }

  /// `correction`'s fit on the last stage's pairing of the full-resolution (voxel_size) scan:
  /// robust point to plane, an unpaired point costing what a pair at the distance limit would.
  Score score(const Correction& correction) const {
    const std::vector<Pair> pairs =
        detail::pair_up(full_, correction, c_, map_, config_.min_distance);
    Score s;
    s.correspondences = count(pairs);
    const double kernel = config_.min_distance / 3.0;
    const double limit = 9.0 / (1.0 + 9.0);
    for (const Pair& pair : pairs) {
      const double u = pair.residual / kernel;
      s.robust += pair.valid ? u * u / (1.0 + u * u) : limit;  // Geman-McClure
    }
    const Vector6d x = correction.coordinates();
    s.prior = 0.5 * x.dot(prior * x);
    return s;
  }

  /// The posterior's cost of a fit whose pairs weigh `share` each.
  double cost(const Score& s, double share) const {
    const double kernel = config_.min_distance / 3.0;
    return 0.5 * share * data_weight_ * kernel * kernel * s.robust + s.prior;
  }

  /// How far apart two solutions put the scan: the sensor's shift, or the turn between them at
  /// the scan's radius, whichever is larger [m].
  double separation(const Solution& a, const Solution& b) const {
    const Eigen::AngleAxisd turn(a.correction.R * b.correction.R.transpose());
    return std::max((a.correction.t - b.correction.t).norm(), radius_ * turn.angle());
  }

  /// The pose `correction` makes of the guess.
  Eigen::Isometry3d pose(const Correction& correction) const {
    Eigen::Isometry3d solved = Eigen::Isometry3d::Identity();
    // NOTE: many small rotations drift from orthonormal by ~1e-16 each; project back.
    solved.linear() =
        Eigen::Quaterniond(correction.R * guess_.linear()).normalized().toRotationMatrix();
    solved.translation() = c_ + correction.t;
    return solved;
  }

  /// The scan's points at full resolution (voxel_size).
  std::size_t full_size() const { return full_.size(); }

  const Matrix6d prior;
  std::vector<Stage> stages;

 private:
  Eigen::Isometry3d guess_;
  Eigen::Vector3d c_;
  const VoxelMap& map_;
  const RegistrationConfig& config_;
  double data_weight_;
  PointCloud full_;
  Eigen::Vector3d centroid_;
  double radius_ = 0.0;
  double range_ = 0.0;  ///< [m] the scan's farthest point from the sensor
};

}  // namespace

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

  const Problem problem(points_sensor, T_world_sensor_guess, map, config);
  result.first_distance = problem.stages.front().distance;
  Solution best;
  bool ambiguous = false;  // another start reached a distinct pose at a cost as low
  run_with_threads(config.num_threads, [&] {
    const Score guessed = problem.score(Correction{});
    result.guess_correspondences = guessed.correspondences;
    // NOTE: Gauss-Newton finds the basin its start lies in. A guess turned by 2 sigma or more
    // can lie in a wrong one (a neighbouring object's face), which passes the check as easily
    // as the right one; the starts turned by +-start_sigmas x yaw sigma find the other basins,
    // the lowest posterior cost wins, and a rival as good but elsewhere makes the pose uncertain.
    const std::vector<Solution> solutions = problem.solve(problem.starts(), result.iterations);
    // NOTE: neighbouring points share their map points, normals and the scan's systematic
    // errors; every fit is weighed with the share of the most pairs any of them found, so that
    // their costs compare.
    std::size_t most = guessed.correspondences;
    for (const Solution& s : solutions) most = std::max(most, s.score.correspondences);
    const double share = independent_share(most, config);
    result.guess_cost = problem.cost(guessed, share);
    const auto cost = [&](const Solution& s) { return problem.cost(s.score, share); };
    best =
        *std::min_element(solutions.begin(), solutions.end(),
                          [&](const Solution& a, const Solution& b) { return cost(a) < cost(b); });
    result.cost = cost(best);
    // NOTE: further apart than the check lets the posterior be unsure of the position.
    ambiguous = std::any_of(solutions.begin(), solutions.end(), [&](const Solution& other) {
      return cost(other) < result.cost + config.ambiguity_cost &&
             problem.separation(other, best) > 2.0 * config.max_position_sigma;
    });
  });

  const Vector6d x = best.correction.coordinates();
  result.mahalanobis2 = x.dot(problem.prior * x);
  result.correspondences = best.score.correspondences;
  result.position_sigma = best.position_sigma;
  result.constrained_directions = best.constrained_directions;
  result.T_world_sensor_solved = problem.pose(best.correction);
  result.points = problem.full_size();
  if (result.correspondences < config.min_correspondences ||
      static_cast<double>(result.correspondences) <
          config.min_overlap * static_cast<double>(result.points)) {
    result.outcome = RegistrationOutcome::kTooFewMatches;
  } else if (result.mahalanobis2 > config.max_mahalanobis2) {
    result.outcome = RegistrationOutcome::kOutsidePrior;
  } else if (result.position_sigma > config.max_position_sigma || ambiguous) {
    result.outcome = RegistrationOutcome::kUncertain;
  } else if (!(result.cost < result.guess_cost)) {
    result.outcome = RegistrationOutcome::kWorseThanPrior;
  } else {
    result.outcome = RegistrationOutcome::kAccepted;
    result.T_world_sensor = result.T_world_sensor_solved;
  }
  return result;
}

void silence_pcl_console() { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }

}  // namespace vantage::perception
