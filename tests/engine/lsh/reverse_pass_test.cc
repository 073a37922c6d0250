// ReversePass with every frame in one bucket (ExhaustiveParts): it finds exactly the older
// frames within eps and their columns' thresholds, distances bit for bit; it stops at its
// budget; the seeds, advanced, come first and outside the budget, cut at the frame limit.
#include "engine/lsh/reverse_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

class ReversePassTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    PoseFeatures features = testing::SyntheticFeatures(20000, 13);
    NeighbourRules rules = testing::RulesWithEstimatedEps(features, 40);
    parts_ = new testing::QueryParts(testing::ExhaustiveParts(std::move(features), rules));
  }
  static void TearDownTestSuite() { delete parts_; }
  static testing::QueryParts* parts_;
};

testing::QueryParts* ReversePassTest::parts_ = nullptr;

bool ByFrame(const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; }

TEST_F(ReversePassTest, EveryFrameInOneBucket) {
  for (uint32_t table = 0; table < parts_->index.table_count(); ++table) {
    EXPECT_EQ(parts_->index.BucketStats(table).buckets, 1u);
  }
}

TEST_F(ReversePassTest, FindsEveryOlderFrameWithinItsThreshold) {
  const PoseFeatures& features = parts_->features;
  const NeighbourRules& rules = parts_->rules;
  const uint64_t frame_limit = 10000;
  std::vector<float> thresholds(frame_limit);
  for (uint64_t frame = 0; frame < frame_limit; ++frame) {
    thresholds[frame] = frame % 3 == 0 ? -1.0f : (frame % 3 == 1 ? 0.5f : 1.0f) * rules.eps;
  }
  ReversePass pass(parts_->context());
  for (uint64_t column :
       testing::ColumnsWithOlderNeighbours(features, rules, frame_limit, frame_limit, 30, 3)) {
    std::vector<Neighbour> found;
    pass.Run(column, {frame_limit, thresholds.data()}, 4000, nullptr, &found);
    std::sort(found.begin(), found.end(), ByFrame);
    std::vector<Neighbour> expected;
    const uint32_t clip = features.ClipOf(column);
    for (uint32_t frame = 0; frame < frame_limit; ++frame) {
      if (rules.Excluded(column, frame, clip, features.ClipOf(frame))) continue;
      const float distance = PoseDistance(features, column, frame);
      if (distance <= rules.eps && distance <= thresholds[frame]) {
        expected.push_back({frame, distance});
      }
    }
    EXPECT_GT(expected.size(), 10u) << "column " << column;
    EXPECT_EQ(found, expected) << "column " << column;
  }
}

// eps far above every distance: each frame verified is reported.
NeighbourRules WideRules(const NeighbourRules& rules) {
  NeighbourRules wide = rules;
  wide.eps = 1000;
  return wide;
}

TEST_F(ReversePassTest, StopsAtItsBudget) {
  const NeighbourRules wide = WideRules(parts_->rules);
  LshQueryContext context = parts_->context();
  const LshQueryContext wide_context{context.features, wide,          context.options,
                                     context.family,   context.index, context.extension_radius};
  ReversePass pass(wide_context);
  for (uint32_t budget : {1u, 20u, 100u}) {
    std::vector<Neighbour> found;
    pass.Run(2999, {3000, nullptr}, budget, nullptr, &found);
    EXPECT_EQ(found.size(), budget);
  }
}

TEST_F(ReversePassTest, VerifiesTheSeedsFirstAndOutsideTheBudget) {
  const NeighbourRules wide = WideRules(parts_->rules);
  LshQueryContext context = parts_->context();
  const LshQueryContext wide_context{context.features, wide,          context.options,
                                     context.family,   context.index, context.extension_radius};
  ASSERT_EQ(context.options.chain_advance, 2u);
  ReversePass pass(wide_context);
  const std::vector<Neighbour> seeds = {{100, 0.1f}, {200, 0.2f}};
  std::vector<Neighbour> found;
  pass.Run(2999, {3000, nullptr}, 1, &seeds, &found);
  ASSERT_EQ(found.size(), 7u);  // six seeds, then one frame of the scan's budget
  const std::vector<uint32_t> seeded = {100, 101, 102, 200, 201, 202};
  for (size_t idx = 0; idx < seeded.size(); ++idx) {
    EXPECT_EQ(found[idx].frame, seeded[idx]);
    EXPECT_EQ(found[idx].distance, PoseDistance(parts_->features, 2999, seeded[idx]));
  }
  EXPECT_EQ(std::find(seeded.begin(), seeded.end(), found[6].frame), seeded.end());
  // Thirty seeds (full batches of them) and a budget of 20: all fifty are verified.
  std::vector<Neighbour> many_seeds;
  for (uint32_t frame = 100; frame <= 1000; frame += 100) many_seeds.push_back({frame, 0.0f});
  found.clear();
  pass.Run(2999, {3000, nullptr}, 20, &many_seeds, &found);
  EXPECT_EQ(found.size(), 50u);
  // Frames at the frame limit or after it are not older frames: the seeds stop there.
  found.clear();
  pass.Run(2999, {201, nullptr}, 1, &seeds, &found);
  ASSERT_EQ(found.size(), 5u);
  EXPECT_EQ(found[3].frame, 200u);
  EXPECT_LT(found[4].frame, 201u);
}

}  // namespace
}  // namespace motif
