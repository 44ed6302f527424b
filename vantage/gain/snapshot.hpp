#pragma once
/// @file
/// The snapshot the gain evaluations read: `GainMap`, one small code per cell into a table of the
/// grid's distinct values.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// A read-only snapshot of an occupancy grid, laid out for gain evaluation: per cell a small code
/// into a table of the distinct log-odds values the grid holds, each with its probability,
/// entropy and class. A grid updated by hits and misses holds few distinct values, so the codes
/// are usually one byte (a 129 x 129 x 65 grid fits in 1 MiB of cache).
///
/// Probabilities and classes are computed from the stored log-odds exactly as OccupancyGrid does,
/// so a model run on the snapshot gives the same numbers as one run on the grid.
class GainMap {
 public:
  /// What the evaluation needs to know about a cell.
  struct Value {
    double p = 0.5;        ///< occupancy probability
    double entropy = 1.0;  ///< H(p) [bits]
    CellState state = CellState::kUnobserved;
  };

  /// Takes the snapshot; `num_threads` as everywhere (0 = all cores).
  explicit GainMap(const OccupancyGrid& grid, int num_threads = 0);
  /// The snapshot of the grid's classes alone, for a model that reads a cell's class and nothing
  /// of its probability (a metric whose value is a sum of cell credits, models/metric_cells.hpp):
  /// three values, ascending, each its class's nominal one (free: p 0, occupied: p 1, both 0
  /// bits; unobserved: p 0.5, 1 bit), as the walks by reach codes hand them. Unpacked from the
  /// grid's classes (OccupancyGrid::classes) where the full snapshot sorts the grid's values
  /// (`BM_MetricSetUp`; docs/decision.md, "The set-up of a metric decision").
  static GainMap of_classes(const OccupancyGrid& grid, int num_threads = 0);

  const GridSpec& spec() const { return spec_; }
  const OccupancyParams& params() const { return params_; }
  std::size_t size() const { return spec_.num_cells(); }

  /// Bytes per cell code: 1, 2 or 4.
  int code_width() const { return code_width_; }
  /// The table of distinct values, ascending in log-odds.
  std::span<const Value> values() const { return values_; }
  /// Codes of width `Code` (which must match code_width()), one per cell in linear order.
  template <typename Code>
  const Code* codes() const {
    if constexpr (sizeof(Code) == 1) {
      return codes8_.data();
    } else if constexpr (sizeof(Code) == 2) {
      return codes16_.data();
    } else {
      return codes32_.data();
    }
  }
  /// The value of cell `i`, whatever the code width. Inline: every per-target ray reads it per
  /// cell.
  const Value& value(std::size_t i) const {
    switch (code_width_) {
      case 1:
        return values_[codes8_[i]];
      case 2:
        return values_[codes16_[i]];
      default:
        return values_[codes32_[i]];
    }
  }

 private:
  GainMap(const GridSpec& spec, const OccupancyParams& params) : spec_(spec), params_(params) {}

  GridSpec spec_;
  OccupancyParams params_;
  int code_width_ = 1;
  std::vector<Value> values_;
  // The codes, in the one vector of width code_width_.
  std::vector<std::uint8_t> codes8_;
  std::vector<std::uint16_t> codes16_;
  std::vector<std::uint32_t> codes32_;
};

/// Calls `f(codes)` with the snapshot's codes as a pointer of their width (std::uint8_t,
/// std::uint16_t or std::uint32_t); returns what `f` returns.
template <typename F>
decltype(auto) with_codes(const GainMap& map, F&& f) {
  switch (map.code_width()) {
    case 1:
      return f(map.codes<std::uint8_t>());
    case 2:
      return f(map.codes<std::uint16_t>());
    default:
      return f(map.codes<std::uint32_t>());
  }
}

/// A cell's class bit (class_bit), read from the snapshot's codes of width `Code` by a table of
/// the codes' classes, where GainMap::value switches on the width at each call.
template <typename Code>
struct ClassOf {
  const Code* codes;
  std::vector<std::uint8_t> bit;  ///< per code

  explicit ClassOf(const GainMap& map) : codes(map.codes<Code>()) {
    for (const GainMap::Value& v : map.values()) bit.push_back(class_bit(v.state));
  }
  std::uint8_t operator()(std::size_t i) const { return bit[codes[i]]; }
};

/// Runs `f(ClassOf<Code>)` with the snapshot's code width; returns what `f` returns.
template <typename F>
decltype(auto) with_classes(const GainMap& map, F&& f) {
  switch (map.code_width()) {
    case 1:
      return f(ClassOf<std::uint8_t>(map));
    case 2:
      return f(ClassOf<std::uint16_t>(map));
    default:
      return f(ClassOf<std::uint32_t>(map));
  }
}

/// Inclusive index box of the grid cells that may lie inside a frustum (its bounding box, cut to
/// the grid); empty when the frustum misses the grid.
struct CellBox {
  Index3 lo, hi;
  bool empty() const { return (hi.array() < lo.array()).any(); }
};

inline CellBox cells_under(const GridSpec& spec, const Frustum& view) {
  const Eigen::AlignedBox3d box = view.bounds();
  return {spec.lattice_index(box.min()).cwiseMax(Index3::Zero()),
          spec.lattice_index(box.max()).cwiseMin(spec.dims - Index3::Ones())};
}

}  // namespace vantage
