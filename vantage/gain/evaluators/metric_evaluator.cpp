#include "vantage/gain/evaluators/metric_evaluator.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/models/credit_rays.hpp"
#include "vantage/gain/models/metric_cells.hpp"
#include "vantage/gain/models/metric_rays.hpp"
#include "vantage/map/block_census.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

namespace {

/// The census of the snapshot's classes, for a map without its grid.
BlockCensus census_of(const GainMap& map) {
  BlockCensus census(map.spec().dims);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const CellState state = map.value(i).state;
    if (state != CellState::kUnobserved) census.move(i, CellState::kUnobserved, state);
  }
  return census;
}

/// The blocks of `spec`'s grid, kShift cells a side.
Index3 block_dims(const GridSpec& spec) {
  return (spec.dims.array() + (FreeSpace::kBlock - 1)).matrix() / FreeSpace::kBlock;
}

/// Per block, a label over its cells: `label(i)` (>= 0) when every cell i of the block has the
/// same one, -1 when they differ or one has -1.
template <typename Label>
std::vector<std::int64_t> block_labels(const GridSpec& spec, Label&& label) {
  std::vector<std::int64_t> out(static_cast<std::size_t>(block_dims(spec).prod()), -2);
  for_block_runs(spec, 0, spec.dims.z(), [&](std::size_t block, std::size_t first, int n) {
    std::int64_t& b = out[block];
    for (std::size_t i = first; i < first + static_cast<std::size_t>(n); ++i) {
      const std::int64_t l = label(i);
      b = (b == -2 || b == l) && l >= 0 ? l : -1;
    }
  });
  return out;
}

/// The cubes of blocks of one label (>= 0), built as free_space builds its cubes of free blocks:
/// one more than the least of the seven neighbours ahead, here those of the same label.
FreeSpace cubes_of(const Index3& d, const std::vector<std::int64_t>& label) {
  FreeSpace cubes;
  cubes.dims = d;
  const auto block = [&](int x, int y, int z) {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(d.x()) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(d.y()) * z);
  };
  for (int o = 0; o < 8; ++o) {
    std::vector<std::uint8_t>& e = cubes.extent[static_cast<std::size_t>(o)];
    e.assign(label.size(), 0);
    const int sx = (o & 1) ? 1 : -1, sy = (o & 2) ? 1 : -1, sz = (o & 4) ? 1 : -1;
    for (int kz = 0; kz < d.z(); ++kz) {
      const int z = sz > 0 ? d.z() - 1 - kz : kz;
      for (int ky = 0; ky < d.y(); ++ky) {
        const int y = sy > 0 ? d.y() - 1 - ky : ky;
        for (int kx = 0; kx < d.x(); ++kx) {
          const int x = sx > 0 ? d.x() - 1 - kx : kx;
          const std::size_t b = block(x, y, z);
          if (label[b] < 0) continue;
          int least = 254;  // blocks past the grid do not limit the cube
          for (int n = 1; n < 8; ++n) {
            const int nx = x + ((n & 1) ? sx : 0), ny = y + ((n & 2) ? sy : 0),
                      nz = z + ((n & 4) ? sz : 0);
            if (nx < 0 || ny < 0 || nz < 0 || nx >= d.x() || ny >= d.y() || nz >= d.z()) continue;
            const std::size_t m = block(nx, ny, nz);
            least = std::min(least, label[m] == label[b] ? static_cast<int>(e[m]) : 0);
          }
          e[b] = static_cast<std::uint8_t>(least + 1);
        }
      }
    }
  }
  return cubes;
}

/// The cubes of free cells of one value (detail::MetricContext::uniform): the label of a free
/// cell is its code.
FreeSpace uniform_free_space(const GainMap& map) {
  return with_codes(map, [&](const auto* codes) {
    return cubes_of(
        block_dims(map.spec()), block_labels(map.spec(), [&](std::size_t i) -> std::int64_t {
          return map.value(i).state == CellState::kFree ? static_cast<std::int64_t>(codes[i]) : -1;
        }));
  });
}

/// With distances, the cubes of free cells and unobserved ones beyond D of every occupied cell
/// (detail::QuietCells); empty without.
FreeSpace far_space(const GainMap& map, const std::vector<float>& near) {
  if (near.empty()) return FreeSpace{};
  return cubes_of(block_dims(map.spec()), block_labels(map.spec(), [&](std::size_t i) {
                    const CellState state = map.value(i).state;
                    return state == CellState::kFree ||
                                   (state == CellState::kUnobserved && near[i] > kProximityCells)
                               ? 0
                               : -1;
                  }));
}

/// From the census, the cubes of blocks of unobserved cells beyond D of every occupied cell
/// (detail::MetricContext::far_unobserved): blocks of unobserved cells only, not near an occupied
/// one (near_occupied_blocks), where labelling every cell by its code took 2 ms of a ring
/// decision's 25.
FreeSpace far_unobserved_space(const BlockCensus& census, const std::vector<std::uint8_t>& near) {
  std::vector<std::int64_t> label(near.size(), -1);
  for (std::size_t b = 0; b < label.size(); ++b) {
    if (detail::far_unobserved_block(census.classes(b), near[b] != 0)) label[b] = 0;
  }
  return cubes_of(census.dims(), label);
}

/// Calls `visit(i)` with every cell of `spec`'s grid in the blocks `keep` marks (per block of
/// FreeSpace::kBlock cells a side), in ascending linear index.
template <typename Keep, typename Visit>
void for_cells_in_blocks(const GridSpec& spec, Keep&& keep, Visit&& visit) {
  for_block_runs(spec, 0, spec.dims.z(), [&](std::size_t block, std::size_t first, int n) {
    if (!keep(block)) return;
    for (std::size_t i = first; i < first + static_cast<std::size_t>(n); ++i) visit(i);
  });
}

/// The occupied cells' box and cubes that `method` needs (detail::OccupiedCells), read from the
/// blocks the census says hold one.
detail::OccupiedCells occupied_cells(const GainMap& map, const BlockCensus& census,
                                     GainMethod method) {
  const MethodTraits& traits = method_traits(method);
  const bool rear_side = traits.rear_side_rays;
  detail::OccupiedCells out;
  if (!rear_side && !traits.needs_distances) return out;
  const GridSpec& spec = map.spec();
  const auto holds = [&](std::size_t b) {
    return (census.classes(b) & class_bit(CellState::kOccupied)) != 0;
  };
  Eigen::AlignedBox3d box;
  box.setEmpty();
  for_cells_in_blocks(spec, holds, [&](std::size_t i) {
    if (map.value(i).state == CellState::kOccupied) box.extend(spec.center(spec.unravel(i)));
  });
  out.box = box;
  if (rear_side) {
    std::vector<std::int64_t> label(static_cast<std::size_t>(census.dims().prod()), 0);
    for (std::size_t b = 0; b < label.size(); ++b) label[b] = holds(b) ? -1 : 0;
    out.open = cubes_of(census.dims(), label);
  }
  return out;
}

/// The cells a metric whose value is a sum of cell credits may credit (MetricEvaluator::
/// creditable), read from the blocks near an occupied cell; none for another metric.
std::vector<std::uint32_t> creditable_cells(const GainMap& map, const std::vector<float>& near,
                                            const std::vector<std::uint8_t>& blocks,
                                            GainMethod method) {
  std::vector<std::uint32_t> out;
  if (method_traits(method).cells == nullptr || near.empty()) return out;
  for_cells_in_blocks(
      map.spec(), [&](std::size_t b) { return blocks[b] != 0; },
      [&](std::size_t i) {
        if (near[i] <= kProximityCells && map.value(i).state == CellState::kUnobserved) {
          out.push_back(static_cast<std::uint32_t>(i));
        }
      });
  return out;
}

/// The snapshot `config`'s metric reads: the classes alone for one whose value is a sum of cell
/// credits, which reads nothing else of a cell (GainMap::of_classes); the grid's values for the
/// others.
GainMap snapshot(const OccupancyGrid& grid, const GainConfig& config) {
  return method_traits(config.method).cells != nullptr
             ? GainMap::of_classes(grid, config.num_threads)
             : GainMap(grid, config.num_threads);
}

/// Throws when `config` names no metric.
void require_metric(const GainConfig& config) {
  config.validate();
  if (!is_volumetric_metric(config.method)) {
    throw std::invalid_argument(
        cat("gain.method '", to_string(config.method), "' is not a volumetric metric"));
  }
}

/// The distances the metric reads, none when it reads none.
std::vector<float> distances_for(const GainMap& map, const GainConfig& config,
                                 const BlockCensus* census = nullptr) {
  return method_traits(config.method).needs_distances
             ? occupied_distance(map, kProximityCells, config.num_threads, census)
             : std::vector<float>{};
}

}  // namespace

namespace detail {

/// The cubes the jumping walk crosses (detail::MetricContext); all null: the reference walk.
struct Spaces {
  const FreeSpace *free = nullptr, *uniform = nullptr, *far = nullptr, *open = nullptr;
  const Eigen::AlignedBox3d* occupied = nullptr;  // detail::MetricContext::occupied
  const OctantShadows* shadows = nullptr;         // detail::MetricContext::shadows
  const std::uint8_t* reach = nullptr;            // detail::MetricContext::reach
  const FreeSpace* far_unobserved = nullptr;      // detail::MetricContext::far_unobserved
  const CreditBlocks* credit_blocks = nullptr;    // detail::MetricContext::credit_blocks
};

}  // namespace detail

namespace {

using detail::Spaces;

/// What the metric's rays at `coarseness` times the pitch `config` asks for share, crossing
/// `spaces` (the reference walk when they are null).
detail::MetricContext context(const GainMap& map, const std::vector<float>& near,
                              const Spaces& spaces, const GainConfig& config, int coarseness,
                              bool count_cells) {
  return {.map = map,
          .near = near,
          .spacing = config.ray_spacing,
          .subsample = config.evaluation == GainEvaluation::kExact ? 1 : kFastSubsample,
          .free = spaces.free,
          .uniform = spaces.uniform,
          .far = spaces.far,
          .open = spaces.open,
          .occupied = spaces.occupied,
          .count_cells = count_cells,
          .coarseness = coarseness,
          .surface_rates = config.surface_rates,
          .shadows = spaces.shadows,
          .reach = spaces.reach,
          .far_unobserved = spaces.far_unobserved,
          .credit_blocks = spaces.credit_blocks};
}

/// The metric's rays at `coarseness` times the pitch `config` asks for, by the jumping walk over
/// `spaces` (the reference walk when they are null).
std::vector<ViewGain> evaluate(const GainMap& map, const std::vector<float>& near,
                               const Spaces& spaces, std::span<const Frustum> views,
                               const GainConfig& config, int coarseness, bool count_cells) {
  return method_traits(config.method)
      .metric(context(map, near, spaces, config, coarseness, count_cells), views,
              config.num_threads);
}

}  // namespace

std::vector<ViewGain> metric_view_gains(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config) {
  require_metric(config);
  const FreeSpace free = free_space(census_of(map)), uniform = uniform_free_space(map);
  return evaluate(map, distances_for(map, config), Spaces{&free, &uniform}, views, config, 1, true);
}

std::vector<ViewGain> metric_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                        const GainConfig& config) {
  return MetricEvaluator(grid, config).gains(views);
}

MetricEvaluator::MetricEvaluator(const OccupancyGrid& grid, const GainConfig& config)
    : config_((require_metric(config), config)),
      map_(snapshot(grid, config)),
      near_blocks_(detail::near_occupied_blocks(grid.census())) {
  const MethodTraits& traits = method_traits(config.method);
  const BlockCensus& census = grid.census();
  // NOTE: the shadows read the grid's classes alone, beside the chain that reads the snapshot:
  // the distances, then the passes that read them (each one serial pass, 0.3-0.7 ms on
  // tabletop-4, 1.9 ms in turn) side by side, then the codes; all in the decision's arena.
  run_with_threads(config.num_threads, [&] {
    tbb::parallel_invoke(
        [&] {
          if (lists_cells()) {
            shadows_ = OctantShadows(grid.spec(), grid.classes(), census, config.num_threads);
          }
        },
        [&] {
          near_ = distances_for(map_, config, &census);
          tbb::parallel_invoke(
              [&] { free_ = free_space(census); },
              [&] {
                if (traits.crosses_uniform) uniform_ = uniform_free_space(map_);
                if (traits.crosses_far) far_ = far_space(map_, near_);
              },
              [&] { occupied_ = occupied_cells(map_, census, config.method); },
              [&] { creditable_ = creditable_cells(map_, near_, near_blocks_, config.method); },
              [&] {
                if (traits.crosses_far_unobserved) {
                  far_unobserved_ = far_unobserved_space(census, near_blocks_);
                }
              });
          if (lists_cells()) {
            reach_ = detail::reach_codes(map_, near_, free_, config.num_threads,
                                         detail::uniform_block_codes(census, near_blocks_));
          }
        });
  });
}

Spaces MetricEvaluator::spaces() const {
  return Spaces{&free_,
                uniform_.empty() ? nullptr : &uniform_,
                far_.empty() ? nullptr : &far_,
                occupied_.open.empty() ? nullptr : &occupied_.open,
                occupied_.box ? &*occupied_.box : nullptr,
                shadows_.empty() ? nullptr : &shadows_,
                reach_.empty() ? nullptr : reach_.data(),
                far_unobserved_.empty() ? nullptr : &far_unobserved_};
}

std::vector<ViewGain> MetricEvaluator::gains(std::span<const Frustum> views, int coarseness,
                                             bool count_cells) const {
  if (coarseness < 1) {
    throw std::invalid_argument(cat("MetricEvaluator: coarseness ", coarseness, " is not >= 1"));
  }
  Spaces given = spaces();
  // NOTE: a few views' rays (the race's finalists) walked only where they may credit a cell.
  detail::CreditBlocks blocks;
  if (lists_cells() && !count_cells && coarseness == 1 && !shadows_.empty()) {
    blocks = detail::credit_blocks(map_.spec(), shadows_, creditable_);
    given.credit_blocks = &blocks;
  }
  return evaluate(map_, near_, given, views, config_, coarseness, count_cells);
}

bool MetricEvaluator::lists_cells() const { return method_traits(config_.method).cells != nullptr; }

std::vector<std::uint8_t> MetricEvaluator::sample_boost() const {
  // NOTE: 3 less the distance class, as both metrics credit a nearer cell more: the proximity
  // count by D - d, the surface model by its rates, so by at most log2 of the class's rate over
  // the farthest near class's (none under equal rates, the prior's).
  std::array<std::uint8_t, kSurfaceClasses - 1> boost{};
  const SurfaceRates& r = config_.surface_rates;
  for (std::size_t k = 0; k + 1 < kSurfaceClasses; ++k) {
    int b = static_cast<int>(kSurfaceClasses - 2 - k);
    if (config_.method == GainMethod::kSurface) {
      const double ratio = r[k] / r[kSurfaceClasses - 2];
      b = std::clamp(static_cast<int>(std::lround(std::log2(ratio > 0.0 ? ratio : 1.0))), 0, b);
    }
    boost[k] = static_cast<std::uint8_t>(b);
  }
  std::vector<std::uint8_t> out(map_.size(), 0);
  for (const std::uint32_t i : creditable_) out[i] = boost[surface_class(near_[i])];
  return out;
}

std::vector<ViewCells> MetricEvaluator::cells(std::span<const Frustum> views,
                                              std::span<const std::uint32_t> cells,
                                              std::span<StoppedRays* const> stopped) const {
  const MethodTraits& traits = method_traits(config_.method);
  if (traits.cells == nullptr) {
    throw std::invalid_argument(
        cat("MetricEvaluator: ", traits.name, "'s value is not a sum of cell credits"));
  }
  if (!stopped.empty() && stopped.size() != views.size()) {
    throw std::invalid_argument(
        cat("MetricEvaluator: ", stopped.size(), " stopped-ray sets for ", views.size(), " views"));
  }
  return traits.cells(context(map_, near_, spaces(), config_, 1, /*count_cells=*/false), views,
                      cells, config_.num_threads, stopped);
}

std::vector<ViewGain> metric_view_gains_reference(const GainMap& map,
                                                  std::span<const Frustum> views,
                                                  const GainConfig& config) {
  require_metric(config);
  return evaluate(map, distances_for(map, config), Spaces{}, views, config, 1, true);
}

}  // namespace vantage
