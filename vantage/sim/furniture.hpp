#pragma once
/// @file
/// The solids a scene file describes by their sizes: desks, tables, chairs, shelves, and walls
/// with door gaps, as triangle meshes in a local frame whose origin lies on the floor at the
/// centre of the footprint.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vantage/sim/geometry.hpp"

namespace vantage::sim {

/// A solid called `name`, of `kind` ("desk", "wall", ...), made of `mesh` [m].
Shape mesh_shape(std::string name, std::string kind, TriangleMesh mesh);

/// A desk or table of `size` [m]: a top and four legs.
TriangleMesh make_desk(const Eigen::Vector3d& size);
/// A chair of `size` [m]: four legs, a seat at half its height, and a back on its +y side.
TriangleMesh make_chair(const Eigen::Vector3d& size);
/// A bookshelf of `size` [m] open to -y: sides, back, bottom, top and a board every ~0.35 m.
TriangleMesh make_shelf(const Eigen::Vector3d& size);
/// The table of a table-top scene: `size` (x, y) and `height` [m], a top `top` thick and legs
/// `leg` wide [m].
TriangleMesh make_table(const Eigen::Vector2d& size, double height, double top, double leg);

/// A wall's centre line on the floor (x, y) [m], and the name its pieces get.
struct WallSegment {
  Eigen::Vector2d a, b;
  std::string name;
};

/// A gap of `width` [m] in every wall whose centre line passes within a wall's thickness of `at`.
struct Door {
  Eigen::Vector2d at;
  double width = 0.0;
};

/// Appends to `shapes` walls of `height` and `thickness` [m] along `segments`, with the doors'
/// gaps cut out; the outer ends reach half a thickness further, so that walls meeting at a
/// corner close it. Returns, for each door, whether it cut any wall.
std::vector<bool> build_walls(const std::vector<WallSegment>& segments, double height,
                              double thickness, const std::vector<Door>& doors,
                              std::vector<Shape>& shapes);

}  // namespace vantage::sim
