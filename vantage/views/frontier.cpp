#include "vantage/views/frontier.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "vantage/util/text.hpp"
#include "vantage/views/candidate_set.hpp"

namespace vantage {
namespace {

/// The z layers whose cell centres lie in [min_z, max_z], as [first, last]; empty when last <
/// first.
std::pair<int, int> band_layers(const GridSpec& spec, const FrontierConfig& config) {
  const double lo = std::ceil((config.min_z - spec.origin.z()) / spec.resolution - 0.5);
  const double hi = std::floor((config.max_z - spec.origin.z()) / spec.resolution - 0.5);
  const double top = spec.dims.z() - 1;
  return {static_cast<int>(std::clamp(lo, 0.0, top + 1.0)),
          static_cast<int>(std::clamp(hi, -1.0, top))};
}

bool has_unobserved_neighbour(const OccupancyGrid& grid, const Index3& c) {
  const GridSpec& spec = grid.spec();
  for (int axis = 0; axis < 3; ++axis) {
    for (const int step : {-1, 1}) {
      Index3 n = c;
      n[axis] += step;
      if (spec.contains(n) && grid.is_unobserved(spec.linear(n))) return true;
    }
  }
  return false;
}

}  // namespace

void FrontierConfig::validate() const {
  if (std::isnan(min_z) || std::isnan(max_z) || !(min_z <= max_z)) {
    throw std::invalid_argument(
        cat("frontier.min_z (", min_z, ") must not exceed frontier.max_z (", max_z, ")"));
  }
  if (min_cells < 1) {
    throw std::invalid_argument(cat("frontier.min_cells must be >= 1, got ", min_cells));
  }
  if (!(max_radius >= 0.0 && std::isfinite(max_radius))) {
    throw std::invalid_argument(cat("frontier.max_radius must be >= 0 m, got ", max_radius));
  }
}

bool is_frontier_cell(const OccupancyGrid& grid, std::size_t linear, const FrontierConfig& config) {
  if (grid.state(linear) != CellState::kFree) return false;
  const GridSpec& spec = grid.spec();
  const Index3 c = spec.unravel(linear);
  const double z = spec.center(c).z();
  if (z < config.min_z || z > config.max_z) return false;
  return has_unobserved_neighbour(grid, c);
}

std::vector<std::uint32_t> frontier_cells(const OccupancyGrid& grid, const FrontierConfig& config) {
  config.validate();
  const GridSpec& spec = grid.spec();
  const auto [first, last] = band_layers(spec, config);
  std::vector<std::uint32_t> cells;
  for (int z = first; z <= last; ++z) {
    for (int y = 0; y < spec.dims.y(); ++y) {
      for (int x = 0; x < spec.dims.x(); ++x) {
        const Index3 c(x, y, z);
        const std::size_t i = spec.linear(c);
        if (grid.state(i) == CellState::kFree && has_unobserved_neighbour(grid, c)) {
          cells.push_back(static_cast<std::uint32_t>(i));
        }
      }
    }
  }
  return cells;
}

std::vector<FrontierRegion> frontier_regions(const OccupancyGrid& grid,
                                             const FrontierConfig& config) {
  const std::vector<std::uint32_t> cells = frontier_cells(grid, config);
  if (cells.empty()) return {};
  const GridSpec& spec = grid.spec();
  // NOTE: a dense label per cell of the band's layers (no hashing per cell): -1 = not a
  // frontier cell, -2 = a frontier cell not yet in a region, >= 0 = taken.
  const auto [first, last] = band_layers(spec, config);
  const std::size_t layer = static_cast<std::size_t>(spec.dims.x()) * spec.dims.y();
  const std::size_t offset = layer * static_cast<std::size_t>(first);
  std::vector<int> label(layer * static_cast<std::size_t>(last - first + 1), -1);
  for (const std::uint32_t i : cells) label[i - offset] = -2;

  const double r2 = config.max_radius * config.max_radius;
  std::vector<FrontierRegion> regions;
  std::vector<std::uint32_t> queue;
  int next_label = 0;
  for (const std::uint32_t seed : cells) {
    if (label[seed - offset] != -2) continue;
    const Eigen::Vector3d seed_centre = spec.center(spec.unravel(seed));
    const int id = next_label++;
    label[seed - offset] = id;
    queue.assign(1, seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const Index3 c = spec.unravel(queue[head]);
      for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const Index3 n = c + Index3(dx, dy, dz);
            if (!spec.contains(n) || n.z() < first || n.z() > last) continue;
            const std::size_t j = spec.linear(n);
            if (label[j - offset] != -2) continue;
            if (r2 > 0.0 && (spec.center(n) - seed_centre).squaredNorm() > r2) continue;
            label[j - offset] = id;
            queue.push_back(static_cast<std::uint32_t>(j));
          }
        }
      }
    }
    if (queue.size() < static_cast<std::size_t>(config.min_cells)) continue;
    FrontierRegion region;
    region.cells = queue;
    for (const std::uint32_t i : queue) region.centroid += spec.center(spec.unravel(i));
    region.centroid /= static_cast<double>(queue.size());
    regions.push_back(std::move(region));
  }
  return regions;
}

PlacedViews frontier_candidates(const CandidateSite& site, const CandidateParams& params) {
  if (site.grid == nullptr) {
    throw std::invalid_argument("frontier candidates are found in a map: none was given");
  }
  const OccupancyGrid& grid = *site.grid;
  FrontierConfig config;
  const double half = 0.5 * grid.spec().resolution;
  if (params.band) {
    config.min_z = params.band->first - half;
    config.max_z = params.band->second + half;
  }
  const std::vector<FrontierRegion> regions = frontier_regions(grid, config);
  PlacedViews views;
  std::size_t dropped = 0;
  for (const FrontierRegion& region : regions) {
    Eigen::Vector3d place = region.centroid;
    if (params.band) place.z() = std::clamp(place.z(), params.band->first, params.band->second);
    // NOTE: a robot cannot stand in unknown or occupied space: such a centroid is dropped.
    const std::optional<Index3> cell = grid.spec().find(place);
    if (!cell || grid.state(grid.spec().linear(*cell)) != CellState::kFree) {
      dropped += 4;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::AngleAxisd(k * std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ())
                          .toRotationMatrix();
      pose.translation() = place;
      views.poses.push_back(pose);
    }
  }
  if (views.poses.empty()) {
    throw std::runtime_error(
        regions.empty()
            ? std::string(params.band ? "the map has no frontier regions at --sensor-height to "
                                        "plan from"
                                      : "the map has no frontier regions to plan from")
            : cat("none of the ", regions.size(),
                  " frontier regions' centroids lies in a known free cell (try --sensor-height)"));
  }
  views.note = cat(
      "frontier: ", regions.size(), " regions, ", views.poses.size(), " views",
      dropped > 0 ? cat(" (", dropped, " dropped: their place is not known free)") : std::string());
  return views;
}

}  // namespace vantage
