// libFuzzer harness: the OctoMap reader (read_octomap of a `.bt` when the first line says
// "binary", else of a `.ot`), deriving the grid from the tree as `vantage plan --map` does.
#include <algorithm>

#include "fuzz/harness.hpp"
#include "vantage/io/octomap_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string_view first_line = bytes.substr(0, std::min(bytes.find('\n'), bytes.size()));
  const bool binary = first_line.find("binary") != std::string_view::npos;
  const auto path = vantage::fuzz::write_input(data, size, binary ? "map.bt" : "map.ot");
  vantage::fuzz::expect_clean([&] { vantage::read_octomap(path); });
  return 0;
}
