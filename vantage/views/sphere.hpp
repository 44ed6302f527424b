#pragma once
/// @file
/// Candidate views spread evenly over a sphere (or a band of it) around a region of interest,
/// each looking at its centre: the classic view sphere of object reconstruction.

#include <Eigen/Geometry>
#include <vector>

namespace vantage {

/// A band of a sphere between two elevations, sampled by a Fibonacci lattice.
struct SphereConfig {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< point every view looks at [m]
  double radius = 1.0;                               ///< [m]
  int views = 50;                                    ///< how many candidates
  double min_elevation = 0.0;        ///< lowest view above the centre's horizon [rad]
  double max_elevation = 1.3962634;  ///< highest, 80 degrees (avoids looking straight down) [rad]

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Poses on the band, evenly spread (equal area per view), each looking at the centre.
std::vector<Eigen::Isometry3d> sphere_poses(const SphereConfig& config);

/// Views on an object's view sphere by default: SCVP's and MA-SCVP's 32.
inline constexpr int kObjectViews = 32;

/// The whole sphere of `views` views at `radius` around `center` (elevations -90 to 90 degrees):
/// the view space of single-object NBV benchmarks (SCVP, MA-SCVP, PB-NBV).
SphereConfig object_view_sphere(const Eigen::Vector3d& center, double radius,
                                int views = kObjectViews);

}  // namespace vantage
