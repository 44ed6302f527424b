#include "vantage/views/ring.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/map/grid_spec.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_set.hpp"
#include "vantage/views/detail/placement.hpp"

namespace vantage {

void RingConfig::validate() const {
  detail::validate_placement("ring", center, radius);
  if (!(std::abs(height) <= kMaxWorldCoordinate)) {
    throw std::invalid_argument(cat("ring.height must lie in [-", kMaxWorldCoordinate, ", ",
                                    kMaxWorldCoordinate, "] m, got ", height));
  }
  if (positions < 1) {
    throw std::invalid_argument(cat("ring.positions must be >= 1, got ", positions));
  }
  if (yaw_offsets.empty()) throw std::invalid_argument("ring.yaw_offsets must not be empty");
  for (const double yaw : yaw_offsets) {
    if (!std::isfinite(yaw)) throw std::invalid_argument("ring.yaw_offsets must be finite");
  }
  // NOTE: the one limit of candidate views (vantage/util/limits.hpp), for a scene's ring, plan's
  // --views and Python's ring_candidates alike.
  const double views = static_cast<double>(positions) * static_cast<double>(yaw_offsets.size());
  if (views > static_cast<double>(kMaxCandidateViews)) {
    throw std::invalid_argument(cat("ring.positions (", positions, ") x ring.yaw_offsets (",
                                    yaw_offsets.size(), ") make ", views, " views, more than the ",
                                    kMaxCandidateViews, " a decision scores"));
  }
}

RingConfig default_ring(const Eigen::AlignedBox3d& roi) {
  RingConfig ring;
  ring.center = roi.center();
  ring.radius = std::max(1.0, 1.5 * 0.5 * roi.sizes().head<2>().norm());
  ring.height = roi.max().z() + 0.3;
  ring.positions = 10;
  return ring;
}

Eigen::Isometry3d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d x = target - eye;
  if (x.norm() < 1e-12) throw std::invalid_argument("look_at: eye and target coincide");
  const Eigen::Vector3d forward = x.normalized();
  Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(forward);
  if (left.norm() < 1e-9) left = Eigen::Vector3d::UnitY();  // looking straight up or down
  left.normalize();
  Eigen::Matrix3d R;
  R.col(0) = forward;
  R.col(1) = left;
  R.col(2) = forward.cross(left);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = eye;
  return T;
}

std::vector<Eigen::Isometry3d> ring_poses(const RingConfig& config) {
  config.validate();
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(static_cast<std::size_t>(config.positions) * config.yaw_offsets.size());
  for (int k = 0; k < config.positions; ++k) {
    const double bearing = config.start_angle + 2.0 * std::numbers::pi * k / config.positions;
    const Eigen::Vector3d eye(config.center.x() + config.radius * std::cos(bearing),
                              config.center.y() + config.radius * std::sin(bearing), config.height);
    const Eigen::Isometry3d centred = look_at(eye, config.center);
    for (const double yaw : config.yaw_offsets) {
      Eigen::Isometry3d pose = centred;
      pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * centred.linear();
      poses.push_back(pose);
    }
  }
  return poses;
}

std::vector<Frustum> make_views(const std::vector<Eigen::Isometry3d>& poses, const SensorFov& fov) {
  std::vector<Frustum> views;
  views.reserve(poses.size());
  for (const Eigen::Isometry3d& pose : poses) views.emplace_back(pose, fov);
  return views;
}

PlacedViews ring_candidates(const CandidateSite& site, const CandidateParams& params) {
  RingConfig ring = site.ring ? *site.ring : default_ring(site.region);
  if (params.radius > 0.0) ring.radius = params.radius;
  if (!std::isnan(params.height)) ring.height = params.height;
  if (params.views > 0) {
    const int offsets = static_cast<int>(ring.yaw_offsets.size());
    if (params.views % offsets != 0) {
      throw std::invalid_argument(cat("ring: views (", params.views, ") must be a multiple of its ",
                                      offsets, " yaw offsets"));
    }
    ring.positions = params.views / offsets;
  }
  return {.poses = ring_poses(ring),
          .travel = {TravelRule::Kind::kRingWalk, ring.center, ring.radius}};
}

}  // namespace vantage
