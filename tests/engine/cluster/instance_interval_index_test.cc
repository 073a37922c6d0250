#include "engine/cluster/instance_interval_index.h"

#include <random>

#include <gtest/gtest.h>

namespace motif {
namespace {

std::vector<uint32_t> BruteForce(const std::vector<MotifInstance>& instances, uint64_t frame) {
  std::vector<uint32_t> ids;
  for (size_t id = 0; id < instances.size(); ++id) {
    if (instances[id].start <= frame && frame < instances[id].end) ids.push_back(uint32_t(id));
  }
  return ids;
}

TEST(InstanceIntervalIndexTest, AnswersLikeABruteForceScan) {
  std::mt19937_64 random(3);
  std::vector<MotifInstance> instances;
  for (int idx = 0; idx < 200; ++idx) {
    const uint64_t start = random() % 5000;
    instances.push_back({start, start + 1 + random() % 300});
  }
  const InstanceIntervalIndex index(instances);
  InstanceIntervalIndex::Cursor cursor(index);
  for (uint64_t frame = 0; frame < 5500; ++frame) {  // ascending: the cursor's case
    const std::vector<uint32_t> expected = BruteForce(instances, frame);
    auto found = index.Containing(frame);
    EXPECT_EQ(std::vector<uint32_t>(found.begin(), found.end()), expected) << frame;
    auto by_cursor = cursor.Containing(frame);
    EXPECT_EQ(std::vector<uint32_t>(by_cursor.begin(), by_cursor.end()), expected) << frame;
  }
  // Jumps forward and back (after Reset) give the same answers.
  cursor.Reset();
  for (uint64_t frame : {4000u, 4100u, 4999u}) {
    auto by_cursor = cursor.Containing(frame);
    EXPECT_EQ(std::vector<uint32_t>(by_cursor.begin(), by_cursor.end()),
              BruteForce(instances, frame));
  }
}

TEST(InstanceIntervalIndexTest, EmptyIndexAndFramesOutside) {
  const InstanceIntervalIndex empty({});
  EXPECT_TRUE(empty.Containing(0).empty());
  const InstanceIntervalIndex index({{10, 20}, {30, 40}});
  EXPECT_TRUE(index.Containing(9).empty());
  EXPECT_TRUE(index.Containing(20).empty());  // end is exclusive
  EXPECT_TRUE(index.Containing(25).empty());
  EXPECT_TRUE(index.Containing(40).empty());
  ASSERT_EQ(index.Containing(30).size(), 1u);
  EXPECT_EQ(index.Containing(30)[0], 1u);
}

}  // namespace
}  // namespace motif
