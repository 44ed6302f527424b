#include "vantage/io/trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

std::string rigid_transform_problem(const Eigen::Matrix4d& m) {
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (std::isnan(m(r, c))) return cat("entry [", r, "][", c, "] is NaN");
      if (!std::isfinite(m(r, c))) return cat("entry [", r, "][", c, "] is infinite");
    }
  }
  const Eigen::RowVector4d bottom = m.row(3);
  if ((bottom - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    return cat("bottom row is [", bottom(0), " ", bottom(1), " ", bottom(2), " ", bottom(3),
               "], not [0 0 0 1]");
  }
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  const double deviation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kRotationTolerance) {
    return cat("rotation is not orthonormal: max |R^T R - I| = ", deviation, " > ",
               kRotationTolerance);
  }
  if (R.determinant() < 0.0) return "rotation is a reflection (det R = -1), not a rotation";
  return {};
}

std::vector<StampedPose> read_tum_trajectory(const fs::path& path) {
  std::string text;
  try {
    text = read_input_file(path, InputKind::kPoses);
  } catch (const FormatError& e) {
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
  static constexpr std::array<std::string_view, 8> kFields = {"timestamp", "tx", "ty", "tz",
                                                              "qx",        "qy", "qz", "qw"};
  std::vector<StampedPose> poses;
  Lines lines(text);
  while (const auto line = lines.next()) {
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(cat(path.string(), ":", lines.number(), ": ", what));
    };
    std::array<double, 8> v{};
    int n = 0;
    for (const std::string_view token : split(*line)) {
      if (n == 0 && token.starts_with("#")) break;
      if (n == 8) fail("more than 8 fields (timestamp tx ty tz qx qy qz qw)");
      const std::optional<double> value = parse_number(token);
      if (!value) fail(cat(kFields[n], " '", printable(token, 40), "' is not a number"));
      if (std::isnan(*value)) fail(cat(kFields[n], " is NaN"));
      if (!std::isfinite(*value)) fail(cat(kFields[n], " is infinite"));
      v[n++] = *value;
    }
    if (n == 0) continue;
    if (n != 8) fail(cat(n, " fields; a TUM pose has 8 (timestamp tx ty tz qx qy qz qw)"));
    if (poses.size() >= kMaxCandidateViews) {
      fail(cat("more than ", kMaxCandidateViews,
               " poses, the most a pose file may hold (docs/robustness.md, \"Limits\")"));
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    const double norm = q.norm();
    if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
      fail(cat("quaternion norm ", norm, " is not 1 (within ", kQuaternionNormTolerance,
               "): not a rotation"));
    }
    q.normalize();
    StampedPose pose;
    pose.stamp = v[0];
    pose.T_world_frame.setIdentity();
    pose.T_world_frame.linear() = q.toRotationMatrix();
    pose.T_world_frame.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    poses.push_back(pose);
  }
  return poses;
}

void write_tum_trajectory(const fs::path& path, const std::vector<StampedPose>& poses) {
  write_atomically(path, [&](std::ostream& out) {
    out.precision(std::numeric_limits<double>::max_digits10);
    out << "# timestamp tx ty tz qx qy qz qw\n";
    for (const StampedPose& pose : poses) {
      const Eigen::Vector3d t = pose.T_world_frame.translation();
      const Eigen::Quaterniond q(pose.T_world_frame.rotation());
      out << pose.stamp << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' '
          << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
    }
  });
}

std::optional<Eigen::Isometry3d> interpolate_pose(const std::vector<StampedPose>& poses,
                                                  double stamp, double max_time_difference) {
  for (std::size_t i = 1; i < poses.size(); ++i) {
    if (!(poses[i].stamp > poses[i - 1].stamp)) {
      throw std::invalid_argument(cat("pose stamps must increase: pose ", i, " at ", poses[i].stamp,
                                      " s follows ", poses[i - 1].stamp, " s"));
    }
  }
  const auto after = std::lower_bound(poses.begin(), poses.end(), stamp,
                                      [](const StampedPose& p, double t) { return p.stamp < t; });
  if (after != poses.end() && after->stamp == stamp) return after->T_world_frame;
  if (after == poses.begin() || after == poses.end()) return std::nullopt;
  const StampedPose& a = *std::prev(after);
  const StampedPose& b = *after;
  if (stamp - a.stamp > max_time_difference || b.stamp - stamp > max_time_difference) {
    return std::nullopt;
  }
  const double s = (stamp - a.stamp) / (b.stamp - a.stamp);
  const Eigen::Quaterniond qa(a.T_world_frame.linear()), qb(b.T_world_frame.linear());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = qa.slerp(s, qb).normalized().toRotationMatrix();
  T.translation() = (1.0 - s) * a.T_world_frame.translation() + s * b.T_world_frame.translation();
  return T;
}

}  // namespace vantage
