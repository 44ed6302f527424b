#pragma once
/// @file
/// Runs work on a given number of threads, without global thread-pool state.

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "vantage/util/text.hpp"

namespace vantage {

/// Runs `work` inside a TBB arena of `num_threads` threads (0 = all cores), at most as many as
/// the machine has cores: TBB ignores more and prints its own warning on stderr (results do not
/// depend on the count).
template <typename Work>
void run_with_threads(int num_threads, Work&& work) {
  if (num_threads < 0) {
    throw std::invalid_argument(cat("num_threads must be >= 0 (0 = all cores), got ", num_threads));
  }
  const int threads = std::min(num_threads, tbb::info::default_concurrency());
  // NOTE: inside an arena of as many threads already (a decision's steps, in its one arena), the
  // work runs in it: a new arena each step cost its creation and its threads' wake-up.
  if (num_threads == 0 ||
      (tbb::this_task_arena::current_thread_index() != tbb::task_arena::not_initialized &&
       tbb::this_task_arena::max_concurrency() == threads)) {
    std::forward<Work>(work)();
    return;
  }
  tbb::task_arena arena(threads);
  arena.execute(std::forward<Work>(work));
}

}  // namespace vantage
