// run_with_threads: a step inside an arena of as many threads runs in it (a decision's steps in
// its one arena), a step that asks for another count gets an arena of its own, and a bad count
// is refused.

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

TEST(RunWithThreads, NestedStepsRunInTheArenaOfTheirThreads) {
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
