#include "vantage/io/trajectory.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "vantage/io/atomic_file.hpp"
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
  std::ifstream in(path);
  if (!in) throw std::runtime_error(cat(path.string(), ": cannot open the trajectory"));
  static constexpr std::array<std::string_view, 8> kFields = {"timestamp", "tx", "ty", "tz",
                                                              "qx",        "qy", "qz", "qw"};
  std::vector<StampedPose> poses;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(cat(path.string(), ":", number, ": ", what));
    };
    std::istringstream tokens(line);
    std::string token;
    std::array<double, 8> v{};
    int n = 0;
    while (tokens >> token) {
      if (n == 0 && token.starts_with("#")) break;
      if (n == 8) fail("more than 8 fields (timestamp tx ty tz qx qy qz qw)");
      std::string_view text = token;
      if (text.starts_with("+")) text.remove_prefix(1);
      const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v[n]);
      if (ec != std::errc() || ptr != text.data() + text.size()) {
        fail(cat(kFields[n], " '", token, "' is not a number"));
      }
      if (std::isnan(v[n])) fail(cat(kFields[n], " is NaN"));
      if (!std::isfinite(v[n])) fail(cat(kFields[n], " is infinite"));
      ++n;
    }
    if (n == 0) continue;
    if (n != 8) fail(cat(n, " fields; a TUM pose has 8 (timestamp tx ty tz qx qy qz qw)"));
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
  if (in.bad()) throw std::runtime_error(cat(path.string(), ": read error"));
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

}  // namespace vantage
