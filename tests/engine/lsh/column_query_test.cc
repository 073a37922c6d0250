// ColumnQuery with every frame in one bucket (ExhaustiveParts): a column's query finds exactly
// the exact column in both candidate orders; it stops at its budget; a chained column that does
// not probe keeps exactly the k_max nearest of its seeds, one that probes finds the exact column;
// with a ReverseQuery it reports exactly the older frames within eps it verified.
#include "engine/lsh/column_query.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

class ColumnQueryTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(20000, 17));
    rules_ = new NeighbourRules(testing::RulesWithEstimatedEps(*features_, 40));
  }
  static void TearDownTestSuite() {
    delete rules_;
    delete features_;
  }
  static testing::QueryParts* Parts(LshRanking ranking = LshRanking::kSortValue,
                                    const NeighbourRules* rules = nullptr) {
    return new testing::QueryParts(
        testing::ExhaustiveParts(PoseFeatures(*features_), rules ? *rules : *rules_, ranking));
  }
  static PoseFeatures* features_;
  static NeighbourRules* rules_;
};

PoseFeatures* ColumnQueryTest::features_ = nullptr;
NeighbourRules* ColumnQueryTest::rules_ = nullptr;

TEST_F(ColumnQueryTest, FindsTheExactColumnInBothOrders) {
  for (LshRanking ranking : {LshRanking::kSortValue, LshRanking::kPositionCode}) {
    std::unique_ptr<testing::QueryParts> parts(Parts(ranking));
    ASSERT_EQ(parts->index.BucketStats(0).buckets, 1u);
    ColumnQuery query(parts->context());
    for (uint64_t column : {0u, 1500u, 19999u}) {
      SCOPED_TRACE(::testing::Message() << LshRankingName(ranking) << " column " << column);
      std::vector<Neighbour> found;
      ColumnWork work;
      query.Run(column, nullptr, &found, &work);
      EXPECT_EQ(found, testing::ExactColumn(*features_, *rules_, column));
      EXPECT_GT(work.lsh.probes, 0u);
      EXPECT_GT(work.lsh.entries_examined, 0u);
      EXPECT_LE(work.evaluations, features_->frame_count());
      EXPECT_EQ(work.lsh.columns_budget_capped, 0u);
    }
  }
}

TEST_F(ColumnQueryTest, StopsAtItsBudget) {
  NeighbourRules wide = *rules_;
  wide.eps = 1000;  // every frame within reach and within eps
  wide.k_max = 5000;
  for (LshRanking ranking : {LshRanking::kSortValue, LshRanking::kPositionCode}) {
    std::unique_ptr<testing::QueryParts> parts(Parts(ranking, &wide));
    parts->options.max_candidates = 50;
    ColumnQuery query(parts->context());
    std::vector<Neighbour> found;
    ColumnWork work;
    query.Run(1234, nullptr, &found, &work);
    EXPECT_EQ(work.evaluations, 50u) << LshRankingName(ranking);
    EXPECT_EQ(work.lsh.columns_budget_capped, 1u);
    ASSERT_EQ(found.size(), 50u);
    for (const Neighbour& neighbour : found) {
      EXPECT_EQ(neighbour.distance, PoseDistance(*features_, 1234, neighbour.frame));
    }
  }
}

// The distinct frames j + 0..2 of `previous` that column may hold.
std::vector<uint32_t> SeedsOf(const std::vector<Neighbour>& previous, uint64_t column,
                              const NeighbourRules& rules, const PoseFeatures& features) {
  std::set<uint32_t> seeds;
  for (const Neighbour& neighbour : previous) {
    for (uint32_t advance = 0; advance <= 2; ++advance) {
      const uint32_t frame = neighbour.frame + advance;
      if (frame >= features.frame_count() ||
          rules.Excluded(column, frame, features.ClipOf(column), features.ClipOf(frame))) {
        continue;
      }
      seeds.insert(frame);
    }
  }
  return {seeds.begin(), seeds.end()};
}

TEST_F(ColumnQueryTest, AChainedColumnVerifiesItsSeedsAndProbesOnlyAtItsTurn) {
  std::unique_ptr<testing::QueryParts> parts(Parts());
  parts->options.chain_columns = 256;
  parts->options.chain_probe_every = 4;
  parts->options.chained_max_candidates = 4000;
  ColumnQuery query(parts->context());
  // Column 1001 is at position 233 of its chain: it does not probe.
  const std::vector<Neighbour> previous = testing::ExactColumn(*features_, *rules_, 1000);
  const std::vector<uint32_t> seeds = SeedsOf(previous, 1001, *rules_, *features_);
  std::vector<Neighbour> expected;
  for (uint32_t frame : seeds) {
    const float distance = PoseDistance(*features_, 1001, frame);
    if (distance <= rules_->eps) expected.push_back({frame, distance});
  }
  FinishColumn(rules_->k_max, &expected);
  std::vector<Neighbour> found;
  ColumnWork work;
  query.Run(1001, &previous, &found, &work);
  EXPECT_EQ(found, expected);
  EXPECT_EQ(work.evaluations, seeds.size());
  EXPECT_EQ(work.lsh.seed_evaluations, seeds.size());
  EXPECT_EQ(work.lsh.probes, 0u);
  // Column 1004 (position 236) probes after its seeds, and finds the whole exact column.
  const std::vector<Neighbour> before = testing::ExactColumn(*features_, *rules_, 1003);
  work = ColumnWork();
  query.Run(1004, &before, &found, &work);
  EXPECT_EQ(found, testing::ExactColumn(*features_, *rules_, 1004));
  EXPECT_EQ(work.lsh.seed_evaluations, SeedsOf(before, 1004, *rules_, *features_).size());
  EXPECT_GT(work.lsh.probes, 0u);
  EXPECT_GT(work.evaluations, work.lsh.seed_evaluations);
}

TEST_F(ColumnQueryTest, ReportsTheOlderFramesItVerified) {
  NeighbourRules rules = *rules_;
  rules.k_max = 5000;  // the radius stays eps: every frame within eps is verified
  std::unique_ptr<testing::QueryParts> parts(Parts(LshRanking::kSortValue, &rules));
  ColumnQuery query(parts->context());
  const ReverseQuery reverse_query{10000, nullptr};
  const std::vector<uint64_t> columns = testing::ColumnsWithOlderNeighbours(
      *features_, rules, reverse_query.frame_limit, reverse_query.frame_limit, 5, 1);
  ASSERT_EQ(columns.size(), 1u);
  const uint64_t column = columns[0];
  std::vector<Neighbour> found;
  std::vector<Neighbour> reverse;
  ColumnWork work;
  query.Run(column, nullptr, &found, &work, &reverse_query, &reverse);
  std::sort(reverse.begin(), reverse.end(),
            [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
  std::vector<Neighbour> expected;
  for (const Neighbour& neighbour : testing::ExactColumn(*features_, rules, column)) {
    if (neighbour.frame < reverse_query.frame_limit) expected.push_back(neighbour);
  }
  EXPECT_GT(expected.size(), 5u);
  EXPECT_EQ(reverse, expected);
  EXPECT_EQ(found, testing::ExactColumn(*features_, rules, column));
}

}  // namespace
}  // namespace motif
