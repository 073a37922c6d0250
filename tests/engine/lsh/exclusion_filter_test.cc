// ExclusionFilter: the column itself and its own clip's frames nearer than exclusion_frames, as
// NeighbourRules::Excluded says, for every pair of a three-clip archive; nothing across a clip
// boundary; only the column itself with an exclusion radius of 0.
#include "engine/lsh/exclusion_filter.h"

#include <gtest/gtest.h>

#include <vector>

namespace motif {
namespace {

// 400 frames of a two-joint identity pose in clips [0, 100), [100, 250), [250, 400).
PoseFeatures ThreeClips() {
  const uint32_t joints = 2;
  const size_t stride = 4 * joints + 4;
  std::vector<float> rows(400 * stride, 0.0f);
  for (size_t frame = 0; frame < 400; ++frame) {
    for (uint32_t joint = 0; joint < joints; ++joint) rows[frame * stride + 4 * joint] = 1.0f;
  }
  return PoseFeatures::FromRows(rows.data(), 400, joints, {1.0f, 1.0f}, {0, 100, 250});
}

NeighbourRules RulesOf(uint32_t exclusion_frames) {
  NeighbourRules rules;
  rules.eps = 1;
  rules.exclusion_frames = exclusion_frames;
  rules.clip_first_frames = {0, 100, 250};
  return rules;
}

TEST(ExclusionFilter, AgreesWithTheRulesForEveryPair) {
  const PoseFeatures features = ThreeClips();
  const NeighbourRules rules = RulesOf(30);
  const ExclusionFilter filter(features, rules);
  uint64_t excluded = 0;
  for (uint64_t column = 0; column < 400; ++column) {
    const uint32_t clip = features.ClipOf(column);
    for (uint32_t frame = 0; frame < 400; ++frame) {
      const bool expected = rules.Excluded(column, frame, clip, features.ClipOf(frame));
      ASSERT_EQ(filter.Excluded(column, clip, frame), expected) << column << " " << frame;
      excluded += expected;
    }
  }
  EXPECT_GT(excluded, 400u);
}

TEST(ExclusionFilter, ExcludesTheColumnsOwnClipNeighbourhoodOnly) {
  const PoseFeatures features = ThreeClips();
  const NeighbourRules rules = RulesOf(30);
  const ExclusionFilter filter(features, rules);
  EXPECT_TRUE(filter.Excluded(150, 1, 150));
  EXPECT_TRUE(filter.Excluded(150, 1, 121));   // 29 frames before, same clip
  EXPECT_FALSE(filter.Excluded(150, 1, 120));  // 30 frames before
  EXPECT_TRUE(filter.Excluded(150, 1, 179));
  EXPECT_FALSE(filter.Excluded(150, 1, 180));
  EXPECT_FALSE(filter.Excluded(101, 1, 99));   // the previous clip, 2 frames before
  EXPECT_FALSE(filter.Excluded(249, 1, 250));  // the next clip
  EXPECT_TRUE(filter.Excluded(249, 1, 248));
}

TEST(ExclusionFilter, WithoutARadiusOnlyTheColumnItself) {
  const PoseFeatures features = ThreeClips();
  const NeighbourRules rules = RulesOf(0);
  const ExclusionFilter filter(features, rules);
  EXPECT_TRUE(filter.Excluded(150, 1, 150));
  EXPECT_FALSE(filter.Excluded(150, 1, 149));
  EXPECT_FALSE(filter.Excluded(150, 1, 151));
  EXPECT_FALSE(filter.Excluded(0, 0, 1));
}

}  // namespace
}  // namespace motif
