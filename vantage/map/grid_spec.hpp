#pragma once
/// @file
/// Geometry of a dense, axis-aligned grid of cubic cells, and world/index conversions.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace vantage {

/// Integer cell coordinates (x, y, z).
using Index3 = Eigen::Vector3i;

/// Largest grid we allocate: 2^30 cells (4 GiB of float log-odds).
inline constexpr std::int64_t kMaxGridCells = std::int64_t{1} << 30;

/// The largest coordinate, distance or size any input may name [m]: beyond it a float position
/// is meaningless at the scale of a cell, and Embree's ray checks abort (about 1.8e18 m).
inline constexpr double kMaxWorldCoordinate = 1e5;

/// Where a grid lies in the world and how it is cut into cells.
///
/// Cell (i, j, k) spans [origin + (i, j, k) * resolution, origin + (i + 1, j + 1, k + 1) *
/// resolution). Linear indices run x fastest, then y, then z.
struct GridSpec {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< min corner of cell (0, 0, 0) [m]
  double resolution = 0.01;                          ///< edge length of a cubic cell [m]
  Index3 dims = Index3::Ones();                      ///< number of cells along x, y, z

  /// A grid of `dims` cells whose box is centred on `center`.
  static GridSpec centered(const Eigen::Vector3d& center, double resolution, const Index3& dims);

  /// Throws std::invalid_argument naming the field when the spec is unusable (non-positive or
  /// non-finite resolution, non-positive dims, more than kMaxGridCells cells).
  void validate() const;

  std::size_t num_cells() const {
    return static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) *
           static_cast<std::size_t>(dims.z());
  }
  Eigen::Vector3d size() const { return dims.cast<double>() * resolution; }  ///< [m]
  Eigen::Vector3d max_corner() const { return origin + size(); }             ///< [m]

  bool contains(const Index3& cell) const {
    return (cell.array() >= 0).all() && (cell.array() < dims.array()).all();
  }
  bool contains(const Eigen::Vector3d& p_world) const { return contains(lattice_index(p_world)); }

  std::size_t linear(const Index3& cell) const {
    return static_cast<std::size_t>(cell.x()) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(cell.y()) +
                static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(cell.z()));
  }
  Index3 unravel(std::size_t linear_index) const;

  /// Centre of a cell, inside the grid or not [m].
  Eigen::Vector3d center(const Index3& cell) const {
    return origin + (cell.cast<double>().array() + 0.5).matrix() * resolution;
  }

  /// Index of the lattice cell holding p, extending the grid's lattice beyond its bounds.
  /// Inline: the gain evaluation calls it for every replayed cell and every jump.
  Index3 lattice_index(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d scaled = (p_world - origin) / resolution;
    // NOTE: clamp before the cast so that far-away points cannot overflow int.
    constexpr double kLimit = 1e9;
    return scaled.array().floor().max(-kLimit).min(kLimit).cast<int>();
  }

  /// Index of the grid cell holding p, or nothing when p is outside the grid (or not finite).
  std::optional<Index3> find(const Eigen::Vector3d& p_world) const;

  /// Index of the grid cell holding p; throws std::out_of_range naming the point otherwise.
  Index3 index_of(const Eigen::Vector3d& p_world) const;

  bool operator==(const GridSpec&) const = default;
};

}  // namespace vantage
