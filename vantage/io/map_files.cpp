#include "vantage/io/map_files.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

// Shortest text that reads back as the same double.
std::string number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace

void write_map_files(const std::filesystem::path& dir, const OccupancyGrid& grid) {
  write_octomap(dir / "map.ot", grid);
  write_octomap(dir / "map.bt", grid);
  write_top_view(dir / "map_top.csv", grid);
}

void write_top_view(const std::filesystem::path& path, const OccupancyGrid& grid) {
  const GridSpec& spec = grid.spec();
  const auto columns = static_cast<std::size_t>(spec.dims.x()) * spec.dims.y();
  std::vector<std::uint32_t> occupied(columns, 0), unobserved(columns, 0);
  std::vector<int> top(columns, -1);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellState state = grid.state(i);
    if (state == CellState::kFree) continue;
    const std::size_t column = i % columns;  // x fastest, then y, then z
    if (state == CellState::kOccupied) {
      ++occupied[column];
      top[column] = static_cast<int>(i / columns);  // z grows with i
    } else {
      ++unobserved[column];
    }
  }
  std::string text =
      cat("# grid origin ", number(spec.origin.x()), " ", number(spec.origin.y()), " ",
          number(spec.origin.z()), " resolution ", number(spec.resolution), " dims ", spec.dims.x(),
          " ", spec.dims.y(), " ", spec.dims.z(), "\nx,y,occupied,unobserved,top\n");
  for (std::size_t column = 0; column < columns; ++column) {
    if (occupied[column] == 0 && unobserved[column] == 0) continue;
    const int x = static_cast<int>(column % static_cast<std::size_t>(spec.dims.x()));
    const int y = static_cast<int>(column / static_cast<std::size_t>(spec.dims.x()));
    const Eigen::Vector3d c = spec.center(Index3(x, y, std::max(top[column], 0)));
    text += cat(number(c.x()), ",", number(c.y()), ",", occupied[column], ",", unobserved[column],
                ",", top[column] >= 0 ? number(c.z()) : std::string(), "\n");
  }
  write_atomically(path, text);
}

}  // namespace vantage
