#include "vantage/io/ply_export.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <vector>

#include "vantage/io/atomic_file.hpp"

namespace vantage {
namespace {

struct Color {
  std::uint8_t r, g, b;
};
constexpr Color kOccupiedColor{255, 0, 0};
constexpr Color kUnobservedColor{255, 255, 0};

// Appends the little-endian bytes of a float.
void put_float(std::vector<char>& out, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((bits >> (8 * k)) & 0xffu));
}

}  // namespace

CellPlyExport write_cells_ply(const std::filesystem::path& path, const OccupancyGrid& grid,
                              const CellPlyConfig& config) {
  const GridSpec& spec = grid.spec();
  CellPlyExport result;
  std::vector<std::size_t> cells;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellState state = grid.state(i);
    if (state == CellState::kOccupied && config.occupied) {
      cells.push_back(i);
      ++result.occupied;
    } else if (state == CellState::kUnobserved && config.unobserved) {
      cells.push_back(i);
      ++result.unobserved;
    }
  }

  write_atomically(path, [&](std::ostream& out) {
    out << "ply\n"
        << (config.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n")
        << "comment Vantage occupancy grid: occupied cells red, unobserved cells yellow\n"
        << "comment resolution " << spec.resolution << " m\n"
        << "element vertex " << cells.size() << "\n"
        << "property float x\nproperty float y\nproperty float z\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        << "property float probability\n"
        << "end_header\n";
    std::vector<char> buffer;
    constexpr std::size_t kRecord = 3 * 4 + 3 + 4;
    constexpr std::size_t kBlock = 1 << 16;
    buffer.reserve(kBlock * kRecord);
    out.precision(9);  // float round trip in ASCII
    for (std::size_t n = 0; n < cells.size(); ++n) {
      const std::size_t i = cells[n];
      const Eigen::Vector3f c = spec.center(spec.unravel(i)).cast<float>();
      const Color color = grid.state(i) == CellState::kOccupied ? kOccupiedColor : kUnobservedColor;
      const auto p = static_cast<float>(grid.probability(i));
      if (config.binary) {
        put_float(buffer, c.x());
        put_float(buffer, c.y());
        put_float(buffer, c.z());
        buffer.push_back(static_cast<char>(color.r));
        buffer.push_back(static_cast<char>(color.g));
        buffer.push_back(static_cast<char>(color.b));
        put_float(buffer, p);
        if (buffer.size() >= kBlock * kRecord) {
          out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
          buffer.clear();
        }
      } else {
        out << c.x() << ' ' << c.y() << ' ' << c.z() << ' ' << int{color.r} << ' ' << int{color.g}
            << ' ' << int{color.b} << ' ' << p << '\n';
      }
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  });
  return result;
}

}  // namespace vantage
