#include "vantage/gain/fast.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/fast_cast.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/metrics.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage {
namespace detail {
namespace {

/// The steady states of the codes that fill whole blocks and are not occupied.
template <typename Model>
std::vector<std::vector<RayOdds>> steady_states(const GainMap& map, const BlockSummary& blocks,
                                                double alpha, int max_cells) {
  const std::span<const GainMap::Value> values = map.values();
  std::vector<std::vector<RayOdds>> steady(values.size());
  std::vector<bool> wanted(values.size(), false);
  for (const std::uint16_t c : blocks.code) {
    if (c != BlockSummary::kMixed && values[c].state != CellState::kOccupied) wanted[c] = true;
  }
  for (std::size_t c = 0; c < values.size(); ++c) {
    if (wanted[c]) steady[c] = Model::uniform_run(alpha, values[c].p, max_cells + 1);
  }
  return steady;
}

/// Casts every live ray of every group: one task per image row; the row sums are added per view
/// in row order, so the result does not depend on the threads.
template <typename CodeT, typename Model>
std::vector<ViewGain> cast_all(const CastContext<Model>& cx, const CodeT* codes,
                               const FastPlan& plan, std::size_t num_views) {
  const std::vector<RayGroup>& groups = plan.groups;
  std::vector<std::size_t> first_row(groups.size() + 1, 0);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    first_row[i + 1] = first_row[i] + static_cast<std::size_t>(groups[i].rows);
  }
  std::vector<RaySum> row_sums(first_row.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, row_sums.size()), [&](const auto& range) {
    std::size_t group = static_cast<std::size_t>(
        std::upper_bound(first_row.begin(), first_row.end(), range.begin()) - first_row.begin() -
        1);
    for (std::size_t r = range.begin(); r != range.end(); ++r) {
      while (r >= first_row[group + 1]) ++group;
      const RayGroup& rays = groups[group];
      const int row = static_cast<int>(r - first_row[group]);
      RaySum sum;
      const std::uint8_t* tiles =
          plan.live[group].data() +
          static_cast<std::ptrdiff_t>(row / kTile) * ((rays.cols + kTile - 1) / kTile);
      for (int col = 0; col < rays.cols; ++col) {
        if (tiles[col / kTile] == 0) {
          col += kTile - 1 - col % kTile;  // the rest of this tile
          continue;
        }
        sum.add(cast_ray(cx, codes, rays, col, row), rays.members.size());
      }
      row_sums[r] = sum;
    }
  });
  std::vector<ViewGain> gains(num_views);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    for (std::size_t r = first_row[i]; r < first_row[i + 1]; ++r) {
      for (std::size_t k = 0; k < groups[i].members.size(); ++k) {
        ViewGain& g = gains[groups[i].members[k]];
        g.gain += row_sums[r].gain[k];
        g.cells += row_sums[r].cells[k];
        g.targets += row_sums[r].targets[k];
      }
    }
  }
  return gains;
}

template <typename Model>
std::vector<ViewGain> cast_with(const FastPlan& plan, const GainMap& map,
                                std::span<const Frustum> views, const GainConfig& config) {
  CastContext<Model> cx{&map.spec(),
                        map.values().data(),
                        &plan.blocks,
                        RayTables<Model>(config.alpha, map.params().p_min, plan.max_cells),
                        steady_states<Model>(map, plan.blocks, config.alpha, plan.max_cells),
                        config.epsilon};
  switch (map.code_width()) {
    case 1:
      return cast_all(cx, map.codes<std::uint8_t>(), plan, views.size());
    case 2:
      return cast_all(cx, map.codes<std::uint16_t>(), plan, views.size());
    default:
      return cast_all(cx, map.codes<std::uint32_t>(), plan, views.size());
  }
}

}  // namespace

std::vector<ViewGain> cast_rays(const FastPlan& plan, const GainMap& map,
                                std::span<const Frustum> views, const GainConfig& config) {
  return cast_with<PaperModel>(plan, map, views, config);
}

}  // namespace detail

template <typename Model>
std::vector<ViewGain> fast_view_gains(const GainMap& map, std::span<const Frustum> views,
                                      const GainConfig& config) {
  config.validate();
  require_model_method(config, "fast_view_gains");
  // NOTE: only the paper's model has rays cast outward (methods.hpp, fast_mode).
  if (!method_traits(config.method).fast_mode) {
    return exact_view_gains<Model>(map, views, config);
  }
  std::vector<ViewGain> gains;
  run_with_threads(config.num_threads, [&] {
    const detail::FastPlan plan = detail::plan_rays(map, views, config);
    gains = detail::cast_with<Model>(plan, map, views, config);
  });
  return gains;
}

template std::vector<ViewGain> fast_view_gains<PaperModel>(const GainMap&, std::span<const Frustum>,
                                                           const GainConfig&);
template std::vector<ViewGain> fast_view_gains<BlindModel>(const GainMap&, std::span<const Frustum>,
                                                           const GainConfig&);

std::vector<ViewGain> fast_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                      const GainConfig& config) {
  config.validate();
  return fast_view_gains(GainMap(grid, config.num_threads), views, config);
}

}  // namespace vantage
