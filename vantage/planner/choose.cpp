#include "vantage/planner/choose.hpp"

#include <cmath>
#include <stdexcept>

#include "vantage/util/hash.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

std::size_t choose_best(std::span<const double> gains) {
  if (gains.empty()) throw std::invalid_argument("no candidate views to choose from");
  std::size_t best = 0;
  for (std::size_t i = 0; i < gains.size(); ++i) {
    if (std::isnan(gains[i])) throw std::invalid_argument(cat("gain of view ", i, " is NaN"));
    if (gains[i] > gains[best]) best = i;
  }
  return best;
}

std::size_t choose_best(std::span<const double> scores, std::span<const double> tie_break) {
  if (scores.size() != tie_break.size()) {
    throw std::invalid_argument(cat("choose_best: ", scores.size(), " scores but ",
                                    tie_break.size(), " tie-breaking values"));
  }
  std::size_t best = choose_best(scores);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    if (std::isnan(tie_break[i])) {
      throw std::invalid_argument(cat("tie-breaking value of view ", i, " is NaN"));
    }
    if (scores[i] == scores[best] && tie_break[i] > tie_break[best]) best = i;
  }
  return best;
}

std::size_t choose_random(std::size_t n, std::uint64_t seed) {
  if (n == 0) throw std::invalid_argument("no candidate views to choose from");
  // NOTE: SplitMix64 rather than a std distribution, whose output differs between standard
  // libraries; the modulo bias is below 1e-17 for any realistic n.
  return static_cast<std::size_t>(mix64(seed) % n);
}

}  // namespace vantage
