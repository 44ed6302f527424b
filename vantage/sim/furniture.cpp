#include "vantage/sim/furniture.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "vantage/sim/scene.hpp"

namespace vantage::sim {
namespace {

/// Pieces of a box, placed in a furniture item's local frame (origin on the floor, at the centre
/// of its footprint).
void add_box(TriangleMesh& into, const Eigen::Vector3d& size, const Eigen::Vector3d& base) {
  append(into, transformed(make_box(size), Eigen::Isometry3d(Eigen::Translation3d(base))));
}

}  // namespace

Shape mesh_shape(std::string name, std::string kind, TriangleMesh mesh) {
  Shape s;
  s.name = std::move(name);
  s.kind = std::move(kind);
  s.mesh_world = std::move(mesh);
  return s;
}

TriangleMesh make_desk(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double top = std::min(0.03, size.z() / 4),
               leg = std::min({0.05, size.x() / 4, size.y() / 4});
  add_box(m, {size.x(), size.y(), top}, {0, 0, size.z() - top});
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(m, {leg, leg, size.z() - top},
              {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
    }
  }
  return m;
}

TriangleMesh make_chair(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double seat_z = size.z() / 2, seat = 0.04,
               leg = std::min({0.04, size.x() / 4, size.y() / 4});
  add_box(m, {size.x(), size.y(), seat}, {0, 0, seat_z - seat});
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(m, {leg, leg, seat_z - seat},
              {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
    }
  }
  add_box(m, {size.x(), leg, size.z() - seat_z}, {0, (size.y() - leg) / 2, seat_z});
  return m;
}

TriangleMesh make_shelf(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const double t = std::min({0.02, size.x() / 6, size.y() / 6, size.z() / 6});
  add_box(m, {t, size.y(), size.z()}, {-(size.x() - t) / 2, 0, 0});
  add_box(m, {t, size.y(), size.z()}, {(size.x() - t) / 2, 0, 0});
  add_box(m, {size.x() - 2 * t, t, size.z()}, {0, (size.y() - t) / 2, 0});
  const int boards = std::max(2, static_cast<int>(std::lround(size.z() / 0.35)) + 1);
  for (int k = 0; k < boards; ++k) {
    const double z = (size.z() - t) * k / (boards - 1);
    add_box(m, {size.x() - 2 * t, size.y() - t, t}, {0, -t / 2, z});
  }
  return m;
}

TriangleMesh make_table(const Eigen::Vector2d& size, double height, double top, double leg) {
  TriangleMesh m;
  add_box(m, {size.x(), size.y(), top}, {0, 0, height - top});
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      add_box(m, {leg, leg, height - top},
              {sx * (size.x() - leg) / 2, sy * (size.y() - leg) / 2, 0.0});
    }
  }
  return m;
}

std::vector<bool> build_walls(const std::vector<WallSegment>& segments, double height,
                              double thickness, const std::vector<Door>& doors,
                              std::vector<Shape>& shapes) {
  std::vector<bool> door_used(doors.size(), false);
  for (const WallSegment& wall : segments) {
    const Eigen::Vector2d axis = wall.b - wall.a;
    const double length = axis.norm();
    const Eigen::Vector2d dir = axis / length;
    // Pieces as [s0, s1] along the centre line; the outer ends reach half a thickness further so
    // that walls meeting at a corner close it.
    std::vector<std::pair<double, double>> pieces = {{-thickness / 2, length + thickness / 2}};
    for (std::size_t d = 0; d < doors.size(); ++d) {
      const auto& [at, width] = doors[d];
      const Eigen::Vector2d rel = at - wall.a;
      const double s = rel.dot(dir);
      const double off = std::abs(rel.x() * dir.y() - rel.y() * dir.x());
      if (off > thickness || s < 0.0 || s > length) continue;
      door_used[d] = true;
      std::vector<std::pair<double, double>> cut;
      for (const auto& [s0, s1] : pieces) {
        if (s - width / 2 > s0) cut.emplace_back(s0, std::min(s1, s - width / 2));
        if (s + width / 2 < s1) cut.emplace_back(std::max(s0, s + width / 2), s1);
      }
      pieces = cut;
    }
    const double yaw = std::atan2(dir.y(), dir.x());
    for (const auto& [s0, s1] : pieces) {
      if (s1 - s0 < 1e-6) continue;
      const Eigen::Vector2d mid = wall.a + dir * (s0 + s1) / 2;
      const Eigen::Isometry3d T = pose_from_xyz_rpy({mid.x(), mid.y(), 0.0}, {0, 0, yaw});
      shapes.push_back(
          mesh_shape(wall.name, "wall", transformed(make_box({s1 - s0, thickness, height}), T)));
    }
  }
  return door_used;
}

}  // namespace vantage::sim
