#pragma once
/// @file
/// The map as the rays of the survival reading and greedy read it (docs/decision.md, "The swept
/// search", item 6): each cell's class, read from the grid's own packed classes, and its free
/// space, derived from the grid's census. Both are kept by integration, so a ClassMap costs a
/// pass over the blocks (1/64 of the cells), not a copy of the grid as GainMap does.

#include <cstddef>

#include "vantage/gain/free_space.hpp"
#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// A view of a grid's classes; the grid must outlive it and stay unchanged while it is read.
class ClassMap {
 public:
  /// What a walk reads of a cell (as GainMap::Value, its class only).
  struct Value {
    CellState state;
  };

  explicit ClassMap(const OccupancyGrid& grid)
      : spec_(grid.spec()), classes_(&grid.classes()), free_(vantage::free_space(grid.census())) {}

  const GridSpec& spec() const { return spec_; }
  std::size_t size() const { return spec_.num_cells(); }
  CellState state(std::size_t i) const { return (*classes_)[i]; }
  Value value(std::size_t i) const { return {state(i)}; }
  /// Where rays may cross free cells a cube of blocks at a time.
  const FreeSpace& free_space() const { return free_; }

 private:
  GridSpec spec_;
  const CellClasses* classes_;
  FreeSpace free_;
};

}  // namespace vantage
