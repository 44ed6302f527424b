#include "vantage/gain/evaluators/exact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "vantage/gain/evaluators/target_sums.hpp"
#include "vantage/gain/evaluators/with_predictor.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/hash.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using detail::longest_ray;
using detail::sum_by_origin;

/// Unobserved cells before the target on its ray, or -1 when an occupied cell lies before it
/// (the cells GridWalk takes, as the survival reading's exact evaluation).
int unobserved_before(const GainMap& map, const Eigen::Vector3d& origin, const Index3& target) {
  const GridSpec& spec = map.spec();
  GridWalk walk(spec, origin, target);
  if (!walk.entered()) return -1;  // never seen: predicts nothing, as exact_view_gains
  int unobserved = 0;
  for (; !walk.at_end(); walk.advance()) {
    switch (map.value(walk.linear()).state) {
      case CellState::kOccupied:
        return -1;
      case CellState::kUnobserved:
        ++unobserved;
        break;
      case CellState::kFree:
        break;
    }
  }
  return unobserved;
}

}  // namespace

std::vector<double> survival_cells_by_alpha(const OccupancyGrid& grid,
                                            std::span<const Frustum> views,
                                            std::span<const double> alphas, int num_threads) {
  const GainMap map(grid, num_threads);
  const GridSpec& spec = map.spec();
  const int cells = longest_ray(spec, views);
  // NOTE: counts, not sums of powers: integers add up the same in any order, so the histogram,
  // and every E(a) from it, is the same for any thread count.
  std::vector<std::uint64_t> histogram(static_cast<std::size_t>(cells) + 1, 0);
  run_with_threads(num_threads, [&] {
    for (const Frustum& view : views) {
      const CellBox box = cells_under(spec, view);
      if (box.empty()) continue;
      const Eigen::Vector3d origin = view.origin();
      const int ny = box.hi.y() - box.lo.y() + 1;
      const int nz = box.hi.z() - box.lo.z() + 1;
      const auto rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
      tbb::combinable<std::vector<std::uint64_t>> partial(
          [&] { return std::vector<std::uint64_t>(histogram.size(), 0); });
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows), [&](const auto& range) {
        std::vector<std::uint64_t>& counts = partial.local();
        for (std::size_t row = range.begin(); row != range.end(); ++row) {
          Index3 cell(0, box.lo.y() + static_cast<int>(row % static_cast<std::size_t>(ny)),
                      box.lo.z() + static_cast<int>(row / static_cast<std::size_t>(ny)));
          for (cell.x() = box.lo.x(); cell.x() <= box.hi.x(); ++cell.x()) {
            if (map.value(spec.linear(cell)).state != CellState::kUnobserved ||
                !view.contains(spec.center(cell))) {
              continue;
            }
            const int n = unobserved_before(map, origin, cell);
            if (n >= 0) ++counts[static_cast<std::size_t>(n)];
          }
        }
      });
      partial.combine_each([&](const std::vector<std::uint64_t>& counts) {
        for (std::size_t n = 0; n < counts.size(); ++n) histogram[n] += counts[n];
      });
    }
  });
  std::vector<double> expected;
  for (const double alpha : alphas) {
    double sum = 0.0, power = 1.0;  // eq. (9)-(10), the survival reading: v_M = a^n
    for (const std::uint64_t count : histogram) {
      sum += static_cast<double>(count) * power;
      power *= alpha;
    }
    expected.push_back(sum);
  }
  return expected;
}

std::vector<std::vector<std::size_t>> views_by_origin(std::span<const Frustum> views) {
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Eigen::Vector3d origin = views[v].origin();
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const auto& g) { return views[g.front()].origin() == origin; });
    if (it == groups.end()) {
      groups.push_back({v});
    } else {
      it->push_back(v);
    }
  }
  return groups;
}

template <typename Model>
std::vector<ViewGain> exact_view_gains(const GainMap& map, std::span<const Frustum> views,
                                       const GainConfig& config) {
  config.validate();
  require_model_method(config, "exact_view_gains");
  return detail::with_predictor<Model>(
      config, map.params().p_min, longest_ray(map.spec(), views), [&](const auto& predict) {
        return sum_by_origin(map, views, config.num_threads,
                             [&](const Eigen::Vector3d& origin, const Index3& target) {
                               return predict(map, origin, target);
                             });
      });
}

template std::vector<ViewGain> exact_view_gains<PaperModel>(const GainMap&,
                                                            std::span<const Frustum>,
                                                            const GainConfig&);
template std::vector<ViewGain> exact_view_gains<BlindModel>(const GainMap&,
                                                            std::span<const Frustum>,
                                                            const GainConfig&);

bool in_cell_sample(std::uint64_t i, int bits) {
  return bits <= 0 || (mix64(i) >> (64 - bits)) == 0;
}

namespace {

/// Calls `f(i)` for every unobserved cell of the grid's classes, in ascending linear index.
template <typename F>
void for_each_unobserved(const ClassMap& map, F&& f) {
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (map.state(i) == CellState::kUnobserved) f(i);
  }
}

}  // namespace

std::vector<std::uint32_t> unobserved_sample(const ClassMap& map, int bits) {
  std::vector<std::uint32_t> sample;
  for_each_unobserved(map, [&](std::size_t i) {
    if (in_cell_sample(i, bits)) sample.push_back(static_cast<std::uint32_t>(i));
  });
  return sample;
}

std::vector<std::vector<std::uint32_t>> unobserved_by_sample(const ClassMap& map,
                                                             std::size_t max_size) {
  std::vector<std::uint32_t> cells;
  for_each_unobserved(map, [&](std::size_t i) { cells.push_back(static_cast<std::uint32_t>(i)); });
  return cells_by_sample(cells, max_size);
}

std::vector<std::vector<std::uint32_t>> cells_by_sample(std::span<const std::uint32_t> cells,
                                                        std::size_t max_size,
                                                        std::span<const std::uint8_t> boost) {
  constexpr int kTop = 63;
  std::vector<std::vector<std::uint32_t>> lists(kTop + 1);
  std::array<std::size_t, kMostBoost + 1> boosted{};  // cells per boost
  for (const std::uint32_t i : cells) {
    // NOTE: in the sample of b bits exactly when the hash's top b - o bits are zero.
    const int o = boost.empty() ? 0 : boost[i];
    const int zeros = std::min(std::countl_zero(mix64(i)) + o, kTop);
    lists[static_cast<std::size_t>(zeros)].push_back(i);
    ++boosted[static_cast<std::size_t>(o)];
  }
  // The expected size of the sample of b bits [cells].
  const auto expected = [&](int b) {
    double n = 0.0;
    for (int o = 0; o <= kMostBoost; ++o) {
      n += std::ldexp(static_cast<double>(boosted[static_cast<std::size_t>(o)]),
                      -std::max(0, b - o));
    }
    return n;
  };
  int bits = 0;
  while (bits < kTop && expected(bits) > static_cast<double>(max_size)) ++bits;
  // The smallest sample's list holds every cell of it: the lists past it folded in, in order.
  std::vector<std::uint32_t>& smallest = lists[static_cast<std::size_t>(bits)];
  for (std::size_t k = static_cast<std::size_t>(bits) + 1; k < lists.size(); ++k) {
    smallest.insert(smallest.end(), lists[k].begin(), lists[k].end());
  }
  std::sort(smallest.begin(), smallest.end());
  lists.resize(static_cast<std::size_t>(bits) + 1);
  return lists;
}

std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config) {
  config.validate();
  return exact_view_gains(GainMap(grid, config.num_threads), views, config);
}

ViewGain exact_view_gain(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config) {
  return exact_view_gains(grid, std::span<const Frustum>(&view, 1), config).front();
}

double exact_cell_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                       const Index3& target, const GainConfig& config) {
  config.validate();
  if (!grid.spec().contains(target)) {
    throw std::out_of_range(cat("target cell (", target.x(), ", ", target.y(), ", ", target.z(),
                                ") is outside the grid"));
  }
  GainConfig literal = config;
  literal.epsilon = 0.0;  // one ray, taken to its end
  return detail::with_predictor(
      literal, grid.params().p_min, max_ray_cells(grid.spec(), origin),
      [&](const auto& predict) { return predict(detail::GridCells{grid}, origin, target).gain; });
}

}  // namespace vantage
