// CandidateVerifier: offered every allowed frame, it keeps exactly the exact column (the k_max
// nearest within eps, distances bit for bit those of PoseDistance) and its radius; it never
// verifies more than its budget; each frame is verified once per column; with a ReverseQuery it
// reports exactly the verified older frames within eps and their thresholds. KeepNearest breaks
// ties by the lower frame.
#include "engine/lsh/candidate_verifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

class CandidateVerifierTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(20000, 5));
    rules_ = new NeighbourRules(testing::RulesWithEstimatedEps(*features_, 40));
  }
  static void TearDownTestSuite() {
    delete rules_;
    delete features_;
  }
  static PoseFeatures* features_;
  static NeighbourRules* rules_;
};

PoseFeatures* CandidateVerifierTest::features_ = nullptr;
NeighbourRules* CandidateVerifierTest::rules_ = nullptr;

bool ByFrame(const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; }

// Offers every frame of the archive (excluded ones are refused by the caller, as the scans do).
uint64_t OfferAll(CandidateVerifier* verifier, uint64_t frame_count) {
  uint64_t offered = 0;
  for (uint32_t frame = 0; frame < frame_count; ++frame) {
    if (verifier->Excluded(frame) || !verifier->FirstVisit(frame)) continue;
    verifier->Gather(frame);
    ++offered;
  }
  verifier->VerifyGathered();
  return offered;
}

TEST_F(CandidateVerifierTest, EveryAllowedFrameGivesTheExactColumnAndItsRadius) {
  CandidateVerifier verifier(*features_, *rules_, 4096);
  for (uint64_t column : {0u, 1234u, 19999u}) {
    verifier.BeginColumn(column, features_->frame_count());
    EXPECT_EQ(verifier.bound(), rules_->eps);
    const uint64_t offered = OfferAll(&verifier, features_->frame_count());
    EXPECT_EQ(verifier.evaluations(), offered);
    std::vector<Neighbour> found = verifier.accepted();
    FinishColumn(rules_->k_max, &found);
    const std::vector<Neighbour> exact = testing::ExactColumn(*features_, *rules_, column);
    EXPECT_EQ(found, exact) << "column " << column;  // frames and distances, bit for bit
    float farthest = 0;
    for (const Neighbour& neighbour : exact) farthest = std::max(farthest, neighbour.distance);
    EXPECT_EQ(verifier.bound(), exact.size() == rules_->k_max ? farthest : rules_->eps);
    EXPECT_LE(verifier.accepted().size(), rules_->k_max);
  }
}

TEST_F(CandidateVerifierTest, CountsTheFramesWithinEps) {
  NeighbourRules rules = *rules_;
  rules.k_max = 5000;  // never full: the radius stays eps and every distance is exact
  CandidateVerifier verifier(*features_, rules, 4096);
  verifier.BeginColumn(700, features_->frame_count());
  OfferAll(&verifier, features_->frame_count());
  const std::vector<Neighbour> exact = testing::ExactColumn(*features_, rules, 700);
  EXPECT_GT(exact.size(), 0u);
  EXPECT_EQ(verifier.within_eps(), exact.size());
  EXPECT_EQ(verifier.bound(), rules.eps);
}

TEST_F(CandidateVerifierTest, NeverVerifiesMoreThanItsBudget) {
  CandidateVerifier verifier(*features_, *rules_, 4096);
  verifier.BeginColumn(100, 37);
  uint32_t frame = 200;
  // Batches filled up to the limit, as the sort-value scan fills them.
  while (!verifier.BudgetReached()) {
    const uint32_t limit = verifier.BatchLimit();
    while (verifier.batch_size() < limit) verifier.AddToBatch(frame++);
    verifier.Flush();
  }
  verifier.Drain();
  EXPECT_EQ(verifier.evaluations(), 37u);
  EXPECT_EQ(frame, 237u);
  // A new budget after the evaluations done (a chained column's).
  verifier.SetBudget(verifier.evaluations() + 5);
  EXPECT_EQ(verifier.BatchLimit(), 5u);
  EXPECT_FALSE(verifier.BudgetReached());
}

TEST_F(CandidateVerifierTest, ExcludesTheColumnsNeighbourhoodAndVisitsEachFrameOnce) {
  CandidateVerifier verifier(*features_, *rules_, 64);
  verifier.BeginColumn(1000, 100);
  EXPECT_EQ(verifier.column(), 1000u);
  EXPECT_TRUE(verifier.Excluded(1000));
  const uint32_t clip = features_->ClipOf(1000);
  for (uint32_t frame = 900; frame < 1100; ++frame) {
    EXPECT_EQ(verifier.Excluded(frame),
              rules_->Excluded(1000, frame, clip, features_->ClipOf(frame)))
        << frame;
  }
  for (uint32_t frame = 0; frame < 500; ++frame) EXPECT_TRUE(verifier.FirstVisit(frame));
  EXPECT_FALSE(verifier.FirstVisit(7));
  verifier.BeginColumn(1001, 100);
  EXPECT_TRUE(verifier.FirstVisit(7));
}

TEST_F(CandidateVerifierTest, ReportsTheOlderFramesWithinTheirThresholds) {
  const uint64_t frame_limit = 10000;
  std::vector<float> thresholds(frame_limit);
  for (uint64_t frame = 0; frame < frame_limit; ++frame) {
    // Every third frame not wanted, the others at half or all of eps.
    thresholds[frame] = frame % 3 == 0 ? -1.0f : (frame % 3 == 1 ? 0.5f : 1.0f) * rules_->eps;
  }
  const ReverseQuery query{frame_limit, thresholds.data()};
  CandidateVerifier verifier(*features_, *rules_, 4096);
  const std::vector<uint64_t> columns =
      testing::ColumnsWithOlderNeighbours(*features_, *rules_, frame_limit, frame_limit, 30, 1);
  ASSERT_EQ(columns.size(), 1u);
  const uint64_t column = columns[0];
  std::vector<Neighbour> reverse = {{1, 0.0f}};  // cleared by BeginColumn
  verifier.BeginColumn(column, features_->frame_count(), &query, &reverse);
  EXPECT_TRUE(reverse.empty());
  OfferAll(&verifier, features_->frame_count());
  std::vector<Neighbour> expected;
  const uint32_t clip = features_->ClipOf(column);
  for (uint32_t frame = 0; frame < frame_limit; ++frame) {
    if (rules_->Excluded(column, frame, clip, features_->ClipOf(frame))) continue;
    const float distance = PoseDistance(*features_, column, frame);
    if (distance <= rules_->eps && distance <= thresholds[frame]) {
      expected.push_back({frame, distance});
    }
  }
  std::sort(reverse.begin(), reverse.end(), ByFrame);
  EXPECT_GT(expected.size(), 10u);
  EXPECT_EQ(reverse, expected);
  // The column itself is the same as without the reverse query.
  std::vector<Neighbour> found = verifier.accepted();
  FinishColumn(rules_->k_max, &found);
  EXPECT_EQ(found, testing::ExactColumn(*features_, *rules_, column));
}

// 300 frames of one static pose: every distance is 0, so the column is decided by ties alone.
TEST(CandidateVerifier, TiesGoToTheLowerFrameWhateverTheOrderOffered) {
  const uint32_t joints = 2;
  const size_t stride = 4 * joints + 4;
  std::vector<float> rows(300 * stride, 0.0f);
  for (size_t frame = 0; frame < 300; ++frame) {
    for (uint32_t joint = 0; joint < joints; ++joint) rows[frame * stride + 4 * joint] = 1.0f;
  }
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 300, joints, {1, 1}, {0});
  NeighbourRules rules;
  rules.eps = 0.5f;
  rules.k_max = 5;
  rules.exclusion_frames = 30;
  rules.clip_first_frames = {0};
  CandidateVerifier verifier(features, rules, 512);
  verifier.BeginColumn(150, 1000);
  for (uint32_t frame = 300; frame-- > 0;) {  // highest frame first
    if (!verifier.Excluded(frame) && verifier.FirstVisit(frame)) verifier.Gather(frame);
  }
  verifier.VerifyGathered();
  std::vector<Neighbour> found = verifier.accepted();
  FinishColumn(rules.k_max, &found);
  EXPECT_EQ(found, (std::vector<Neighbour>{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}}));
  EXPECT_EQ(verifier.bound(), 0.0f);
}

TEST(KeepNearest, KeepsTheKNearestTiesToTheLowerFrame) {
  std::vector<Neighbour> best = {{9, 0.5f}, {3, 0.2f}, {4, 0.5f}, {1, 0.9f}, {2, 0.5f}};
  EXPECT_EQ(KeepNearest(3, 1.0f, &best), 0.5f);
  std::sort(best.begin(), best.end(), ByFrame);
  EXPECT_EQ(best, (std::vector<Neighbour>{{2, 0.5f}, {3, 0.2f}, {4, 0.5f}}));
  // Not full: nothing dropped, the radius is eps.
  std::vector<Neighbour> few = {{5, 0.1f}};
  EXPECT_EQ(KeepNearest(3, 0.8f, &few), 0.8f);
  EXPECT_EQ(few.size(), 1u);
  // Full, farthest beyond eps: the radius is eps.
  std::vector<Neighbour> far = {{5, 0.1f}, {6, 2.0f}};
  EXPECT_EQ(KeepNearest(2, 0.8f, &far), 0.8f);
}

}  // namespace
}  // namespace motif
