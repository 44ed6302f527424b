// docs/architecture.md, "Adding a candidate set": views at the 6 face centres of a cube around
// the target, each looking at it, travelled along straight lines. A set is this one file and
// one row in vantage/views/candidate_sets.cpp's kRows (here kCubeRow, the row it would add).

#include <array>

#include "vantage/views/candidate_set.hpp"
#include "vantage/views/candidate_sets.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {

/// The cube's half side is `radius` (default: the region's largest half extent, at least 0.5 m).
inline PlacedViews cube_candidates(const CandidateSite& site, const CandidateParams& params) {
  const double half =
      params.radius > 0.0 ? params.radius : std::max(0.5, 0.5 * site.region.sizes().maxCoeff());
  PlacedViews views;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      Eigen::Vector3d eye = site.target;
      eye[axis] += side * half;
      views.poses.push_back(look_at(eye, site.target));
    }
  }
  return views;  // travel: the default rule, the straight line
}

/// The row candidate_sets.cpp would list it by.
inline constexpr CandidateSetRow kCubeRow{
    "cube", "six views at the faces of a cube around the target, travel the straight line",
    cube_candidates};

}  // namespace vantage
