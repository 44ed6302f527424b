#include "vantage/io/ply_export.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/ply.hpp"

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

  // NOTE: a fresh stream's 6 significant digits (not cat()'s 10), as this comment always had.
  std::ostringstream resolution;
  resolution << "resolution " << spec.resolution << " m";
  constexpr ScalarType kFloat{'F', 4}, kByte{'U', 1};
  const PlyElement vertex{"vertex",
                          cells.size(),
                          {{"x", kFloat},
                           {"y", kFloat},
                           {"z", kFloat},
                           {"red", kByte},
                           {"green", kByte},
                           {"blue", kByte},
                           {"probability", kFloat}}};
  const std::string header = ply_header(
      config.binary ? PlyFormat::kBinaryLittleEndian : PlyFormat::kAscii,
      {"Vantage occupancy grid: occupied cells red, unobserved cells yellow", resolution.str()},
      {vertex});

  write_atomically(path, [&](std::ostream& out) {
    out << header;
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
