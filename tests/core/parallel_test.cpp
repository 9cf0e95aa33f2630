#include "core/parallel.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "support/test_support.h"

namespace hm {

TEST(Parallel, EveryIndexVisitedOnce) {
  for (std::size_t n : {0u, 5u, 255u, 256u, 10000u}) {
    std::vector<int> hits(n, 0);
    parallel_for(0, n, [&](std::size_t i) { hits[i] += 1; });
    EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), static_cast<int>(n));
    for (int h : hits) ASSERT_EQ(h, 1);
  }
}

TEST(Parallel, ExceptionLeavesTaskAsTypedError) {
  EXPECT_THROW(parallel_for(0, 100000,
                            [](std::size_t i) {
                              if (i == 777) throw GeometryError("bad patch");
                            }),
               GeometryError);
}

// The background task's result arrives by wait() with one thread (run when waited for) and with
// two (beside the caller's loop), and what it throws comes out of wait() with its type.
TEST(Parallel, BackgroundTaskResultAndErrorArriveAtWait) {
  for (int threads : {1, 2}) {
    test::with_threads(threads, [] {
      long sum = 0;
      BackgroundTask task([&] {
        for (long i = 1; i <= 100000; ++i) sum += i;
      });
      std::vector<int> hits(10000, 0);
      parallel_for(0, hits.size(), [&](std::size_t i) { hits[i] = 1; });
      task.wait();
      EXPECT_EQ(sum, 5000050000L);
      EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), 10000);
      BackgroundTask bad([] { throw GeometryError("bad patch"); });
      EXPECT_THROW(bad.wait(), GeometryError);
      return 0;
    });
  }
}

TEST(Errors, ExitCodesAreDistinct) {
  EXPECT_EQ(static_cast<int>(IgesError("x").exit_code()), 3);
  EXPECT_EQ(static_cast<int>(LimitError("x").exit_code()), 4);
  EXPECT_EQ(static_cast<int>(IoError("x").exit_code()), 6);
  EXPECT_EQ(static_cast<int>(UsageError("x").exit_code()), 2);
}

}  // namespace hm
