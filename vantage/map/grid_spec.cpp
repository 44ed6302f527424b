#include "vantage/map/grid_spec.hpp"

#include <cmath>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage {

GridSpec GridSpec::centered(const Eigen::Vector3d& center, double resolution, const Index3& dims) {
  GridSpec spec;
  spec.resolution = resolution;
  spec.dims = dims;
  spec.origin = center - 0.5 * dims.cast<double>() * resolution;
  return spec;
}

void GridSpec::validate() const {
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    throw std::invalid_argument(
        cat("grid.resolution must be a positive number of metres, got ", resolution));
  }
  if (!origin.allFinite()) {
    throw std::invalid_argument("grid.origin must be finite");
  }
  if ((dims.array() <= 0).any()) {
    throw std::invalid_argument(
        cat("grid.dims must be positive, got ", dims.x(), " x ", dims.y(), " x ", dims.z()));
  }
  if (!(origin.array().abs() <= kMaxWorldCoordinate).all() ||
      !(max_corner().array().abs() <= kMaxWorldCoordinate).all()) {
    throw std::invalid_argument(cat("grid lies beyond ", kMaxWorldCoordinate,
                                    " m of the origin (from (", origin.x(), ", ", origin.y(), ", ",
                                    origin.z(), ") m, ", resolution, " m cells)"));
  }
  const auto cells = static_cast<std::int64_t>(dims.x()) * dims.y() * dims.z();
  if (cells > kMaxGridCells) {
    throw std::invalid_argument(cat("grid.dims ", dims.x(), " x ", dims.y(), " x ", dims.z(), " = ",
                                    cells, " cells exceeds the limit of ", kMaxGridCells,
                                    " cells"));
  }
}

Index3 GridSpec::unravel(std::size_t linear_index) const {
  const auto nx = static_cast<std::size_t>(dims.x());
  const auto ny = static_cast<std::size_t>(dims.y());
  return {static_cast<int>(linear_index % nx), static_cast<int>((linear_index / nx) % ny),
          static_cast<int>(linear_index / (nx * ny))};
}

std::optional<Index3> GridSpec::find(const Eigen::Vector3d& p_world) const {
  if (!p_world.allFinite()) return std::nullopt;
  const Index3 cell = lattice_index(p_world);
  if (!contains(cell)) return std::nullopt;
  return cell;
}

Index3 GridSpec::index_of(const Eigen::Vector3d& p_world) const {
  if (auto cell = find(p_world)) return *cell;
  const Eigen::Vector3d hi = max_corner();
  throw std::out_of_range(cat("point (", p_world.x(), ", ", p_world.y(), ", ", p_world.z(),
                              ") is outside the grid [", origin.x(), ", ", origin.y(), ", ",
                              origin.z(), "] - [", hi.x(), ", ", hi.y(), ", ", hi.z(), "]"));
}

}  // namespace vantage
