#pragma once
/// @file
/// Single objects on a view sphere: the field's protocol (SCVP, MA-SCVP, PB-NBV; docs/objects.md)
/// as a scene. Each object is read from a mesh file (PLY, OBJ, OFF, STL) or named as a built-in
/// model, centred on its bounding sphere and scaled so that the sphere has the protocol's radius,
/// then placed floating (no table, no floor: every side can be seen); the candidate views are
/// spread evenly over a sphere around the objects, each looking at their centre, and the sensor
/// travels on that sphere. The same builder makes a user's own cluster of objects a scene (an
/// object file, `kind: object`, names several meshes with their poses).

#include <Eigen/Geometry>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "vantage/sim/scene.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::sim {

/// The protocol's sizes, as SCVP's and MA-SCVP's simulators set them (docs/objects.md).
struct ObjectProtocol {
  double object_radius = 0.1;  ///< each object's bounding sphere is scaled to this radius [m]
  /// The view sphere's radius about the objects' centre: the Kinect's 0.5 m minimum range plus
  /// the object, so that no part of it is too near [m].
  double view_radius = 0.7;
  int views = kObjectViews;       ///< candidate views on the sphere (32, as SCVP and MA-SCVP)
  double resolution = 0.005;      ///< the grid's cell, 1/40 of an object's width by default [m]
  std::string sensor = "kinect";  ///< a built-in sensor (sim/sensor.hpp)

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// One object of an object scene.
struct ObjectPlacement {
  std::string mesh;  ///< a mesh file's path, or a built-in model's name (bunny, dragon, teapot)
  /// Where its bounding sphere's centre goes and how it is turned (T_world_object) [m].
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  double radius = 0.0;  ///< its bounding sphere's radius [m]; 0: the protocol's object_radius
};

/// The mesh centred on its bounding sphere and scaled to `radius`. The sphere is the one about
/// the centre of the mesh's bounding box through its farthest vertex (not the smallest enclosing
/// sphere, but the same for every tool that reads the box). Throws std::invalid_argument for an
/// empty mesh or a non-positive radius.
TriangleMesh fit_to_sphere(const TriangleMesh& mesh, double radius);

/// The scene of `objects` under `protocol`: grid, shapes, sensor, the view sphere as its
/// candidates and start poses (the sphere's views ordered so that the first few are spread:
/// each the farthest from those before it, from the view nearest +x). `base_dir` resolves
/// relative mesh paths. Throws std::invalid_argument naming the object for a bad placement and
/// std::runtime_error naming the file for a mesh that cannot be read.
Scene object_scene(std::string name, std::span<const ObjectPlacement> objects,
                   const ObjectProtocol& protocol, const std::filesystem::path& base_dir = {});

/// A single mesh under the protocol: object_scene with one object at the origin, named after the
/// file's stem (or the model).
Scene single_object_scene(const std::string& mesh, const ObjectProtocol& protocol = {});

/// Whether load_scene reads `name_or_path` as a single object: a built-in model's name (bunny,
/// dragon, teapot) or a path ending in .ply, .obj, .off or .stl (any case).
bool is_object_source(const std::string& name_or_path);

/// load_scene (scene.hpp), with a single object (is_object_source) placed under `objects`.
Scene load_scene(const std::string& name_or_path, const ObjectProtocol& objects);

/// The view sphere's views in start order: index i of the result is the view index of start i
/// (see object_scene).
std::vector<int> spread_start_order(std::span<const Eigen::Isometry3d> views,
                                    const Eigen::Vector3d& center);

}  // namespace vantage::sim
