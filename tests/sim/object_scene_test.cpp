// Single objects on a view sphere (vantage/sim/object_scene.hpp): the protocol's placement, the
// starts' spread, the object file, and a mesh path read as a scene.

#include "vantage/sim/object_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "vantage/sim/scene.hpp"

namespace vantage::sim {
namespace {

namespace fs = std::filesystem;

/// A box of 0.4 x 0.2 x 0.1 units, off the origin, as an OBJ file (our own writer: assimp reads
/// it as a user's file).
fs::path write_box_obj(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "vantage-object-scene-test";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream out(path);
  const double x0 = 3, x1 = 3.4, y0 = -1, y1 = -0.8, z0 = 2, z1 = 2.1;
  for (const double x : {x0, x1}) {
    for (const double y : {y0, y1}) {
      for (const double z : {z0, z1}) out << "v " << x << ' ' << y << ' ' << z << '\n';
    }
  }
  // Vertex k is (x, y, z) with bits (x, y, z) = (k & 4, k & 2, k & 1), 1-based in OBJ.
  out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return path;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(ObjectScene, AMeshIsCentredAndScaledToItsBoundingSphere) {
  TriangleMesh mesh;
  mesh.vertices = {{3, -1, 2}, {3.4, -1, 2}, {3, -0.8, 2.1}};
  mesh.triangles = {{0, 1, 2}};
  const TriangleMesh fitted = fit_to_sphere(mesh, 0.1);
  double farthest = 0.0;
  for (const Eigen::Vector3d& v : fitted.vertices) farthest = std::max(farthest, v.norm());
  EXPECT_NEAR(farthest, 0.1, 1e-12);
  EXPECT_LT(fitted.bounds().center().norm(), 1e-12);
  EXPECT_THROW(fit_to_sphere(TriangleMesh{}, 0.1), std::invalid_argument);
  EXPECT_THROW(fit_to_sphere(mesh, 0.0), std::invalid_argument);
}

TEST(ObjectScene, AUsersMeshFloatsInsideItsGridWithTheSphereAsItsViews) {
  const Scene scene = load_scene(write_box_obj("box.obj").string());
  EXPECT_EQ(scene.kind, SceneKind::kObject);
  EXPECT_EQ(scene.name, "box");
  ASSERT_EQ(scene.shapes.size(), 1u);  // no table, no floor
  const Eigen::AlignedBox3d grid(scene.grid.origin, scene.grid.max_corner());
  EXPECT_TRUE(grid.contains(scene.shapes[0].bounds()));
  EXPECT_NEAR(scene.shapes[0].bounds().center().norm(), 0.0, 1e-12);
  const std::vector<Eigen::Isometry3d> views = scene.candidate_poses();
  ASSERT_EQ(views.size(), 32u);
  for (const Eigen::Isometry3d& v : views) {
    EXPECT_NEAR((v.translation() - scene.mount.target).norm(), ObjectProtocol{}.view_radius, 1e-9);
    EXPECT_FALSE(grid.contains(v.translation()));  // the sensor stays outside the object's grid
  }
  // The starts are the views, spread: any two of the first five at least 60 degrees apart.
  ASSERT_EQ(scene.start_poses.size(), 32u);
  for (const Eigen::Isometry3d& s : scene.start_poses) {
    EXPECT_EQ(std::count_if(views.begin(), views.end(),
                            [&](const Eigen::Isometry3d& v) { return v.isApprox(s, 1e-12); }),
              1);
  }
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < i; ++j) {
      const Eigen::Vector3d a = (scene.start_poses[i].translation() - scene.mount.target);
      const Eigen::Vector3d b = (scene.start_poses[j].translation() - scene.mount.target);
      EXPECT_LT(a.normalized().dot(b.normalized()), std::cos(deg2rad(60.0))) << i << ", " << j;
    }
  }
}

TEST(ObjectScene, AnObjectFilePlacesSeveralMeshesAndTheSphereGrowsWithThem) {
  const fs::path mesh = write_box_obj("part.obj");
  const fs::path file = mesh.parent_path() / "pair.yaml";
  std::ofstream(file) << "name: pair\nkind: object\nobjects:\n"
                         "  - {file: part.obj, pose: [0.15, 0, 0]}\n"
                         "  - {file: part.obj, radius: 0.05, pose: [-0.15, 0, 0, 0, 0, 90]}\n"
                         "protocol: {views: 40}\n";
  const Scene scene = load_scene(file.string());
  EXPECT_EQ(scene.kind, SceneKind::kObject);
  ASSERT_EQ(scene.shapes.size(), 2u);
  EXPECT_EQ(scene.candidate_poses().size(), 40u);
  ASSERT_TRUE(scene.view_sphere.has_value());
  // Their spheres span x from -0.2 to 0.25 m: centred at 0.025, they reach 0.225 m from it, and
  // the sensor keeps the protocol's 0.6 m from that.
  EXPECT_NEAR(scene.mount.target.x(), 0.025, 1e-12);
  EXPECT_NEAR(scene.view_sphere->radius, 0.6 + 0.225, 1e-9);
}

TEST(ObjectScene, BadProtocolsAndFilesNameTheirFault) {
  const fs::path mesh = write_box_obj("bad.obj");
  ObjectProtocol near;
  near.view_radius = 0.3;  // the Kinect sees nothing nearer than 0.5 m
  EXPECT_NE(error_of([&] { (void)single_object_scene(mesh.string(), near); })
                .find("object.view_radius (0.3 m) leaves the object nearer than the kinect's "
                      "minimum range (0.5 m)"),
            std::string::npos);
  const fs::path file = mesh.parent_path() / "typo.yaml";
  std::ofstream(file) << "name: t\nkind: object\nobjects:\n  - {file: bad.obj, radios: 1}\n";
  EXPECT_NE(error_of([&] { (void)load_scene(file.string()); }).find("unknown key 'radios'"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              (void)load_scene((mesh.parent_path() / "gone.stl").string());
            }).find("gone.stl"),
            std::string::npos);
}

}  // namespace
}  // namespace vantage::sim
