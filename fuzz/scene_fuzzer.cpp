// libFuzzer harness: the scene YAML reader (parse_scene, then the candidate views the scene
// describes). Models are looked up in an empty folder, so a mesh is a missing file, not an
// assimp run.
#include <cstdlib>

#include "fuzz/harness.hpp"
#include "vantage/sim/scene.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const auto models = vantage::fuzz::scratch_dir() / "models";
  std::filesystem::create_directories(models);
  setenv("VANTAGE_MODELS_DIR", models.c_str(), 1);
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
