#include "vantage/sim/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage::sim {

Eigen::AlignedBox3d TriangleMesh::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : vertices) box.extend(v);
  return box;
}

void TriangleMesh::validate(std::string_view what) const {
  if (triangles.empty()) throw std::invalid_argument(cat(what, ": the mesh has no triangle"));
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      throw std::invalid_argument(cat(what, ": vertex ", i, " is not finite"));
    }
  }
  const auto n = static_cast<long long>(vertices.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (triangles[i][c] < 0 || triangles[i][c] >= n) {
        throw std::invalid_argument(
            cat(what, ": triangle ", i, " refers to vertex ", triangles[i][c], " of ", n));
      }
    }
  }
}

void append(TriangleMesh& into, const TriangleMesh& mesh) {
  const auto offset = static_cast<int>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
  into.triangles.reserve(into.triangles.size() + mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    into.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T_world_local,
                         const Eigen::Vector3d& scale) {
  TriangleMesh out;
  out.triangles = mesh.triangles;
  out.vertices.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) {
    out.vertices.push_back(T_world_local * v.cwiseProduct(scale));
  }
  // NOTE: a mirroring scale turns the mesh inside out; flip the winding to keep normals outward.
  if (scale.prod() < 0.0) {
    for (Eigen::Vector3i& t : out.triangles) std::swap(t[1], t[2]);
  }
  return out;
}

TriangleMesh make_box(const Eigen::Vector3d& size) {
  TriangleMesh box;
  const double hx = size.x() / 2, hy = size.y() / 2, h = size.z();
  for (int k = 0; k < 8; ++k) {
    box.vertices.emplace_back((k & 1) ? hx : -hx, (k & 2) ? hy : -hy, (k & 4) ? h : 0.0);
  }
  // Outward winding (counter-clockwise seen from outside).
  box.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return box;
}

TriangleMesh make_cylinder(double radius, double height, int segments) {
  TriangleMesh cyl;
  cyl.vertices.emplace_back(0.0, 0.0, 0.0);     // 0: bottom centre
  cyl.vertices.emplace_back(0.0, 0.0, height);  // 1: top centre
  for (int k = 0; k < segments; ++k) {
    const double a = 2.0 * std::numbers::pi * k / segments;
    cyl.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
    cyl.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), height);
  }
  for (int k = 0; k < segments; ++k) {
    const int b0 = 2 + 2 * k, t0 = b0 + 1;
    const int b1 = 2 + 2 * ((k + 1) % segments), t1 = b1 + 1;
    cyl.triangles.emplace_back(0, b1, b0);
    cyl.triangles.emplace_back(1, t0, t1);
    cyl.triangles.emplace_back(b0, b1, t1);
    cyl.triangles.emplace_back(b0, t1, t0);
  }
  return cyl;
}

Eigen::AlignedBox3d Shape::bounds() const {
  if (sphere) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(sphere->radius);
    return {sphere->center - r, sphere->center + r};
  }
  return mesh_world.bounds();
}

std::vector<Eigen::Vector2d> top_outline(const Shape& shape) {
  std::vector<Eigen::Vector2d> points;
  if (shape.sphere) {
    for (int k = 0; k < 32; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 32;
      // NOTE: the polygon circumscribes the circle, so the outline never cuts into the sphere.
      const double r = shape.sphere->radius / std::cos(std::numbers::pi / 32);
      points.push_back(shape.sphere->center.head<2>() +
                       r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return points;
  }
  for (const Eigen::Vector3d& v : shape.mesh_world.vertices) points.push_back(v.head<2>());
  // Andrew's monotone chain.
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const Eigen::Vector2d& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace vantage::sim
