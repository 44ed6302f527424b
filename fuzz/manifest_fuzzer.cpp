// libFuzzer harness: the manifest reader (read_manifest of a `manifest.yaml`), and the same bytes
// as a TUM pose file (read_tum_trajectory). Beside it lie the
// files the seeds name (fuzz/make_seeds.py): a.pcd with a VIEWPOINT, a.ply, 2.5.pcd (a stamp in
// its name) and trajectory.txt (TUM), so that the fuzzer gets past "file not found".
#include "fuzz/harness.hpp"
#include "vantage/io/manifest.hpp"
#include "vantage/io/trajectory.hpp"

namespace {

void put(const std::string& name, const std::string& text) {
  vantage::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), name);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const std::string pcd =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
      "VIEWPOINT 0.5 0 1 0.7071068 0 0.7071068 0\nPOINTS 1\nDATA ascii\n0 0 1\n";
  put("a.pcd", pcd);
  put("2.5.pcd", pcd);
  put("a.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 1\n");
  put("trajectory.txt",
      "# timestamp tx ty tz qx qy qz qw\n1.0 0 0 1 0 0 0 1\n2.5 0.5 0 1 0 0 0.3826834 0.9238795\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vantage::fuzz::write_input(data, size, "manifest.yaml");
  vantage::fuzz::expect_clean([&] { vantage::read_manifest(path); });
  // NOTE: the same bytes as a pose file (a manifest's trajectory, `plan --candidates FILE`;
  // issue 39): the TUM reader is a line reader, which text mutated from manifests and the TUM
  // seed exercises, without a harness of its own.
  const auto poses = vantage::fuzz::write_input(data, size, "poses.txt");
  vantage::fuzz::expect_clean([&] {
    vantage::fuzz::sink = static_cast<double>(vantage::read_tum_trajectory(poses).size());
  });
  return 0;
}
