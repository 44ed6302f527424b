#pragma once
/// @file
/// The fast evaluation's rays (docs/fast-gain.md "The rays"): views that share an origin share
/// one pinhole image of rays, and rays are cast only in the tiles of that image that may own an
/// unobserved cell. Internal to vantage/gain.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// Views share rays when they share an origin; a group holds at most this many.
constexpr int kMaxGroup = 8;
/// Rays are cast by tiles of kTile x kTile pixels, and only in tiles whose pixels may own an
/// unobserved cell.
constexpr int kTile = 8;

/// The rays of views that share an origin: a pinhole image in the group's frame whose pixel
/// (col, row) has its ray through u = u0 + (col + 0.5) du, v = v0 + (row + 0.5) du on the plane
/// x = 1. The window covers every member's field of view, cut to the grid's image.
struct RayGroup {
  std::vector<std::size_t> members;  // view indices
  std::vector<const Frustum*> views;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();   // world <- group frame
  Eigen::Matrix3d Rt = Eigen::Matrix3d::Identity();  // group frame <- world
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double u0 = 0, v0 = 0, du = 1;
  int cols = 0, rows = 0;
  double reach = 0;  // farthest distance a credited cell's point can lie from the origin [m]
  Index3 origin_cell = Index3::Zero();
  bool origin_inside = false;
};

/// Cuts the image window [u_lo, u_hi] x [v_lo, v_hi] (on the plane x = 1 of the frame `Rt` at
/// `origin`) to the image of the grid's box when the whole box lies in front, and returns the
/// depth of the box's farthest corner, capped at `max_range` [m]: the depth that sets the ray
/// pitch. Shared with the OctoMap baseline of the benchmarks.
double cut_to_grid(const GridSpec& spec, const Eigen::Matrix3d& Rt, const Eigen::Vector3d& origin,
                   double max_range, double& u_lo, double& u_hi, double& v_lo, double& v_hi);

/// The rays of one fast evaluation, laid out before any is cast.
struct FastPlan {
  std::vector<RayGroup> groups;
  BlockSummary blocks;
  std::vector<std::vector<std::uint8_t>> live;  ///< per group, its live tiles (row-major)
  int max_cells = 1;                            ///< lattice steps of the longest ray, plus one

  /// The rays in live tiles: the fast mode's cost, in rays.
  double live_rays() const;
};

/// Groups the views, lays out each group's image and marks its live tiles.
FastPlan plan_rays(const GainMap& map, std::span<const Frustum> views, const GainConfig& config);

}  // namespace vantage::detail
