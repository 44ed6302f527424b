#include "vantage/sim/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "vantage/sim/builtin_models.hpp"

namespace vantage::sim {
namespace {

namespace fs = std::filesystem;

/// A fresh folder for one test's files, removed afterwards.
class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vantage_mesh_io_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  fs::path dir_;
};

// A unit tetrahedron: 4 vertices, 4 triangles, in every text format assimp reads.
constexpr const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
constexpr const char* kObj =
    "# tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
constexpr const char* kOff =
    "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
constexpr const char* kStl =
    "solid tet\n"
    "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "endsolid tet\n";

TEST_F(MeshFiles, LoadsEachFormat) {
  for (const auto& [name, text] : {std::pair{"tet.ply", kPly}, std::pair{"tet.obj", kObj},
                                   std::pair{"tet.off", kOff}, std::pair{"tet.stl", kStl}}) {
    const TriangleMesh mesh = load_mesh(write(name, text));
    EXPECT_EQ(mesh.triangles.size(), 4u) << name;
    const Eigen::AlignedBox3d box = mesh.bounds();
    EXPECT_TRUE(box.min().isApprox(Eigen::Vector3d::Zero())) << name;
    EXPECT_TRUE(box.max().isApprox(Eigen::Vector3d::Ones())) << name;
    // The faces enclose the tetrahedron's volume 1/6, whatever the format's vertex sharing.
    double volume = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
    }
    EXPECT_NEAR(std::abs(volume), 1.0 / 6.0, 1e-9) << name;
  }
}

TEST_F(MeshFiles, MissingFileIsNamed) {
  const fs::path path = dir_ / "nowhere.ply";
  try {
    load_mesh(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nowhere.ply: no such file"), std::string::npos)
        << e.what();
  }
}

// issue 27: a folder or a FIFO is said as what it is, not "not found"; assimp's internals stay
// inside ("aiScene::mNumMeshes is 0").
TEST_F(MeshFiles, PathKindsAndEmptyMeshesAreSaidPlainly) {
  const fs::path folder = dir_ / "folder.obj";
  fs::create_directories(folder);
  try {
    load_mesh(folder);
    FAIL() << "a folder was read as a mesh";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("folder.obj: is a directory, not a file"),
              std::string::npos)
        << e.what();
  }
  const fs::path empty = dir_ / "empty.obj";
  std::ofstream(empty) << "# no vertices, no faces\n";
  try {
    load_mesh(empty);
    FAIL() << "an empty OBJ was read as a mesh";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find("aiScene"), std::string::npos) << message;
    EXPECT_NE(message.find("empty.obj"), std::string::npos) << message;
  }
}

// issue 39: assimp reads what it sniffs, so OBJ text in `m.xyz` was read as a mesh; an extension
// that is no mesh format's, or that the content contradicts, is refused.
TEST_F(MeshFiles, AnExtensionThatLiesIsRefused) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const auto message = [&](const std::string& name, const std::string& text) {
    try {
      load_mesh(write(name, text));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_NE(message("m.xyz", obj).find("'.xyz' is not a mesh format vantage reads"),
            std::string::npos)
      << message("m.xyz", obj);
  EXPECT_NE(message("m.off", obj).find("m.off holds OBJ text, not what its .off extension says"),
            std::string::npos)
      << message("m.off", obj);
  EXPECT_EQ(load_mesh(write("m.obj", obj)).triangles.size(), 1u);
  EXPECT_EQ(load_mesh(write("M.OBJ", obj)).triangles.size(), 1u);
}

// issue 39: an OFF header declaring 2e9 vertices made assimp reserve for them ("std::bad_alloc");
// counts its bytes cannot hold are refused from the header.
TEST_F(MeshFiles, AnOffHeaderBeyondItsBytesIsRefused) {
  try {
    load_mesh(write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n"));
    FAIL() << "an OFF file of 2e9 vertices in 30 bytes was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the OFF header declares 2000000000 vertices and 1 faces, more than"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("bad_alloc"), std::string::npos) << what;
  }
}

TEST_F(MeshFiles, ReadsBinaryPlyInEitherByteOrder) {
  for (const bool big : {false, true}) {
    std::string text = std::string("ply\nformat ") +
                       (big ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nproperty uchar red\nelement face 2\n"
                       "property list uchar int vertex_indices\nend_header\n";
    auto put = [&](const void* p, std::size_t n) {
      const auto* b = static_cast<const char*>(p);
      for (std::size_t i = 0; i < n; ++i) text += b[big ? n - 1 - i : i];
    };
    const float xyz[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {2, 3, 0.5f}};
    for (const auto& v : xyz) {
      for (const float c : v) put(&c, 4);
      text += '\x7f';
    }
    // One triangle and one quad: the quad becomes two triangles.
    text += '\x03';
    for (const std::int32_t i : {0, 1, 2}) put(&i, 4);
    text += '\x04';
    for (const std::int32_t i : {0, 1, 3, 2}) put(&i, 4);
    const TriangleMesh mesh = load_mesh(write(big ? "be.ply" : "le.ply", text));
    ASSERT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(2, 3, 0.5));
    ASSERT_EQ(mesh.triangles.size(), 3u);
    EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 3, 2));
  }
}

TEST_F(MeshFiles, CorruptFilesAreNamed) {
  const std::string ply = kPly;
  const std::string off = kOff;
  std::vector<std::pair<std::string, std::string>> cases = {
      {"header.ply", ply.substr(0, 60)},    // truncated header
      {"header2.ply", ply.substr(0, 150)},  // no end_header
      {"body.ply", ply.substr(0, 170)},     // truncated faces
      {"binary.ply",
       [&] {  // binary header, text body
         std::string t = ply;
         t.replace(t.find("ascii"), 5, "binary_little_endian");
         return t;
       }()},
      {"index.ply",
       [&] {  // a face refers to a vertex that does not exist
         std::string t = ply;
         t.replace(t.rfind("3 1 2 3"), 7, "3 1 2 9");
         return t;
       }()},
      {"count.ply",
       [&] {  // claims far more vertices than the file holds
         std::string t = ply;
         t.replace(t.find("vertex 4"), 8, "vertex 4000000000");
         return t;
       }()},
      {"faces.off", off.substr(0, 33)},  // truncated before the faces
      {"bad.off", "OFF\n4 4 6\n0 0 0\nnonsense\n"},
      {"bad.stl", "solid x\nfacet normal\nendsolid\n"},
      {"empty.obj", "# nothing\n"},
  };
  for (const auto& [name, text] : cases) {
    const fs::path path = write(name, text);
    try {
      load_mesh(path);
      ADD_FAILURE() << name << ": no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
}

// issue 53: an ASCII STL cut short was said as assimp's "Cannot parse string "" as a real number".
TEST_F(MeshFiles, AnAsciiStlCutShortIsSaidAsSuch) {
  const std::string stl = kStl;
  const fs::path path = write("cut.stl", stl.substr(0, stl.find("endsolid") - 20));
  try {
    load_mesh(path);
    ADD_FAILURE() << "a cut STL was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.stl: the ASCII STL ends at byte "), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(" without its 'endsolid' line: cut short"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(MeshFiles, ReadsJavaScriptMeshDataWithoutRunningIt) {
  const fs::path path = write(
      "mesh.js",
      "exports.positions=[[0,0,0],[1,0,0],[0,1.5e0,0],\n [0,0,-2.25]]\nexports.cells = [[0,2,1],"
      "[0,1,3],[0,3,2],[1,2,3]];\n");
  const TriangleMesh mesh = load_js_mesh(path);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(0, 1.5, 0));
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 0, -2.25));
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(1, 2, 3));

  for (const std::string bad : {"exports.positions=[[0,0,0]]\n",  // no cells
                                "exports.positions=[[0,0]]\nexports.cells=[[0,0,0]]\n",
                                "exports.positions=[[0,0,0]]\nexports.cells=[[0,0,1]]\n",
                                "exports.positions=[[0,0,0]]\nexports.cells=[[0,0,0.5]]\n",
                                "exports.positions=require('x')\nexports.cells=[[0,0,0]]\n"}) {
    EXPECT_THROW(load_js_mesh(write("bad.js", bad)), std::runtime_error) << bad;
  }
}

TEST_F(MeshFiles, MissingBuiltinModelSaysHowToGetIt) {
  try {
    load_builtin_model("bunny", dir_);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("make deps"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fetch-models.sh"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_builtin_model("armadillo", dir_), std::invalid_argument);
}

TEST(BuiltinModels, LoadNormalisedZUp) {
  // Fetched by `make deps` (scripts/fetch-models.sh), which `make test` runs first.
  for (const std::string& name : builtin_model_names()) {
    const TriangleMesh mesh = load_builtin_model(name);
    EXPECT_GT(mesh.triangles.size(), 900u) << name;
    const Eigen::AlignedBox3d box = mesh.bounds();
    EXPECT_NEAR(box.sizes().maxCoeff(), 1.0, 1e-12) << name;
    EXPECT_NEAR(box.min().z(), 0.0, 1e-12) << name;
    EXPECT_NEAR(box.center().x(), 0.0, 1e-12) << name;
    EXPECT_NEAR(box.center().y(), 0.0, 1e-12) << name;
  }
  // The bunny stands taller than it is deep once z is up.
  const Eigen::Vector3d bunny = load_builtin_model("bunny").bounds().sizes();
  EXPECT_GT(bunny.z(), bunny.y());
}

}  // namespace
}  // namespace vantage::sim
