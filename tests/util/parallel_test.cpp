// run_with_threads: a step nested in another runs on the threads it asks for, the same count as
// the caller's or another (its own arena), its work done whole, and a bad count is refused. That
// a step of the caller's count runs in the caller's arena rather than a new one of as many
// threads is not observable through TBB's interface (both give the same concurrency and thread
// index to the caller), so it is not asserted here; it changes no result.

#include "vantage/util/parallel.hpp"

#include <gtest/gtest.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace vantage {
namespace {

TEST(RunWithThreads, NestedStepsRunOnTheThreadsTheyAskFor) {
  const int threads = std::min(2, tbb::info::default_concurrency());
  int outer = 0, same = 0, one = 0;
  std::atomic<int> sum{0};
  run_with_threads(threads, [&] {
    outer = tbb::this_task_arena::max_concurrency();
    run_with_threads(threads, [&] {
      same = tbb::this_task_arena::max_concurrency();
      tbb::parallel_for(0, 100, [&](int i) { sum += i; });
    });
    run_with_threads(1, [&] { one = tbb::this_task_arena::max_concurrency(); });
  });
  EXPECT_EQ(outer, threads);
  EXPECT_EQ(same, threads);
  EXPECT_EQ(one, 1);
  EXPECT_EQ(sum.load(), 4950);
  EXPECT_THROW(run_with_threads(-1, [] {}), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
