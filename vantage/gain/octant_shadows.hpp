#pragma once
/// @file
/// Where no walk can reach a cell without passing an occupied one first (docs/decision.md, "A
/// metric raced cell by cell"): per cell and per octant of walk directions, whether every
/// 6-connected path that moves only in the octant's directions and reaches the cell from the
/// grid's face passes an occupied cell before it. A walk (GridWalk, map/traversal.hpp) from a
/// sensor is such a path, so a cell shadowed in the octant of every walk from an origin to it is
/// not reached from there, whatever the rays: a proof in one look-up. After a few scans of a table
/// top most of the cells a surface metric credits lie inside the objects, in such shadows for
/// every octant.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/map/block_census.hpp"
#include "vantage/map/cell_classes.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// Per cell and octant, the shadow bit. Octant o's bit a is set when a walk moves towards higher
/// indices on axis a (FreeSpace's octants, GridWalk::octant).
///
/// The bit is the least solution of B(c) = AND over the three axes a of OB(c - s_a e_a), OB(c) =
/// occupied(c) or B(c), with s_a the octant's step on axis a and every cell past the grid's face
/// open (OB false): by induction along a walk, a walk that enters the grid from outside (its first
/// cell has a predecessor past the face) or starts in a cell whose bit is clear reaches no cell
/// whose bit is set without stepping into an occupied cell first, where every walk of the project
/// ends; a jump across free cells lands where the steps land.
class OctantShadows {
 public:
  OctantShadows() = default;
  /// The shadows of the occupied cells among `classes` (a grid of `spec`, whose blocks' counts
  /// `census` holds), the eight octants on `num_threads` threads (0: all cores); the same for any
  /// number.
  OctantShadows(const GridSpec& spec, const CellClasses& classes, const BlockCensus& census,
                int num_threads = 0);

  bool empty() const { return words_ == 0; }
  /// The cell's eight bits (bit o: shadowed for octant o).
  std::uint8_t bits(const Index3& cell) const;
  /// The octants a walk from `origin` to a point of a cell in [lo, hi] may step in.
  std::uint8_t octants(const Eigen::Vector3d& origin, const Index3& lo, const Index3& hi) const;
  /// The octants in which a walk from `origin` starts where the induction holds: every one when
  /// it lies outside the grid, else those whose bit its cell lacks.
  std::uint8_t open_octants(const Eigen::Vector3d& origin) const;
  /// The cells among `cells` (linear indices, not occupied) that some walk from one of `origins`
  /// may reach: those hidden from every origin (hides) left out, in their order. All of them when
  /// an origin's walks to them may start in a shadow. On `num_threads` threads (0: all cores);
  /// the same for any number.
  std::vector<std::uint32_t> reachable(std::span<const Eigen::Vector3d> origins,
                                       std::span<const std::uint32_t> cells,
                                       int num_threads = 0) const;
  /// Whether every walk from `origin` to a point of `cell`'s cube, a cell that is not occupied,
  /// passes an occupied cell before it; `open` is open_octants(origin). False proves nothing.
  bool hides(const Eigen::Vector3d& origin, std::uint8_t open, const Index3& cell) const {
    const std::uint8_t need = octants(origin, cell, cell);
    if ((need & open) != need) return false;
    for (int o = 0; o < 8; ++o) {
      if (((need >> o) & 1) && !bit(o, cell)) return false;
    }
    return true;
  }

 private:
  bool bit(int octant, const Index3& cell) const {
    const int x = (octant & 1) ? cell.x() : spec_.dims.x() - 1 - cell.x();
    const std::size_t row =
        static_cast<std::size_t>(cell.y()) +
        static_cast<std::size_t>(spec_.dims.y()) * static_cast<std::size_t>(cell.z());
    const std::uint64_t word =
        rows_[static_cast<std::size_t>(octant)][row * words_ + static_cast<std::size_t>(x >> 6)];
    return (word >> (x & 63)) & 1u;
  }

  GridSpec spec_;
  std::size_t words_ = 0;  ///< 64-bit words a row of cells along x
  /// Per octant, per row (y, z) of cells along x, OB of its cells, bit x (octants stepping up on
  /// x) or dims.x - 1 - x (stepping down), so that each octant's walks run up the bits.
  std::array<std::vector<std::uint64_t>, 8> rows_;
};

}  // namespace vantage
