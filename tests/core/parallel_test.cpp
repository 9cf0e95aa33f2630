#include "core/parallel.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/error.h"

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

TEST(Errors, ExitCodesAreDistinct) {
  EXPECT_EQ(static_cast<int>(IgesError("x").exit_code()), 3);
  EXPECT_EQ(static_cast<int>(LimitError("x").exit_code()), 4);
  EXPECT_EQ(static_cast<int>(IoError("x").exit_code()), 6);
  EXPECT_EQ(static_cast<int>(UsageError("x").exit_code()), 2);
}

}  // namespace hm
