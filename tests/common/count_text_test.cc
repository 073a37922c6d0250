#include "common/count_text.h"

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(CountText, GroupsThousandsWithCommas) {
  EXPECT_EQ(WithCommas(0), "0");
  EXPECT_EQ(WithCommas(999), "999");
  EXPECT_EQ(WithCommas(1000), "1,000");
  EXPECT_EQ(WithCommas(192029), "192,029");
  EXPECT_EQ(WithCommas(18446744073709551615ull), "18,446,744,073,709,551,615");
}

TEST(CountText, CountsWithTheirNoun) {
  EXPECT_EQ(CountOf(1, "clip"), "1 clip");
  EXPECT_EQ(CountOf(0, "clip"), "0 clips");
  EXPECT_EQ(CountOf(1234, "frame"), "1,234 frames");
}

}  // namespace
}  // namespace motif
