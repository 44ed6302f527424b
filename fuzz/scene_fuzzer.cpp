// libFuzzer harness: the scene YAML reader (parse_scene, then the candidate views the scene
// describes). Models are looked up in an empty folder, so a built-in model is a missing file. Mesh
// files a scene may name lie beside it (issue 39): a tetrahedron in each format and files whose
// extension lies or names no mesh format, so that the mutated references reach the mesh reader's
// checks (its extension rule, the sniffed content, the OFF header's counts); their bytes are
// fixed, so assimp only ever reads these.
#include <cstdlib>
#include <string>

#include "fuzz/harness.hpp"
#include "vantage/sim/scene.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const auto models = vantage::fuzz::scratch_dir() / "models";
  std::filesystem::create_directories(models);
  setenv("VANTAGE_MODELS_DIR", models.c_str(), 1);
  const auto put = [](const std::string& name, const std::string& text) {
    vantage::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(),
                               name);
  };
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  put("m.obj", obj);
  put("m.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  put("m.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  put("m.stl",
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid t\n");
  put("lie.off", obj);
  put("m.xyz", obj);
  put("huge.off", "OFF\n2000000000 1 0\n0 0 0\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  vantage::fuzz::expect_clean([&] {
    const vantage::sim::Scene scene =
        vantage::sim::parse_scene(text, "fuzz.yaml", vantage::fuzz::scratch_dir());
    vantage::fuzz::sink = static_cast<double>(scene.candidate_poses().size());
  });
  return 0;
}
