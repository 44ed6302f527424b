// libFuzzer harness: the OctoMap reader (read_octomap of a `.bt` when the first line says
// "binary", else of a `.ot`) twice: into the grid it derives from the tree, as `vantage plan
// --map` reads, refused through check_grid beyond 2^21 cells (8 MiB of log-odds) as plan's
// memory budget refuses a grid beyond the machine's memory; and into a given 32 x 32 x 32 grid
// around the origin with `crop`, at the resolution the header's `res` line states (0.1 when the
// harness finds none).
#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "fuzz/harness.hpp"
#include "vantage/io/octomap_io.hpp"

namespace {

double stated_resolution(std::string_view bytes) {
  const std::size_t at = bytes.find("\nres ");
  if (at == std::string_view::npos) return 0.1;
  const std::string value(bytes.substr(at + 5, 32));
  char* end = nullptr;
  const double res = std::strtod(value.c_str(), &end);
  return end != value.c_str() && res > 1e-6 && res < 1e6 ? res : 0.1;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string_view first_line = bytes.substr(0, std::min(bytes.find('\n'), bytes.size()));
  const bool binary = first_line.find("binary") != std::string_view::npos;
  const auto path = vantage::fuzz::write_input(data, size, binary ? "map.bt" : "map.ot");
  vantage::OctomapImportConfig derived;
  derived.check_grid = [](const vantage::GridSpec& spec) {
    if (spec.num_cells() > (std::size_t{1} << 21)) throw std::runtime_error("over the budget");
  };
  vantage::fuzz::expect_clean([&] { vantage::read_octomap(path, derived); });
  vantage::OctomapImportConfig config;
  config.grid = vantage::GridSpec::centered(Eigen::Vector3d::Zero(), stated_resolution(bytes),
                                            vantage::Index3::Constant(32));
  config.crop = true;
  vantage::fuzz::expect_clean([&] { vantage::read_octomap(path, config); });
  return 0;
}
