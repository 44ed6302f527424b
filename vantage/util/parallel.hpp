#pragma once
/// @file
/// Runs work on a given number of threads, without global thread-pool state.

#include <tbb/task_arena.h>

#include <stdexcept>
#include <utility>

#include "vantage/util/text.hpp"

namespace vantage {

/// Runs `work` inside a TBB arena of `num_threads` threads (0 = all cores).
template <typename Work>
void run_with_threads(int num_threads, Work&& work) {
  if (num_threads < 0) {
    throw std::invalid_argument(cat("num_threads must be >= 0 (0 = all cores), got ", num_threads));
  }
  if (num_threads == 0) {
    std::forward<Work>(work)();
    return;
  }
  tbb::task_arena arena(num_threads);
  arena.execute(std::forward<Work>(work));
}

}  // namespace vantage
