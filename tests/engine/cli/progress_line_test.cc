#include "engine/cli/progress_reporter.h"

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(ProgressLine, ShowsHumanRatesAndNoneInTheFirstQuarterSecond) {
  EXPECT_EQ(ProgressLine("trellis", "columns", 1200000, 2400000, 30.0, false),
            "[trellis] 1.20M/2.40M columns (50%)  40.0k columns/s  ETA 30.0s");
  EXPECT_EQ(ProgressLine("trellis", "columns", 2400000, 2400000, 60.0, true),
            "[trellis] 2.40M columns in 1m00s (40.0k columns/s)");
  // A stage that starts with its work done (reused) or ends within 0.25 s: no rate, which would
  // be billions a second ("5.02G columns/s").
  EXPECT_EQ(ProgressLine("trellis", "columns", 120000, 120000, 0.00002, true),
            "[trellis] 120.0k columns in 0.0s");
  EXPECT_EQ(ProgressLine("grow", "columns", 5000, 120000, 0.1, false),
            "[grow] 5000/120.0k columns (4%)  ETA ?");
  // At 100 % before the stage's last line: nothing left to estimate, no "ETA ?".
  EXPECT_EQ(ProgressLine("import", "takes", 1, 1, 0.01, false), "[import] 1/1 takes (100%)");
  EXPECT_EQ(ProgressLine("import", "takes", 4, 4, 2.0, false),
            "[import] 4/4 takes (100%)  2 takes/s");
  EXPECT_EQ(ProgressRate(1000, 0.2), 0.0);
  EXPECT_EQ(FormatDuration(148 / 120.0), "1.2 s");  // was "0.0 min"
  EXPECT_EQ(FormatDuration(14000 / 120.0), "1.9 min");
  EXPECT_EQ(FormatDuration(1e7 / 120.0), "23.1 h");
  EXPECT_EQ(ProgressRate(1000, 0.5), 2000.0);
}

}  // namespace
}  // namespace motif
