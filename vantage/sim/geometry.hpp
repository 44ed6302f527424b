#pragma once
/// @file
/// The solid geometry of a simulated world: closed triangle meshes and exact spheres, in the
/// world frame.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vantage::sim {

/// A triangle mesh; the triangles index `vertices` [m].
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;

  bool empty() const { return triangles.empty(); }
  /// Box around the vertices; empty for an empty mesh [m].
  Eigen::AlignedBox3d bounds() const;
  /// Throws std::invalid_argument naming `what` when the mesh has no triangle, a non-finite
  /// vertex or an index out of range.
  void validate(std::string_view what) const;
};

/// Appends `mesh` to `into`, re-indexing its triangles.
void append(TriangleMesh& into, const TriangleMesh& mesh);

/// The mesh with each vertex scaled per axis, then moved by T_world_local: v' = T * (s .* v).
TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T_world_local,
                         const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

/// A box of `size` (x, y, z) [m] whose local origin is the centre of its bottom face.
TriangleMesh make_box(const Eigen::Vector3d& size);

/// A closed cylinder (a prism of `segments` sides inscribed in the circle) with its axis along
/// local z, its local origin at the centre of its bottom face [m].
TriangleMesh make_cylinder(double radius, double height, int segments);

/// An exact sphere [m].
struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// One solid of the world: a closed triangle mesh or an exact sphere.
struct Shape {
  std::string name;         ///< where it came from, e.g. "objects[3] (bunny)"
  std::string kind;         ///< box, cylinder, sphere, mesh, table, floor, wall, desk, chair, ...
  TriangleMesh mesh_world;  ///< empty for a sphere [m]
  std::optional<Sphere> sphere;  ///< set for a sphere [m]

  /// Box around the solid [m].
  Eigen::AlignedBox3d bounds() const;
};

/// The convex hull of a shape seen from above (its projection on the x-y plane), counter-clockwise
/// [m]. A sphere gives a 32-gon around its circle.
std::vector<Eigen::Vector2d> top_outline(const Shape& shape);

}  // namespace vantage::sim
