#pragma once
/// @file
/// The baseline of the benchmarks: the same map in an octomap::OcTree, and view gains computed the
/// way OctoMap-based planners compute them.

#include <octomap/OcTree.h>

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "vantage/gain/view_gain.hpp"
#include "vantage/map/occupancy_grid.hpp"

namespace vantage::bench {

/// The grid in an OcTree of the same resolution, with the same sensor model: every cell that is
/// not unknown becomes a leaf holding its log-odds. The grid's cell bounds must lie on multiples
/// of the resolution (OctoMap's keys); throws std::invalid_argument otherwise.
std::unique_ptr<octomap::OcTree> to_octree(const OccupancyGrid& grid);

/// What the OctoMap way of evaluating did.
struct OctoMapGains {
  std::vector<ViewGain> gains;
  std::size_t rays = 0;  ///< pixel rays cast
  std::size_t keys = 0;  ///< cells looked up in the tree
};

/// Gains of the views the way OctoMap-based planners compute them: per view a pinhole ray per
/// pixel at the pitch of the fast mode (one ray per ray_spacing cells at the farthest cell in
/// view), each ray's cells from OcTree::computeRayKeys, each cell looked up with OcTree::search,
/// the model of docs/model.md run along the ray (the same odds form, the same early stop, the same
/// table of states before the grid), and each unobserved cell credited once per view, by the
/// first ray that reaches it, through a KeySet. Views run in parallel (config.num_threads).
OctoMapGains octomap_view_gains(const octomap::OcTree& tree, const GridSpec& spec,
                                const OccupancyParams& params, std::span<const Frustum> views,
                                const GainConfig& config);

}  // namespace vantage::bench
