#include "vantage/views/travel.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vantage/util/text.hpp"

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

namespace {

/// The angle from the 2-D direction `a` to `b`, in (-pi, pi] [rad].
double signed_turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

/// A unit vector perpendicular to `a` (nonzero).
Eigen::Vector3d perpendicular(const Eigen::Vector3d& a) {
  const Eigen::Vector3d axis =
      std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return a.cross(axis).normalized();
}

}  // namespace

std::vector<Eigen::Vector3d> TravelRule::path(const Eigen::Vector3d& from,
                                              const Eigen::Vector3d& to, double step) const {
  if (!(step > 0.0)) {
    throw std::invalid_argument(cat("travel path: step must be > 0 m, got ", step));
  }
  const double length = (*this)(from, to);
  const int pieces = std::max(1, static_cast<int>(std::ceil(length / step)));
  std::vector<Eigen::Vector3d> points{from};
  const auto along = [&](auto&& at) {
    for (int i = 1; i < pieces; ++i) points.push_back(at(static_cast<double>(i) / pieces));
  };
  const auto segment = [&] {
    along([&](double t) { return Eigen::Vector3d(from + t * (to - from)); });
  };
  if (kind == Kind::kStraightLine) {
    segment();
  } else if (kind == Kind::kRingWalk) {
    const Eigen::Vector2d a = from.head<2>() - center.head<2>();
    const Eigen::Vector2d b = to.head<2>() - center.head<2>();
    if (a.norm() > 0.0 && b.norm() > 0.0) {
      const double turn = signed_turn(a, b), bearing = std::atan2(a.y(), a.x());
      along([&](double t) {
        const double angle = bearing + t * turn;
        const double r = a.norm() + t * (b.norm() - a.norm());
        return Eigen::Vector3d(center.x() + r * std::cos(angle), center.y() + r * std::sin(angle),
                               from.z() + t * (to.z() - from.z()));
      });
    } else {
      segment();
    }
  } else if (kind == Kind::kSphereArc) {
    const Eigen::Vector3d a = from - center, b = to - center;
    const double na = a.norm(), nb = b.norm();
    if (na > 0.0 && nb > 0.0) {
      const Eigen::Vector3d normal = a.cross(b);
      const double turn = std::atan2(normal.norm(), a.dot(b));
      // NOTE: opposite views have no one great circle; any through both will do.
      const Eigen::Vector3d axis =
          normal.norm() > 1e-12 * na * nb ? normal.normalized() : perpendicular(a);
      along([&](double t) {
        const Eigen::Vector3d direction =
            Eigen::AngleAxisd(t * turn, axis) * Eigen::Vector3d(a / na);
        return Eigen::Vector3d(center + (na + t * (nb - na)) * direction);
      });
    } else {
      segment();
    }
  }
  points.push_back(to);
  return points;
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
