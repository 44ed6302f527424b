// The sequence's parts that need no map (sequence.hpp): its settings checked, the shortest open
// tour through a few views, and the joint value of per-cell visibilities.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "vantage/planner/sequence.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

void SequenceConfig::validate() const {
  if (horizon < 1 || horizon > kMaxHorizon) {
    throw std::invalid_argument(
        cat("planner.sequence.horizon must lie in [1, ", kMaxHorizon, "], got ", horizon));
  }
  if (!(travel_weight >= 0.0 && std::isfinite(travel_weight))) {
    throw std::invalid_argument(
        cat("planner.sequence.travel_weight must be >= 0 [1/m], got ", travel_weight));
  }
  if (shortlist < 1) {
    throw std::invalid_argument(cat("planner.sequence.shortlist must be >= 1, got ", shortlist));
  }
  if (sample_bits < 0 || sample_bits > 16) {
    throw std::invalid_argument(
        cat("planner.sequence.sample_bits must lie in [0, 16], got ", sample_bits));
  }
}

OpenTour shortest_open_tour(std::span<const double> from_start, std::span<const double> between) {
  const std::size_t n = from_start.size();
  if (between.size() != n * n) {
    throw std::invalid_argument(cat("shortest_open_tour: ", n, " views but ", between.size(),
                                    " distances between them (expected ", n * n, ")"));
  }
  if (n > static_cast<std::size_t>(SequenceConfig::kMaxHorizon) + 2) {
    throw std::invalid_argument(cat("shortest_open_tour: ", n,
                                    " views are too many to order by "
                                    "brute force (at most ",
                                    SequenceConfig::kMaxHorizon + 2, ")"));
  }
  OpenTour best;
  if (n == 0) return best;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  best.length = std::numeric_limits<double>::infinity();
  do {
    double length = from_start[order[0]];
    for (std::size_t i = 1; i < n && length < best.length; ++i) {
      length += between[order[i - 1] * n + order[i]];
    }
    if (length < best.length) {
      best.length = length;
      best.order = order;
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

double joint_cells(std::span<const ViewCells* const> views) {
  std::vector<std::pair<std::uint32_t, double>> all;
  for (const ViewCells* v : views) {
    for (std::size_t i = 0; i < v->cells.size(); ++i) all.emplace_back(v->cells[i], v->seen[i]);
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  double total = 0.0;
  for (std::size_t i = 0; i < all.size();) {
    double missed = 1.0;  // prod (1 - v): no view of the set sees the cell
    std::size_t j = i;
    for (; j < all.size() && all[j].first == all[i].first; ++j) missed *= 1.0 - all[j].second;
    total += 1.0 - missed;
    i = j;
  }
  return total;
}

}  // namespace vantage
