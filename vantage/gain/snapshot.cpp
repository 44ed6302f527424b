#include "vantage/gain/snapshot.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "vantage/gain/ray_model.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage {
namespace {

constexpr std::size_t kSnapshotChunk = std::size_t{1} << 16;

/// A total order on floats that matches numeric order for every non-NaN value.
std::uint32_t ordered_key(float f) {
  const auto b = std::bit_cast<std::uint32_t>(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float from_ordered_key(std::uint32_t k) {
  return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

template <typename Code>
void write_codes(std::span<const float> log_odds, std::span<const std::uint32_t> keys,
                 Code* codes) {
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, log_odds.size(), kSnapshotChunk), [&](const auto& r) {
        std::uint32_t last_key = ordered_key(log_odds[r.begin()]);
        auto last_code =
            static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), last_key) - keys.begin());
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint32_t key = ordered_key(log_odds[i]);
          if (key != last_key) {
            last_key = key;
            last_code =
                static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
          }
          codes[i] = last_code;
        }
      });
}

}  // namespace

GainMap GainMap::of_classes(const OccupancyGrid& grid, int num_threads) {
  GainMap map(grid.spec(), grid.params());
  // NOTE: codes in ascending log-odds, as the full snapshot's: free 0, unobserved 1, occupied 2.
  map.values_ = {Value{0.0, 0.0, CellState::kFree}, Value{0.5, 1.0, CellState::kUnobserved},
                 Value{1.0, 0.0, CellState::kOccupied}};
  std::array<std::uint8_t, 4> code_of{};
  code_of[static_cast<std::size_t>(CellState::kFree)] = 0;
  code_of[static_cast<std::size_t>(CellState::kUnobserved)] = 1;
  code_of[static_cast<std::size_t>(CellState::kOccupied)] = 2;
  // NOTE: the four codes of each packed byte, from a table: a copy of four bytes a byte.
  std::array<std::array<std::uint8_t, 4>, 256> four{};
  for (std::size_t b = 0; b < four.size(); ++b) {
    for (std::size_t k = 0; k < 4; ++k) four[b][k] = code_of[(b >> (2 * k)) & 3u];
  }
  const std::size_t n = map.size();
  map.codes8_.resize(n);
  const std::uint8_t* packed = grid.classes().packed();
  std::uint8_t* codes = map.codes8_.data();
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n / 4, kSnapshotChunk / 4),
                      [&](const auto& r) {
                        for (std::size_t b = r.begin(); b != r.end(); ++b) {
                          std::memcpy(codes + 4 * b, four[packed[b]].data(), 4);
                        }
                      });
  });
  for (std::size_t i = n / 4 * 4; i < n; ++i) codes[i] = four[packed[n / 4]][i % 4];
  return map;
}

GainMap::GainMap(const OccupancyGrid& grid, int num_threads)
    : spec_(grid.spec()), params_(grid.params()) {
  const std::span<const float> log_odds = grid.log_odds();
  const std::size_t n = log_odds.size();
  const std::size_t chunks = (n + kSnapshotChunk - 1) / kSnapshotChunk;
  std::vector<std::uint32_t> keys;
  run_with_threads(num_threads, [&] {
    // Distinct values per fixed chunk, then merged: the table does not depend on the threads.
    std::vector<std::vector<std::uint32_t>> distinct(chunks);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::vector<std::uint32_t>& out = distinct[c];
      const std::size_t end = std::min(n, (c + 1) * kSnapshotChunk);
      std::uint32_t last = ordered_key(log_odds[c * kSnapshotChunk]);
      out.push_back(last);
      for (std::size_t i = c * kSnapshotChunk; i < end; ++i) {
        const std::uint32_t key = ordered_key(log_odds[i]);
        if (key != last) out.push_back(last = key);
      }
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
    });
    for (const auto& part : distinct) keys.insert(keys.end(), part.begin(), part.end());
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

    values_.reserve(keys.size());
    for (const std::uint32_t key : keys) {
      const float l = from_ordered_key(key);
      Value v;
      v.p = logistic(l);  // as OccupancyGrid::probability
      v.entropy = entropy_bits(v.p);
      v.state = grid.state_of(l);
      values_.push_back(v);
    }
    code_width_ = keys.size() <= 0x100u ? 1 : (keys.size() <= 0x10000u ? 2 : 4);
    switch (code_width_) {
      case 1:
        codes8_.resize(n);
        write_codes(log_odds, keys, codes8_.data());
        break;
      case 2:
        codes16_.resize(n);
        write_codes(log_odds, keys, codes16_.data());
        break;
      default:
        codes32_.resize(n);
        write_codes(log_odds, keys, codes32_.data());
        break;
    }
  });
}

}  // namespace vantage
