#include "vantage/views/travel.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vantage {

double TravelRule::operator()(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  switch (kind) {
    case Kind::kStraightLine:
      return (to - from).norm();
    case Kind::kRingWalk: {
      const Eigen::Vector2d a = from.head<2>() - center.head<2>();
      const Eigen::Vector2d b = to.head<2>() - center.head<2>();
      double turn = std::abs(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()));
      if (turn > std::numbers::pi) turn = 2.0 * std::numbers::pi - turn;
      return radius * turn + std::abs(b.norm() - a.norm());
    }
    case Kind::kSphereArc: {
      const Eigen::Vector3d a = from - center;
      const Eigen::Vector3d b = to - center;
      const double na = a.norm(), nb = b.norm();
      if (na == 0.0 || nb == 0.0) return std::abs(nb - na);
      // NOTE: atan2 of the cross and dot products keeps the angle exact near 0 and pi, where
      // acos of the normalised dot product loses digits.
      const double turn = std::atan2(a.cross(b).norm(), a.dot(b));
      return radius * turn + std::abs(nb - na);
    }
  }
  return 0.0;
}

const char* TravelRule::describe() const {
  switch (kind) {
    case Kind::kStraightLine:
      return "the sensor's straight-line path between views [m]";
    case Kind::kRingWalk:
      return "the walk around the table: the arc between bearings at the ring's radius plus the "
             "change in distance from its centre [m]";
    case Kind::kSphereArc:
      return "the path on the view sphere: the great-circle arc between views at the sphere's "
             "radius plus the change in distance from its centre [m]";
  }
  return "";
}

}  // namespace vantage
