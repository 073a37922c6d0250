// ChainSweep against a brute-force sweep: the candidates are the frames j - 0..advance (from the
// successor) or j + 0..advance (from the predecessor) of the given neighbours that the column
// does not hold and may hold, verified against the column's k_max-th distance before the sweep;
// the column becomes the k_max nearest of both, sorted by frame, distances bit for bit.
#include "engine/lsh/chain_sweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

constexpr uint32_t kAdvance = 2;

class ChainSweepTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(20000, 9));
    rules_ = new NeighbourRules(testing::RulesWithEstimatedEps(*features_, 40));
  }
  static void TearDownTestSuite() {
    delete rules_;
    delete features_;
  }
  static PoseFeatures* features_;
  static NeighbourRules* rules_;
};

PoseFeatures* ChainSweepTest::features_ = nullptr;
NeighbourRules* ChainSweepTest::rules_ = nullptr;

struct Expected {
  std::vector<Neighbour> column;
  uint64_t candidates = 0;
  uint64_t within_eps = 0;
};

Expected BruteForceSweep(const PoseFeatures& features, const NeighbourRules& rules, uint64_t column,
                         const std::vector<Neighbour>& from, int direction,
                         const std::vector<Neighbour>& held) {
  std::set<uint32_t> held_frames;
  for (const Neighbour& neighbour : held) held_frames.insert(neighbour.frame);
  std::set<uint32_t> candidates;
  const uint32_t clip = features.ClipOf(column);
  for (const Neighbour& neighbour : from) {
    for (int64_t step = 0; step <= kAdvance; ++step) {
      const int64_t frame = int64_t{neighbour.frame} - direction * step;
      if (frame < 0 || frame >= static_cast<int64_t>(features.frame_count())) continue;
      const uint32_t candidate = static_cast<uint32_t>(frame);
      if (held_frames.count(candidate) ||
          rules.Excluded(column, candidate, clip, features.ClipOf(candidate))) {
        continue;
      }
      candidates.insert(candidate);
    }
  }
  float bound = rules.eps;
  if (held.size() >= rules.k_max) {
    float farthest = 0;
    for (const Neighbour& neighbour : held) farthest = std::max(farthest, neighbour.distance);
    bound = std::min(rules.eps, farthest);
  }
  Expected expected;
  expected.column = held;
  expected.candidates = candidates.size();
  for (uint32_t candidate : candidates) {
    const float distance = PoseDistance(features, column, candidate);
    if (distance <= rules.eps) ++expected.within_eps;
    if (distance <= bound) expected.column.push_back({candidate, distance});
  }
  FinishColumn(rules.k_max, &expected.column);
  return expected;
}

// Every other neighbour of the exact column: a column that misses some.
std::vector<Neighbour> HalfOf(std::vector<Neighbour> column, size_t keep_at_most = SIZE_MAX) {
  std::vector<Neighbour> half;
  for (size_t idx = 0; idx < column.size() && half.size() < keep_at_most; idx += 2) {
    half.push_back(column[idx]);
  }
  return half;
}

void ExpectSweep(const PoseFeatures& features, const NeighbourRules& rules, uint64_t column,
                 const std::vector<Neighbour>& from, int direction, std::vector<Neighbour> held) {
  SCOPED_TRACE(::testing::Message() << "column " << column << " direction " << direction);
  const Expected expected = BruteForceSweep(features, rules, column, from, direction, held);
  ChainSweep sweep(features, rules, kAdvance);
  ColumnWork work;
  sweep.Sweep(column, from, direction, &held, &work);
  EXPECT_EQ(held, expected.column);
  EXPECT_EQ(work.evaluations, expected.candidates);
  EXPECT_EQ(work.lsh.sweep_evaluations, expected.candidates);
}

TEST_F(ChainSweepTest, FromTheSuccessorIntoAFullColumn) {
  const uint64_t column = 1500;
  const std::vector<Neighbour> exact = testing::ExactColumn(*features_, *rules_, column);
  ASSERT_EQ(exact.size(), rules_->k_max);
  // Full with half the exact column's frames (k_max 20), so its radius is below eps: some
  // candidates within eps cannot enter, some enter and push others out.
  NeighbourRules rules = *rules_;
  rules.k_max = rules_->k_max / 2;
  const std::vector<Neighbour> held = HalfOf(exact);
  ASSERT_EQ(held.size(), rules.k_max);
  const std::vector<Neighbour> from = testing::ExactColumn(*features_, *rules_, column + 1);
  const Expected expected = BruteForceSweep(*features_, rules, column, from, +1, held);
  ASSERT_GT(expected.candidates, 0u);
  ASSERT_NE(expected.column, held) << "the sweep changes the column";
  ExpectSweep(*features_, rules, column, from, +1, held);
}

TEST_F(ChainSweepTest, FromThePredecessorIntoAColumnNotFull) {
  for (uint64_t column : {700u, 2200u}) {
    const std::vector<Neighbour> held =
        HalfOf(testing::ExactColumn(*features_, *rules_, column), 10);
    const std::vector<Neighbour> from = testing::ExactColumn(*features_, *rules_, column - 1);
    const Expected expected = BruteForceSweep(*features_, *rules_, column, from, -1, held);
    ASSERT_GT(expected.candidates, 0u);
    ExpectSweep(*features_, *rules_, column, from, -1, held);
    // Not full, the radius is eps: every distance up to it is exact, so is the capped flag.
    ChainSweep sweep(*features_, *rules_, kAdvance);
    ColumnWork work;
    std::vector<Neighbour> column_after = held;
    sweep.Sweep(column, from, -1, &column_after, &work);
    EXPECT_EQ(work.capped, held.size() + expected.within_eps > rules_->k_max);
  }
}

TEST_F(ChainSweepTest, StaysInsideTheArchiveAndDoesNothingWithoutCandidates) {
  const uint64_t last = features_->frame_count() - 1;
  // The predecessor's neighbours include the last frames: j + 1, j + 2 are cut at the end.
  const std::vector<Neighbour> from = {{static_cast<uint32_t>(last - 1), 0.0f},
                                       {static_cast<uint32_t>(last), 0.0f}};
  ExpectSweep(*features_, *rules_, 100, from, -1, {});
  // Frame 0 from the successor: j - 1, j - 2 are cut at the start.
  ExpectSweep(*features_, *rules_, 2000, {{0, 0.0f}, {1, 0.0f}}, +1, {});
  // Nothing to verify.
  ChainSweep sweep(*features_, *rules_, kAdvance);
  ColumnWork work;
  std::vector<Neighbour> held = testing::ExactColumn(*features_, *rules_, 1000);
  const std::vector<Neighbour> before = held;
  sweep.Sweep(1000, {}, +1, &held, &work);
  EXPECT_EQ(held, before);
  EXPECT_EQ(work.evaluations, 0u);
  // The column's own neighbourhood is excluded: a sweep from frames next to it finds nothing.
  for (uint64_t frame = 999; frame <= 1002; ++frame) {
    ASSERT_EQ(features_->ClipOf(frame), features_->ClipOf(1000));
  }
  sweep.Sweep(1000, {{1001, 0.0f}, {1002, 0.0f}}, +1, &held, &work);
  EXPECT_EQ(work.evaluations, 0u);
}

}  // namespace
}  // namespace motif
