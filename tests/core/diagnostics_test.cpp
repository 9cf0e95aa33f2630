#include "core/diagnostics.h"

#include <gtest/gtest.h>

namespace hm {

TEST(Diagnostics, FormatNamesEntityAndLine) {
  Diagnostic d{Severity::kWarning, 37, 12, 128, "zero weight"};
  EXPECT_EQ(format(d), "warning: DE 37 (type 128, P line 12): zero weight");
}

TEST(Diagnostics, FormatWithoutEntity) {
  Diagnostic d{Severity::kNote, 0, 0, 0, "skipped 3 entities"};
  EXPECT_EQ(format(d), "note: skipped 3 entities");
}

TEST(Diagnostics, CountsBySeverity) {
  Diagnostics ds;
  ds.warn("a");
  ds.note("b");
  ds.add(Severity::kError, 1, 1, 128, "c");
  EXPECT_EQ(ds.count(Severity::kWarning), 1u);
  EXPECT_EQ(ds.count(Severity::kNote), 1u);
  EXPECT_EQ(ds.count(Severity::kError), 1u);
}

}  // namespace hm
