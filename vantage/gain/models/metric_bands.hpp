#pragma once
/// @file
/// A cell-sum metric's value by its own rays (models/metric_cells.hpp), each view's rows cast in
/// bands side by side and joined to the one pass's value, bit for bit.

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "vantage/gain/models/credit_rays.hpp"
#include "vantage/gain/models/metric_cells.hpp"
#include "vantage/gain/models/metric_rays.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage::detail {

/// Every view's value under `Metric` (cell_sum) by its own rays, as all_views gives it with the
/// walk by codes (CodeWalk), bit for bit, but each view's rows cast in bands side by side, so that
/// a few views keep both threads busy (the swept search's finalists, the chosen view's report:
/// issue 52). Each band credits and counts cells by a stamp of its own and logs them (Stamp::add);
/// the logs, joined band by band, keep each cell's first credit and count, in the order one pass
/// over the rows adds them: a cell's credit depends on its ray alone, not on which cells earlier
/// rays took. The same for any thread count.
template <typename Metric>
std::vector<ViewGain> all_views_in_bands(const MetricContext& ctx, std::span<const Frustum> views,
                                         int num_threads) {
  static_assert(cell_sum<Metric>());
  // NOTE: at least 16 bands in all, so that both threads stay busy to the end; one band a view
  // when the views are many, which needs no logs unless only some rays are walked.
  constexpr std::size_t kLeastBands = 16, kMostBands = 8;
  const std::size_t bands = std::clamp<std::size_t>(
      (kLeastBands + views.size() - 1) / std::max<std::size_t>(views.size(), 1), 1, kMostBands);
  // NOTE: the rays that may credit a cell, view by view, where the cells need not be counted.
  const bool masked = ctx.credit_blocks != nullptr && ctx.shadows != nullptr && !ctx.count_cells;
  if (bands == 1 && !masked) return all_views<Metric, CodeWalk>(ctx, views, num_threads);
  using Log = std::vector<std::pair<std::uint32_t, double>>;
  struct Band {
    Log credits, seen;
  };
  struct Marks {
    std::vector<std::uint64_t> credit, seen;
  };
  std::vector<std::vector<std::uint8_t>> walked(views.size());
  std::vector<Band> parts(views.size() * bands);
  std::vector<ViewGain> gains(views.size());
  const std::size_t words = (ctx.map.size() + 63) / 64;
  tbb::enumerable_thread_specific<Marks> marks([words] {
    return Marks{std::vector<std::uint64_t>(words, 0), std::vector<std::uint64_t>(words, 0)};
  });
  // NOTE: a stamp is left as found: only the bits its log holds are cleared.
  const auto unmark = [](std::vector<std::uint64_t>& bits, const Log& log) {
    for (const auto& [i, x] : log) bits[i >> 6] &= ~(std::uint64_t{1} << (i & 63));
  };
  run_with_threads(num_threads, [&] {
    if (masked) {
      tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
        const RayImage image(ctx.map.spec(), ctx.spacing, ctx.subsample, ctx.coarseness, views[v]);
        walked[v] = rays_that_may_credit(image, ctx.map.spec(), *ctx.shadows, *ctx.credit_blocks);
      });
    }
    tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t task) {
      Marks& m = marks.local();
      Band& part = parts[task];
      Stamp credit{m.credit, &part.credits}, seen{m.seen, &part.seen};
      Metric metric = make_metric<Metric>(ctx);
      view_rays(ctx, views[task / bands], metric, credit, seen, CodeWalk{},
                static_cast<int>(task % bands), static_cast<int>(bands), walked[task / bands]);
      unmark(m.credit, part.credits);
      unmark(m.seen, part.seen);
    });
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      Marks& m = marks.local();
      Stamp credit{m.credit}, seen{m.seen};
      Metric metric = make_metric<Metric>(ctx);
      ViewGain& out = gains[v];
      for (std::size_t b = 0; b < bands; ++b) {
        for (const auto& [i, x] : parts[v * bands + b].credits) credit.add(i, x, metric.sum);
        for (const auto& [i, x] : parts[v * bands + b].seen) seen.add(i, x, out.cells);
      }
      for (std::size_t b = 0; b < bands; ++b) {
        unmark(m.credit, parts[v * bands + b].credits);
        unmark(m.seen, parts[v * bands + b].seen);
      }
      const RayImage image(ctx.map.spec(), ctx.spacing, ctx.subsample, ctx.coarseness, views[v]);
      out.gain = metric.value(image.count());
      out.targets = static_cast<std::size_t>(out.cells);
    });
  });
  return gains;
}

}  // namespace vantage::detail
