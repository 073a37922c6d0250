// VisitedSet: each frame is new once per column, Clear() starts a new column, and a column that
// inserts far more than the set was sized for makes it grow instead of filling it up.
#include "engine/lsh/visited_set.h"

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(VisitedSetTest, EachFrameIsNewOncePerColumn) {
  VisitedSet visited(100);
  EXPECT_TRUE(visited.Insert(7));
  EXPECT_TRUE(visited.Insert(0));
  EXPECT_FALSE(visited.Insert(7));
  EXPECT_FALSE(visited.Insert(0));
  EXPECT_TRUE(visited.Insert(0xffffffffu));
  visited.Clear();
  EXPECT_TRUE(visited.Insert(7));
  EXPECT_TRUE(visited.Insert(0xffffffffu));
  EXPECT_FALSE(visited.Insert(7));
}

// Sized for 100 inserts (256 slots); 20,000 distinct frames in one column (once the reverse
// scan's unbudgeted seeds could overfill it, and a full table made Insert loop forever).
TEST(VisitedSetTest, GrowsPastItsSizeAndKeepsWhatItHolds) {
  VisitedSet visited(100);
  const uint32_t sized = visited.capacity();
  EXPECT_EQ(sized, 256u);
  for (uint32_t frame = 0; frame < 20000; ++frame) {
    ASSERT_TRUE(visited.Insert(frame * 3 + 1)) << frame;
  }
  EXPECT_GE(visited.capacity(), 20000u * 4 / 3);
  for (uint32_t frame = 0; frame < 20000; ++frame) {
    ASSERT_FALSE(visited.Insert(frame * 3 + 1)) << frame;
    ASSERT_TRUE(visited.Insert(frame * 3 + 2)) << frame;
  }
  visited.Clear();
  for (uint32_t frame = 0; frame < 20000; ++frame) ASSERT_TRUE(visited.Insert(frame * 3 + 1));
}

}  // namespace
}  // namespace motif
