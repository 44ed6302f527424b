// Single objects on a view sphere (object_scene.hpp, docs/objects.md).

#include "vantage/sim/object_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vantage/sim/builtin_models.hpp"
#include "vantage/sim/furniture.hpp"
#include "vantage/sim/mesh_io.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

/// Cells of margin around the objects' bounding sphere, so that its surface cells have
/// neighbours inside the grid.
constexpr double kMarginCells = 2.0;

bool positive_finite(double v) { return v > 0.0 && std::isfinite(v); }

TriangleMesh read_object_mesh(const std::string& mesh, const std::filesystem::path& base_dir) {
  if (is_builtin_model(mesh)) return load_builtin_model(mesh);
  std::filesystem::path path = mesh;
  if (path.is_relative() && !base_dir.empty()) path = base_dir / path;
  return load_mesh(path);
}

}  // namespace

void ObjectProtocol::validate() const {
  if (!positive_finite(object_radius) || object_radius > kMaxWorldCoordinate) {
    throw std::invalid_argument(cat("object.radius must be > 0 m and at most ", kMaxWorldCoordinate,
                                    ", got ", object_radius));
  }
  if (!positive_finite(view_radius) || view_radius > kMaxWorldCoordinate) {
    throw std::invalid_argument(cat("object.view_radius must be > 0 m, got ", view_radius));
  }
  if (!(view_radius > object_radius)) {
    throw std::invalid_argument(cat("object.view_radius (", view_radius,
                                    " m) must exceed the object's radius (", object_radius,
                                    " m): the views lie outside the object"));
  }
  if (views < 1 || static_cast<std::uint64_t>(views) > kMaxCandidateViews) {
    throw std::invalid_argument(
        cat("object.views must lie in [1, ", kMaxCandidateViews, "], got ", views));
  }
  if (!positive_finite(resolution) || resolution > object_radius) {
    throw std::invalid_argument(
        cat("object.resolution must be > 0 m and at most the object's "
            "radius (",
            object_radius, " m), got ", resolution));
  }
  const SensorConfig s = builtin_sensor(sensor);  // throws naming the sensors there are
  if (view_radius - object_radius < s.fov.min_range) {
    throw std::invalid_argument(
        cat("object.view_radius (", view_radius, " m) leaves the object nearer than the ", sensor,
            "'s minimum range (", s.fov.min_range, " m): give a view radius of at least ",
            object_radius + s.fov.min_range, " m"));
  }
}

TriangleMesh fit_to_sphere(const TriangleMesh& mesh, double radius) {
  if (mesh.vertices.empty()) throw std::invalid_argument("fit_to_sphere: the mesh is empty");
  if (!positive_finite(radius)) {
    throw std::invalid_argument(cat("fit_to_sphere: radius must be > 0 m, got ", radius));
  }
  const Eigen::Vector3d center = mesh.bounds().center();
  double farthest = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) farthest = std::max(farthest, (v - center).norm());
  if (!(farthest > 0.0)) {
    throw std::invalid_argument("fit_to_sphere: every vertex lies at one point");
  }
  const double s = radius / farthest;
  TriangleMesh fitted = mesh;
  for (Eigen::Vector3d& v : fitted.vertices) v = s * (v - center);
  return fitted;
}

std::vector<int> spread_start_order(std::span<const Eigen::Isometry3d> views,
                                    const Eigen::Vector3d& center) {
  std::vector<int> order;
  if (views.empty()) return order;
  std::vector<Eigen::Vector3d> directions;
  for (const Eigen::Isometry3d& v : views) {
    directions.push_back((v.translation() - center).normalized());
  }
  // NOTE: the first start is the view nearest +x; each next one the farthest (by angle) from
  // every start before it, ties to the lower index, so that any first few starts are spread.
  std::size_t first = 0;
  for (std::size_t i = 1; i < directions.size(); ++i) {
    if (directions[i].x() > directions[first].x()) first = i;
  }
  std::vector<double> nearest(directions.size(), std::numeric_limits<double>::infinity());
  std::vector<bool> used(directions.size(), false);
  std::size_t next = first;
  for (std::size_t k = 0; k < directions.size(); ++k) {
    order.push_back(static_cast<int>(next));
    used[next] = true;
    std::size_t best = next;
    double best_distance = -1.0;
    for (std::size_t i = 0; i < directions.size(); ++i) {
      if (used[i]) continue;
      nearest[i] = std::min(nearest[i], (directions[i] - directions[next]).norm());
      if (nearest[i] > best_distance) {
        best = i;
        best_distance = nearest[i];
      }
    }
    next = best;
  }
  return order;
}

Scene object_scene(std::string name, std::span<const ObjectPlacement> objects,
                   const ObjectProtocol& protocol, const std::filesystem::path& base_dir) {
  protocol.validate();
  if (objects.empty()) throw std::invalid_argument("an object scene needs at least one object");
  if (objects.size() > kMaxSceneObjects) {
    throw std::invalid_argument(
        cat("an object scene holds at most ", kMaxSceneObjects, " objects, got ", objects.size()));
  }
  Scene scene;
  scene.name = std::move(name);
  scene.source = "object protocol";
  scene.kind = SceneKind::kObject;
  scene.sensor = builtin_sensor(protocol.sensor);
  // The objects' bounding spheres, and the sphere around them all.
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ObjectPlacement& o = objects[i];
    const double r = o.radius > 0.0 ? o.radius : protocol.object_radius;
    if (!positive_finite(r) || !o.pose.matrix().allFinite() ||
        !(o.pose.translation().array().abs() <= kMaxWorldCoordinate).all()) {
      throw std::invalid_argument(cat("objects[", i, "] (", o.mesh,
                                      "): its radius and pose must be finite, the radius > 0 m"));
    }
    TriangleMesh mesh;
    try {
      mesh = fit_to_sphere(read_object_mesh(o.mesh, base_dir), r);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(cat("objects[", i, "] (", o.mesh, "): ", e.what()));
    }
    scene.shapes.push_back(
        mesh_shape(cat("objects[", i, "] (", o.mesh, ")"), "mesh", transformed(mesh, o.pose)));
    box.extend(o.pose.translation() - Eigen::Vector3d::Constant(r));
    box.extend(o.pose.translation() + Eigen::Vector3d::Constant(r));
  }
  const Eigen::Vector3d center = box.center();
  double reach = 0.0;  // the radius of the sphere about `center` that holds every object
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const double r = objects[i].radius > 0.0 ? objects[i].radius : protocol.object_radius;
    reach = std::max(reach, (objects[i].pose.translation() - center).norm() + r);
  }
  const double res = protocol.resolution;
  const double half = reach + kMarginCells * res;
  const int n = static_cast<int>(std::ceil(2.0 * half / res));
  scene.grid.resolution = res;
  scene.grid.dims = Index3(n, n, n);
  scene.grid.origin = center - Eigen::Vector3d::Constant(0.5 * n * res);
  scene.grid.validate();
  // NOTE: the sensor keeps the protocol's distance from the objects' bounding sphere, so a
  // cluster's sphere grows with it.
  const SphereConfig sphere = object_view_sphere(
      center, protocol.view_radius - protocol.object_radius + reach, protocol.views);
  scene.view_sphere = sphere;
  scene.mount.aims_at_target = true;
  scene.mount.target = center;
  scene.mount.height = center.z();
  const std::vector<Eigen::Isometry3d> views = sphere_poses(sphere);
  for (const int i : spread_start_order(views, center)) {
    scene.start_poses.push_back(views[static_cast<std::size_t>(i)]);
  }
  scene.floor_area =
      Eigen::AlignedBox2d(scene.grid.origin.head<2>(), scene.grid.max_corner().head<2>());
  return scene;
}

Scene single_object_scene(const std::string& mesh, const ObjectProtocol& protocol) {
  const std::string name =
      is_builtin_model(mesh) ? mesh : std::filesystem::path(mesh).stem().string();
  const ObjectPlacement object{mesh, Eigen::Isometry3d::Identity(), 0.0};
  Scene scene = object_scene(name.empty() ? std::string("object") : name,
                             std::span<const ObjectPlacement>(&object, 1), protocol);
  scene.source = mesh;
  return scene;
}

}  // namespace vantage::sim
