#include "vantage/planner/screen.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage::detail {
namespace {

/// Sampling stages: a cell is in stage s's sample when the top kStageBits[s] bits of its hash
/// are zero, so each stage's sample holds the one before (rates 1/64, 1/16, 1/4).
constexpr std::array<int, 3> kStageBits = {6, 4, 2};
/// A candidate is dropped when its estimate plus kZ standard errors (its own and the leader's,
/// added: a bound whatever their correlation) stays below (1 - kMargin) of the leader's estimate.
/// NOTE: the margin keeps near-ties for the full evaluation, which decides them; a sample's gain
/// sits in few frontier cells, so its error is far from normal and z alone is not trusted.
constexpr double kZ = 3.0;
constexpr double kMargin = 0.1;
/// Neither side of a comparison is trusted with fewer sampled targets than this.
constexpr std::size_t kMinTargets = 32;

/// SplitMix64 of the cell's index: the sample must not line up with the lattice (a table's plane
/// is a lattice plane).
std::uint64_t cell_hash(std::uint64_t i) {
  std::uint64_t z = i + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// The unobserved cells of each stage's sample that the stage before did not hold, in linear
/// order.
std::array<std::vector<std::uint32_t>, kStageBits.size()> sample_cells(const GainMap& map) {
  std::array<std::vector<std::uint32_t>, kStageBits.size()> stages;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::uint64_t h = cell_hash(i);
    for (std::size_t s = 0; s < kStageBits.size(); ++s) {
      if ((h >> (64 - kStageBits[s])) != 0) continue;
      if (map.value(i).state == CellState::kUnobserved) {
        stages[s].push_back(static_cast<std::uint32_t>(i));
      }
      break;
    }
  }
  return stages;
}

}  // namespace

Screening screen_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                            std::span<const std::size_t> first, const GainConfig& config,
                            bool cells_objective) {
  const std::size_t n = first.size() - 1;
  Screening out;
  out.gains.assign(n, ViewGain{});
  out.estimated.assign(n, false);
  std::vector<std::size_t> alive(n);
  for (std::size_t c = 0; c < n; ++c) alive[c] = c;

  if (n > 1) {
    const GainMap map(grid, config.num_threads);
    const auto stages = sample_cells(map);
    std::vector<SampleSums> sums(frusta.size());  // per view, over the stages so far
    for (std::size_t s = 0; s < stages.size() && alive.size() > 1; ++s) {
      std::vector<Frustum> views;  // the alive candidates' views, in candidate order
      for (const std::size_t c : alive) {
        views.insert(views.end(), frusta.begin() + first[c], frusta.begin() + first[c + 1]);
      }
      const std::vector<SampleSums> add = sampled_view_gains(map, views, stages[s], config);
      std::size_t k = 0;
      for (const std::size_t c : alive) {
        for (std::size_t v = first[c]; v < first[c + 1]; ++v, ++k) {
          sums[v].gain += add[k].gain;
          sums[v].gain_sq += add[k].gain_sq;
          sums[v].cells += add[k].cells;
          sums[v].cells_sq += add[k].cells_sq;
          sums[v].targets += add[k].targets;
        }
      }
      // Horvitz-Thompson: each cell is in the sample with probability 1/rate, so rate * sum is
      // unbiased, with variance estimated by rate (rate - 1) * (sum of squares).
      const double rate = std::ldexp(1.0, kStageBits[s]);
      std::vector<double> estimate(n, 0.0), error(n, 0.0);
      std::vector<std::size_t> sampled(n, 0);
      for (const std::size_t c : alive) {
        ViewGain g;
        for (std::size_t v = first[c]; v < first[c + 1]; ++v) {
          g.gain += rate * sums[v].gain;
          g.cells += rate * sums[v].cells;
          g.targets += static_cast<std::size_t>(rate) * sums[v].targets;
          const double sq = cells_objective ? sums[v].cells_sq : sums[v].gain_sq;
          error[c] += std::sqrt(rate * (rate - 1.0) * sq);  // sd of a sum <= sum of the sds
          sampled[c] += sums[v].targets;
        }
        out.gains[c] = g;
        estimate[c] = cells_objective ? g.cells : g.gain;
      }
      std::size_t leader = alive.front();
      for (const std::size_t c : alive) {
        if (estimate[c] > estimate[leader]) leader = c;
      }
      if (sampled[leader] < kMinTargets) continue;
      std::vector<std::size_t> kept;
      for (const std::size_t c : alive) {
        const bool beaten =
            c != leader && sampled[c] >= kMinTargets &&
            estimate[c] + kZ * (error[c] + error[leader]) < (1.0 - kMargin) * estimate[leader];
        if (beaten) {
          out.estimated[c] = true;
        } else {
          kept.push_back(c);
        }
      }
      alive = std::move(kept);
    }
  }

  std::vector<Frustum> views;
  for (const std::size_t c : alive) {
    views.insert(views.end(), frusta.begin() + first[c], frusta.begin() + first[c + 1]);
  }
  const std::vector<ViewGain> full = evaluate_views(grid, views, config);
  std::size_t k = 0;
  for (const std::size_t c : alive) {
    ViewGain sum;
    for (std::size_t v = first[c]; v < first[c + 1]; ++v, ++k) {
      sum.gain += full[k].gain;
      sum.cells += full[k].cells;
      sum.targets += full[k].targets;
    }
    out.gains[c] = sum;
  }
  return out;
}

}  // namespace vantage::detail
