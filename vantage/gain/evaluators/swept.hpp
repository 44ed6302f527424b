#pragma once
/// @file
/// An estimate of each view's count from a few thousand rays cast outward (docs/decision.md,
/// "The swept search"): each ray stands for the cone of directions around it and credits the
/// volume of that cone inside every unobserved cell it crosses, at the visibility it carries
/// there. The exact evaluation casts one ray per target cell (hundreds of thousands a view);
/// this one casts one per pixel of a coarse image and costs a few hundred microseconds a view.

#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How finely the rays sample a view's image.
struct SweptConfig {
  /// Rays across the image's wider side; the other side gets the same pitch.
  int rays_across = 32;
  /// Survival's a in (0, 1]: the visibility a ray keeps past an unobserved cell (greedy's: 1).
  double alpha = 0.995;
  /// A ray stops once its visibility falls below this, as the exact evaluation's rays do.
  double epsilon = 1e-6;
  int num_threads = 0;  ///< 0 = all cores; the result does not depend on it
  /// Rays cross the map's free cubes (ClassMap::free_space) in one step; false walks them
  /// cell by cell (the reference: the same credits but for rounding).
  bool skip_free = true;
};

/// Every view's estimated `quantity`, a count of cells (counts_classes, types.hpp) [cells]: the
/// expected unobserved cells seen of the survival reading, or greedy's unblocked unobserved cells,
/// over the frustum's volume; throws std::invalid_argument for another quantity.
///
/// Each pixel of a pinhole image over the view's field of view casts one ray from the origin, at
/// a point jittered within the pixel by a hash of the pixel (the same for every view, so the
/// estimate is deterministic). The ray walks the cells it crosses (cells outside the grid are
/// free); in each unobserved cell between the sensor's range limits it credits
/// v * omega * (r1^3 - r0^3) / (3 h^3), the cells' worth of the cone's volume between the
/// distances r0 and r1 where it enters and leaves the cell (omega: the pixel's solid angle, h:
/// the cell's edge), and then multiplies v by alpha; an occupied cell ends it. Free cells credit
/// nothing, and a ray crosses a cube of free blocks in one step. Unbiased for the
/// volume integral of the per-point visibility, which the exact count samples at the cells'
/// centres. Views run in parallel, each summed in a fixed order: the same for any thread count.
std::vector<double> swept_view_counts(const ClassMap& map, std::span<const Frustum> views,
                                      GainQuantity quantity, const SweptConfig& config);

/// Every view's upper bound on its estimate (swept_view_counts, any quantity, any map) [cells]: the
/// cells' worth of the volume its rays' cones sweep between the sensor's range limits, each ray's
/// credit at a visibility of 1 through unobserved cells all the way, scaled up by 10^-9 for the
/// sums' rounding. A frustum all in unobserved cells of the grid reaches it, to the rounding.
/// It depends on the views' fields of view alone, not on their poses. Throws std::invalid_argument
/// for rays across outside [1, 4096] or a resolution <= 0.
std::vector<double> swept_view_bounds(std::span<const Frustum> views, double resolution,
                                      const SweptConfig& config);

}  // namespace vantage
