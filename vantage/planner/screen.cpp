#include "vantage/planner/screen.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/methods.hpp"
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
/// The margin is waived when both sides' samples hold at least this many targets' worth of
/// gain (Kish's effective sample size, (sum g)^2 / sum g^2): then the gain is spread over so many
/// cells that the sum is close to normal and 3 standard errors bound it (an office stop's sweep).
constexpr double kEffectiveTargets = 1000.0;

/// The unobserved cells of each stage's sample that the stage before did not hold, in linear
/// order.
std::array<std::vector<std::uint32_t>, kStageBits.size()> sample_cells(const GainMap& map) {
  std::array<std::vector<std::uint32_t>, kStageBits.size()> stages;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (map.value(i).state != CellState::kUnobserved) continue;
    for (std::size_t s = 0; s < kStageBits.size(); ++s) {
      if (in_cell_sample(i, kStageBits[s])) {
        stages[s].push_back(static_cast<std::uint32_t>(i));
        break;
      }
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

  std::optional<GainMap> map;                   // the snapshot the samples read
  std::vector<SampleSums> sums(frusta.size());  // per view, over the stages so far
  std::size_t ran = 0;                          // stages run
  if (n > 1) {
    map.emplace(grid, config.num_threads);
    const auto stages = sample_cells(*map);
    for (std::size_t s = 0; s < stages.size() && alive.size() > 1; ++s, ++ran) {
      std::vector<Frustum> views;  // the alive candidates' views, in candidate order
      for (const std::size_t c : alive) {
        views.insert(views.end(), frusta.begin() + first[c], frusta.begin() + first[c + 1]);
      }
      const std::vector<SampleSums> add = sampled_view_gains(*map, views, stages[s], config);
      std::size_t k = 0;
      for (const std::size_t c : alive) {
        for (std::size_t v = first[c]; v < first[c + 1]; ++v, ++k) {
          sums[v].gain += add[k].gain;
          sums[v].gain_sq += add[k].gain_sq;
          sums[v].cells += add[k].cells;
          sums[v].cells_sq += add[k].cells_sq;
          sums[v].targets += add[k].targets;
          sums[v].shared += add[k].shared;
        }
      }
      // Horvitz-Thompson: each cell is in the sample with probability 1/rate, so rate * sum is
      // unbiased, with variance estimated by rate (rate - 1) * (sum of squares).
      const double rate = std::ldexp(1.0, kStageBits[s]);
      std::vector<double> estimate(n, 0.0), error(n, 0.0), effective(n, 0.0);
      std::vector<std::size_t> sampled(n, 0);
      for (const std::size_t c : alive) {
        ViewGain g;
        double sum = 0.0, sum_sq = 0.0;  // of the sampled values, over the candidate's views
        bool disjoint = true;
        for (std::size_t v = first[c]; v < first[c + 1]; ++v) {
          g.gain += rate * sums[v].gain;
          g.cells += rate * sums[v].cells;
          g.targets += static_cast<std::size_t>(rate) * sums[v].targets;
          const double sq = cells_objective ? sums[v].cells_sq : sums[v].gain_sq;
          sum += cells_objective ? sums[v].cells : sums[v].gain;
          sum_sq += sq;
          error[c] += std::sqrt(rate * (rate - 1.0) * sq);  // sd of a sum <= sum of the sds
          sampled[c] += sums[v].targets;
          disjoint =
              disjoint && sums[v].shared == 0 && frusta[v].origin() == frusta[first[c]].origin();
        }
        // NOTE: views from one origin that share no sampled cell (an office stop's sweep) sum
        // independent samples, whose variances add.
        if (disjoint) error[c] = std::sqrt(rate * (rate - 1.0) * sum_sq);
        out.gains[c] = g;
        estimate[c] = cells_objective ? g.cells : g.gain;
        effective[c] = sum_sq > 0.0 ? sum * sum / sum_sq : 0.0;
      }
      std::size_t leader = alive.front();
      for (const std::size_t c : alive) {
        if (estimate[c] > estimate[leader]) leader = c;
      }
      if (sampled[leader] < kMinTargets) continue;
      std::vector<std::size_t> kept;
      for (const std::size_t c : alive) {
        const double margin =
            std::min(effective[c], effective[leader]) >= kEffectiveTargets ? 0.0 : kMargin;
        const bool beaten =
            c != leader && sampled[c] >= kMinTargets &&
            estimate[c] + kZ * (error[c] + error[leader]) < (1.0 - margin) * estimate[leader];
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
  // NOTE: an exact evaluation (the survival reading's only one) has evaluated the samples'
  // cells of the candidates left exactly already: only the cells outside them remain.
  const bool reuse = ran > 0 && (!method_traits(config.method).fast_mode ||
                                 config.evaluation == GainEvaluation::kExact);
  const std::vector<ViewGain> full =
      reuse ? exact_view_gains(*map, views, config, kStageBits[ran - 1])
            : evaluate_views(grid, views, config);
  std::size_t k = 0;
  for (const std::size_t c : alive) {
    ViewGain sum;
    for (std::size_t v = first[c]; v < first[c + 1]; ++v, ++k) {
      sum.gain += full[k].gain + (reuse ? sums[v].gain : 0.0);
      sum.cells += full[k].cells + (reuse ? sums[v].cells : 0.0);
      sum.targets += full[k].targets + (reuse ? sums[v].targets : 0);
    }
    out.gains[c] = sum;
  }
  return out;
}

Screening sample_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                            std::span<const std::size_t> first, const GainConfig& config,
                            int bits) {
  const GainMap map(grid, config.num_threads);
  const std::vector<SampleSums> sums =
      sampled_view_gains(map, frusta, unobserved_sample(ClassMap(grid), bits), config);
  const double rate = std::ldexp(1.0, bits);  // Horvitz-Thompson: rate * sum is unbiased
  const std::size_t n = first.size() - 1;
  Screening out;
  out.gains.assign(n, ViewGain{});
  out.estimated.assign(n, true);
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t v = first[c]; v < first[c + 1]; ++v) {
      out.gains[c].gain += rate * sums[v].gain;
      out.gains[c].cells += rate * sums[v].cells;
      out.gains[c].targets += static_cast<std::size_t>(rate) * sums[v].targets;
    }
  }
  return out;
}

}  // namespace vantage::detail
