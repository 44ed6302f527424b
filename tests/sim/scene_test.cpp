#include "vantage/sim/scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace vantage::sim {
namespace {

namespace fs = std::filesystem;

TEST(Scenes, BuiltinNames) {
  const std::vector<std::string> expected = {"office-large-cluttered",
                                             "office-large-sparse",
                                             "office-small-cluttered",
                                             "office-small-sparse",
                                             "tabletop-1",
                                             "tabletop-2",
                                             "tabletop-3",
                                             "tabletop-4"};
  EXPECT_EQ(builtin_scene_names(), expected);
}

TEST(Scenes, TableTopsFollowThePaper) {
  std::size_t previous_objects = 0;
  for (int k = 1; k <= 4; ++k) {
    const std::string name = "tabletop-" + std::to_string(k);
    const Scene scene = load_scene(name);
    SCOPED_TRACE(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_EQ(scene.kind, SceneKind::kTableTop);
    // 129 x 129 x 65 cubic cells under 1 cm, centred over the table, from its surface up.
    EXPECT_EQ(scene.grid.dims, Index3(129, 129, 65));
    EXPECT_EQ(scene.grid.resolution, 1.0 / 128.0);
    EXPECT_NEAR(scene.grid.origin.x() + scene.grid.size().x() / 2, 0.0, 1e-12);
    EXPECT_NEAR(scene.grid.origin.y() + scene.grid.size().y() / 2, 0.0, 1e-12);
    EXPECT_EQ(scene.grid.origin.z(), 0.75);
    // The ring's 30 candidates and one start per ring position, each looking at the table.
    const auto candidates = scene.candidate_poses();
    ASSERT_EQ(candidates.size(), 30u);
    ASSERT_EQ(scene.start_poses.size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
      EXPECT_TRUE(scene.start_poses[i].isApprox(candidates[3 * i + 1], 1e-12));
    }
    // The sensor stands beside the table (outside the grid) and looks at it from low down.
    for (const Eigen::Isometry3d& pose : candidates) {
      EXPECT_FALSE(scene.grid.contains(Eigen::Vector3d(pose.translation())));
      EXPECT_LT(pose.translation().z() - 0.75, 0.5);
    }
    // The table lies just below the grid; the objects stand in it.
    std::size_t objects = 0;
    for (const Shape& shape : scene.shapes) {
      const Eigen::AlignedBox3d box = shape.bounds();
      if (shape.kind == "table") {
        EXPECT_NEAR(box.max().z(), scene.grid.origin.z(), 1e-12);
      } else if (shape.kind != "floor") {
        ++objects;
        EXPECT_GE(box.min().z(), 0.75 - 1e-9) << shape.name;
        EXPECT_TRUE(scene.grid.contains(Eigen::Vector3d(box.center()))) << shape.name;
        EXPECT_LT(box.max().z(), scene.grid.max_corner().z()) << shape.name;
      }
    }
    EXPECT_GT(objects, previous_objects);  // clutter grows from scene to scene
    previous_objects = objects;
  }
}

TEST(Scenes, OfficesHaveCubicCellsFiveStartsAndFurniture) {
  for (const std::string size : {"small", "large"}) {
    std::size_t sparse_furniture = 0;
    for (const std::string clutter : {"sparse", "cluttered"}) {
      const std::string name = "office-" + size + "-" + clutter;
      SCOPED_TRACE(name);
      const Scene scene = load_scene(name);
      EXPECT_EQ(scene.kind, SceneKind::kOffice);
      EXPECT_EQ(scene.sensor.type, SensorType::kRgbd);
      EXPECT_EQ(scene.sensor.fov.max_range, 3.5);
      EXPECT_TRUE(scene.candidate_poses().empty());
      const Eigen::Vector3d extent =
          size == "small" ? Eigen::Vector3d(15, 10, 2) : Eigen::Vector3d(20, 25, 2);
      EXPECT_TRUE(scene.grid.size().isApprox(extent, 1e-12)) << scene.grid.size().transpose();
      // About as many cells as the paper's 257 x 257 x 65, but cubic.
      const double ratio = static_cast<double>(scene.grid.num_cells()) / (257.0 * 257.0 * 65.0);
      EXPECT_GT(ratio, 0.9);
      EXPECT_LT(ratio, 1.1);
      ASSERT_EQ(scene.start_poses.size(), 5u);
      for (const Eigen::Isometry3d& pose : scene.start_poses) {
        EXPECT_TRUE(scene.floor_area.contains(Eigen::Vector2d(pose.translation().head<2>())));
      }
      std::size_t furniture = 0;
      for (const Shape& shape : scene.shapes) {
        furniture += shape.kind != "wall" && shape.kind != "floor";
      }
      if (clutter == "sparse") {
        sparse_furniture = furniture;
        EXPECT_GT(furniture, 5u);
      } else {
        EXPECT_GT(furniture, 2 * sparse_furniture);
      }
    }
  }
}

// A small valid scene; each error test breaks one line of it.
constexpr const char* kMinimal = R"(name: small
kind: tabletop
grid:
  origin: [-0.5, -0.5, 0.75]
  resolution: 0.0078125
  dims: [128, 128, 64]
table: {size: [1.0, 1.0], height: 0.75}
objects:
  - {type: box, size: [0.1, 0.1, 0.2], pose: [0, 0, 0.75]}
  - type: mesh
    file: tet.obj
    scale: 0.1
    pose: [0.2, 0, 0.75, 0, 0, 45]
sensor: hokuyo
mount: {height: 1.1, target: [0, 0, 0.8]}
candidates: {generator: ring, radius: 1.0, positions: 10}
start_poses: ring
)";

class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    // NOTE: one folder per test, as ctest runs this fixture's tests in parallel processes.
    dir_ = fs::temp_directory_path() /
           (std::string("vantage_scene_test_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "tet.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                       "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// The error message of parsing kMinimal with `from` replaced by `to`.
  std::string error_of(const std::string& from, const std::string& to) const {
    std::string text = kMinimal;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    try {
      parse_scene(text, "bad.yaml", dir_);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for " << to;
    return "";
  }

  /// Line (1-based) of the first occurrence of `text` in kMinimal.
  static int line_of(const std::string& text) {
    const std::string all = kMinimal;
    return 1 + static_cast<int>(std::count(all.begin(), all.begin() + all.find(text), '\n'));
  }

  fs::path dir_;
};

TEST_F(SceneFiles, MinimalSceneLoadsWithItsMeshFile) {
  const fs::path path = dir_ / "small.yaml";
  std::ofstream(path) << kMinimal;
  const Scene scene = load_scene(path.string());
  EXPECT_EQ(scene.name, "small");
  ASSERT_EQ(scene.shapes.size(), 3u);  // table, box, mesh
  EXPECT_EQ(scene.shapes[2].kind, "mesh");
  EXPECT_EQ(scene.shapes[2].mesh_world.triangles.size(), 4u);
  // Scaled by 0.1 and turned by 45 degrees about z at (0.2, 0, 0.75).
  const Eigen::Vector3d moved(0.2 + 0.1 * std::sqrt(0.5), 0.1 * std::sqrt(0.5), 0.75);
  const auto& vertices = scene.shapes[2].mesh_world.vertices;
  EXPECT_TRUE(std::any_of(vertices.begin(), vertices.end(),
                          [&](const Eigen::Vector3d& v) { return (v - moved).norm() < 1e-12; }));
  EXPECT_EQ(scene.sensor.name, "hokuyo");
  EXPECT_EQ(scene.start_poses.size(), 10u);
}

TEST_F(SceneFiles, TypoNamesTheKeyAndLine) {
  const std::string e = error_of("objects:", "objets:");
  EXPECT_NE(e.find("bad.yaml:" + std::to_string(line_of("objects:"))), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'objets'"), std::string::npos) << e;

  const std::string nested = error_of("size: [0.1, 0.1, 0.2]", "sise: [0.1, 0.1, 0.2]");
  EXPECT_NE(nested.find("objects[0].sise"), std::string::npos) << nested;
}

TEST_F(SceneFiles, NegativeSizeNamesTheKey) {
  const std::string e = error_of("size: [0.1, 0.1, 0.2]", "size: [0.1, -0.1, 0.2]");
  EXPECT_NE(e.find("bad.yaml:" + std::to_string(line_of("size: [0.1, 0.1, 0.2]"))),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("objects[0].size[1]: must be positive"), std::string::npos) << e;
  EXPECT_NE(error_of("radius: 1.0", "radius: -1.0").find("candidates.radius"), std::string::npos);
  EXPECT_NE(error_of("resolution: 0.0078125", "resolution: -0.01").find("grid.resolution"),
            std::string::npos);
  EXPECT_NE(error_of("height: 0.75}", "height: 0}").find("table.height"), std::string::npos);
}

TEST_F(SceneFiles, UnknownModelNamesTheKeyAndHowToGetModels) {
  const std::string e = error_of("file: tet.obj", "model: armadillo");
  EXPECT_NE(e.find("objects[1].model"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown model 'armadillo'"), std::string::npos) << e;
  const std::string missing = error_of("file: tet.obj", "file: gone.obj");
  EXPECT_NE(missing.find("objects[1].file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("gone.obj: no such file"), std::string::npos) << missing;
}

TEST_F(SceneFiles, OtherMistakesNameTheirKey) {
  EXPECT_NE(error_of("kind: tabletop", "kind: garden").find("kind: must be tabletop, office or object"),
            std::string::npos);
  EXPECT_NE(error_of("resolution: 0.0078125", "resolution: fine").find("grid.resolution"),
            std::string::npos);
  EXPECT_NE(error_of("dims: [128, 128, 64]", "dims: [128, 128]").find("grid.dims"),
            std::string::npos);
  EXPECT_NE(error_of("type: box", "type: blob").find("objects[0].type: unknown object type"),
            std::string::npos);
  EXPECT_NE(error_of("sensor: hokuyo", "sensor: lidar").find("sensor: unknown sensor 'lidar'"),
            std::string::npos);
  EXPECT_NE(error_of("start_poses: ring", "start_poses: [[0, 0, 0]]").find("start_poses[0]"),
            std::string::npos);
  EXPECT_NE(error_of("name: small\n", "").find("missing key 'name'"), std::string::npos);
  EXPECT_NE(error_of("pose: [0, 0, 0.75]", "pose: [0, 0]").find("objects[0].pose"),
            std::string::npos);
  EXPECT_NE(error_of("- {type: box", "- {type: box, {").find("bad.yaml:"), std::string::npos);
}

// issue 39: the ground truth's floor stops are counted before it sweeps from them; an office
// without a floor has none to count.
TEST(Scenes, FloorStopsAreCountedBeforeTheGroundTruth) {
  const std::string office = builtin_scene_text("office-small-sparse");
  const std::string floor = "floor: {size: [15, 10], center: [7.5, 5]}";
  ASSERT_NE(office.find(floor), std::string::npos);
  std::string wide = office;
  wide.replace(wide.find(floor), floor.size(), "floor: {size: [1000, 1000], center: [7.5, 5]}");
  try {
    parse_scene(wide, "wide.yaml", ".");
    ADD_FAILURE() << "4 M floor stops were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("makes 4000000 stops, more than the 20000"),
              std::string::npos)
        << e.what();
  }
  std::string no_floor = office;
  no_floor.replace(no_floor.find(floor), floor.size(), "");
  EXPECT_NO_THROW(parse_scene(no_floor, "no_floor.yaml", "."));
}

// yaml-cpp alone would take the first of two values, or read the first document only.
TEST_F(SceneFiles, DuplicateKeysAndSecondDocumentsAreRefused) {
  const std::string twice = error_of("kind: tabletop\n", "kind: tabletop\nkind: office\n");
  EXPECT_NE(twice.find("bad.yaml:3: kind: duplicate key 'kind' (first at line 2)"),
            std::string::npos)
      << twice;
  const std::string nested =
      error_of("size: [0.1, 0.1, 0.2]", "size: [0.1, 0.1, 0.2], size: [1, 1, 1]");
  EXPECT_NE(nested.find("objects[0].size: duplicate key 'size'"), std::string::npos) << nested;
  const std::string second =
      error_of("start_poses: ring\n", "start_poses: ring\n---\nname: other\n");
  EXPECT_NE(second.find("bad.yaml:" + std::to_string(line_of("start_poses: ring") + 2) +
                        ": a second YAML document"),
            std::string::npos)
      << second;
}

TEST(Scenes, UnknownSceneListsTheBuiltins) {
  try {
    load_scene("tabletop-9");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tabletop-1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vantage::sim
