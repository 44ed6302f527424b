#pragma once
/// @file
/// MRF hole filling with iterated conditional modes (§4.4, eqs. 17–21; docs/model.md step 2).
///
/// Every cell is a node s in {-1, +1}: +1 occupied, -1 not (unobserved or free). The observation
/// o is the cell's state before filling. The energy is
///   E(S, O) = -beta * sum over 6-neighbour pairs {s, n} of s * n  -  eta * sum of s * o,
/// each pair counted once (eq. 21). Only cells that started unobserved may change; ICM sweeps
/// them in raster order, giving each the state of lower local energy, until a full sweep
/// changes nothing. With beta = eta = 1 an unobserved cell turns occupied when at least four of
/// its six neighbours are occupied.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// Weights of the MRF and a safety cap on the sweeps.
struct HoleFillingConfig {
  bool enabled = true;
  double beta = 1.0;      ///< weight of neighbour agreement, eq. (20)
  double eta = 1.0;       ///< weight of agreement with the observation, eq. (19)
  int max_sweeps = 1000;  ///< ICM converges long before; exceeding it throws

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The binary field of one hole-filling run, exposed for tests and diagnostics.
class IcmField {
 public:
  /// Reads the field from the grid: +1 where occupied; mutable where unobserved.
  IcmField(const OccupancyGrid& grid, double beta, double eta);

  /// One raster-order sweep over the mutable cells; returns how many changed.
  std::size_t sweep();
  /// Total energy of eq. (21).
  double energy() const;
  /// Cells that started unobserved and are now +1, ascending.
  std::vector<std::uint32_t> filled() const;

 private:
  double local_field(std::size_t i) const;

  GridSpec spec_;
  double beta_, eta_;
  std::vector<std::int8_t> s_;          // current state
  std::vector<std::int8_t> o_;          // observation
  std::vector<std::uint32_t> mutable_;  // cells that started unobserved, ascending
};

/// What hole filling did.
struct HoleFillingResult {
  std::vector<std::uint32_t> filled;  ///< cells turned occupied, ascending
  int sweeps = 0;                     ///< sweeps run, the last of which changed nothing
};

/// Runs ICM to convergence and gives each filled cell a hit, which makes it occupied.
HoleFillingResult fill_holes(OccupancyGrid& grid, const HoleFillingConfig& config);

}  // namespace vantage
