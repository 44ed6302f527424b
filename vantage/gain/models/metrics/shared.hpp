#pragma once
/// @file
/// What the metrics' own files (this folder) share beneath the metrics' evaluation
/// (gain/evaluators/metric_evaluator.hpp): the distances and the area factor's shape.

#include <cmath>
#include <cstddef>
#include <vector>

#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/block_census.hpp"

namespace vantage {

/// D, the distance [cells] within which an unobserved cell counts as near an occupied one:
/// the proximity count's cut-off and the area factor's "occplane" test.
inline constexpr double kProximityCells = 4.0;

/// The surface model's distance class (kSurfaceClasses) of an unobserved cell `near` cells from
/// the nearest occupied cell (+infinity beyond kProximityCells): 0 within 1 cell (face to face),
/// 1 within 2, 2 within 3, 3 within 4, 4 farther.
inline std::size_t surface_class(float near) {
  if (!(near <= static_cast<float>(kProximityCells))) return kSurfaceClasses - 1;
  return near <= 1.0f ? 0 : static_cast<std::size_t>(std::ceil(near)) - 1;
}

/// The area factor's desired fractions of rays on occupied cells and on occplane cells
/// (Vasquez-Gomez et al. 2014; rpg's defaults).
inline constexpr double kAreaOccupied = 0.2;
inline constexpr double kAreaOccplane = 0.8;

/// Vasquez-Gomez's area factor f(x; alpha) of a fraction x in [0, 1] (Vasquez-Gomez, Sucar &
/// Murrieta-Cid, 2014; Delmerico et al. 2018, §3.2): the cubic that rises from f(0) = 0 to its
/// peak f(alpha) = 1 and falls back to f(1) = 0, flat at all three.
double area_factor(double x, double alpha);

/// Per cell, the Euclidean distance [cells] between its centre and the nearest occupied cell's,
/// where it is at most `radius`; +infinity elsewhere (0 in occupied cells). On `num_threads`
/// threads (0: all cores); the same for any number. With the census of the map's grid, the
/// occupied cells are looked for only in the blocks it says hold one: the same distances.
std::vector<float> occupied_distance(const GainMap& map, double radius, int num_threads = 0,
                                     const BlockCensus* census = nullptr);

}  // namespace vantage
