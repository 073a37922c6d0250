// ProbeSequence: the query's own bucket first in every table, then the neighbouring buckets in
// increasing multi-probe score, exactly those a brute-force enumeration of all 3^m neighbouring
// cells ranks lowest; sorted by (score, table, rank); extension stages append only the next ranks.
#include "engine/lsh/probe_sequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

constexpr uint32_t kTables = 3;
constexpr uint32_t kHashes = 4;
constexpr float kWidth = 0.3f;

class ProbeSequenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(20000, 11));
    family_ = new HashFamily(HashFamily::Draw(features_->weights(), kTables, kHashes, kWidth, 17));
    auto index = LshIndex::Build(*features_, *family_, 1024, 1);
    ASSERT_TRUE(index.ok()) << index.status().ToString();
    index_ = new LshIndex(std::move(*index));
  }
  static void TearDownTestSuite() {
    delete index_;
    delete family_;
    delete features_;
  }
  static PoseFeatures* features_;
  static HashFamily* family_;
  static LshIndex* index_;
};

PoseFeatures* ProbeSequenceTest::features_ = nullptr;
HashFamily* ProbeSequenceTest::family_ = nullptr;
LshIndex* ProbeSequenceTest::index_ = nullptr;

struct ExpectedProbe {
  double score;
  uint32_t key;
  uint32_t minus_mask;
  uint32_t plus_mask;
};

// Every cell within one step of the query's along each coordinate (3^m, the query's own
// included), with its score w^2 * (sum of the squared distances to the boundaries crossed),
// lowest first.
std::vector<ExpectedProbe> AllNeighbouringCells(const float* coordinates) {
  std::vector<ExpectedProbe> cells;
  uint32_t combinations = 1;
  for (uint32_t idx = 0; idx < kHashes; ++idx) combinations *= 3;
  for (uint32_t combination = 0; combination < combinations; ++combination) {
    int32_t cell[kHashes];
    double score = 0;
    uint32_t minus_mask = 0;
    uint32_t plus_mask = 0;
    uint32_t rest = combination;
    for (uint32_t idx = 0; idx < kHashes; ++idx, rest /= 3) {
      const double fraction = coordinates[idx] - std::floor(coordinates[idx]);
      cell[idx] = static_cast<int32_t>(std::floor(coordinates[idx]));
      if (rest % 3 == 1) {
        cell[idx] -= 1;
        score += fraction * fraction;
        minus_mask |= 1u << idx;
      } else if (rest % 3 == 2) {
        cell[idx] += 1;
        score += (1 - fraction) * (1 - fraction);
        plus_mask |= 1u << idx;
      }
    }
    cells.push_back(
        {score * kWidth * kWidth, HashFamily::BucketKey(cell, kHashes), minus_mask, plus_mask});
  }
  std::sort(cells.begin(), cells.end(),
            [](const ExpectedProbe& a, const ExpectedProbe& b) { return a.score < b.score; });
  return cells;
}

// The probes of one table, by rank.
std::vector<BucketProbe> ProbesOfTable(const std::vector<BucketProbe>& probes, uint32_t table) {
  std::vector<BucketProbe> of_table;
  for (const BucketProbe& probe : probes) {
    if (probe.table_idx == table) of_table.push_back(probe);
  }
  std::sort(of_table.begin(), of_table.end(),
            [](const BucketProbe& a, const BucketProbe& b) { return a.rank < b.rank; });
  return of_table;
}

TEST_F(ProbeSequenceTest, OwnBucketFirstInEveryTable) {
  ProbeSequence sequence(*family_, *index_);
  for (uint64_t frame : {0u, 777u, 1999u}) {
    sequence.Prepare(features_->frame(frame), 5);
    ASSERT_EQ(sequence.probes().size(), kTables * 5);
    for (uint32_t table = 0; table < kTables; ++table) {
      const BucketProbe& own = sequence.probes()[table];  // score 0 sorts first, by table
      EXPECT_EQ(own.table_idx, table);
      EXPECT_EQ(own.rank, 0u);
      EXPECT_EQ(own.score, 0.0f);
      EXPECT_EQ(own.key, family_->KeyOfCoordinates(sequence.coordinates(table)));
      // The frame is in its own bucket, under the sort value the query computed.
      const auto [begin, end] = index_->FindBucket(table, own.key);
      const LshTableEntries& entries = index_->table(table);
      const auto found = std::find(entries.frames.begin() + begin, entries.frames.begin() + end,
                                   static_cast<uint32_t>(frame));
      ASSERT_NE(found, entries.frames.begin() + end) << "frame " << frame << " table " << table;
      EXPECT_EQ(entries.sort_values[found - entries.frames.begin()],
                sequence.query_sort_values()[table]);
    }
  }
}

TEST_F(ProbeSequenceTest, ListsTheLowestScoringNeighbouringCellsOfEachTable) {
  ProbeSequence sequence(*family_, *index_);
  for (uint64_t frame : {3u, 500u, 1234u}) {
    sequence.Prepare(features_->frame(frame), 10);
    for (uint32_t table = 0; table < kTables; ++table) {
      const std::vector<ExpectedProbe> expected = AllNeighbouringCells(sequence.coordinates(table));
      const std::vector<BucketProbe> listed = ProbesOfTable(sequence.probes(), table);
      ASSERT_EQ(listed.size(), 10u);
      for (uint32_t rank = 0; rank < 10; ++rank) {
        SCOPED_TRACE(::testing::Message()
                     << "frame " << frame << " table " << table << " rank " << rank);
        EXPECT_EQ(listed[rank].key, expected[rank].key);
        EXPECT_EQ(listed[rank].minus_mask, expected[rank].minus_mask);
        EXPECT_EQ(listed[rank].plus_mask, expected[rank].plus_mask);
        EXPECT_NEAR(listed[rank].score, expected[rank].score, 1e-6 + 1e-5 * expected[rank].score);
      }
    }
  }
}

TEST_F(ProbeSequenceTest, IsSortedByScoreThenTableThenRank) {
  ProbeSequence sequence(*family_, *index_);
  sequence.Prepare(features_->frame(42), 8);
  const std::vector<BucketProbe>& probes = sequence.probes();
  ASSERT_EQ(probes.size(), kTables * 8);
  for (size_t idx = 1; idx < probes.size(); ++idx) {
    EXPECT_TRUE(ProbeBefore(probes[idx - 1], probes[idx])) << idx;
  }
  EXPECT_TRUE(ProbeBefore({0.5f, 2, 3}, {0.6f, 0, 0}));
  EXPECT_TRUE(ProbeBefore({0.5f, 1, 3}, {0.5f, 2, 0}));
  EXPECT_TRUE(ProbeBefore({0.5f, 1, 2}, {0.5f, 1, 3}));
  EXPECT_FALSE(ProbeBefore({0.5f, 1, 3}, {0.5f, 1, 3}));
}

TEST_F(ProbeSequenceTest, AddProbesAppendsOnlyTheNextRanks) {
  ProbeSequence sequence(*family_, *index_);
  sequence.Prepare(features_->frame(1500), 4);
  const std::vector<BucketProbe> first = sequence.probes();
  sequence.AddProbes(16, 4);
  const std::vector<BucketProbe>& all = sequence.probes();
  ASSERT_EQ(all.size(), kTables * 16);
  for (size_t idx = 0; idx < first.size(); ++idx) {
    EXPECT_EQ(all[idx].key, first[idx].key);
    EXPECT_EQ(all[idx].table_idx, first[idx].table_idx);
  }
  const std::vector<BucketProbe> added(all.begin() + first.size(), all.end());
  for (size_t idx = 1; idx < added.size(); ++idx)
    EXPECT_TRUE(ProbeBefore(added[idx - 1], added[idx]));
  for (uint32_t table = 0; table < kTables; ++table) {
    const std::vector<ExpectedProbe> expected = AllNeighbouringCells(sequence.coordinates(table));
    const std::vector<BucketProbe> listed = ProbesOfTable(added, table);
    ASSERT_EQ(listed.size(), 12u);
    for (uint32_t idx = 0; idx < 12; ++idx) {
      EXPECT_EQ(listed[idx].rank, 4 + idx);
      EXPECT_EQ(listed[idx].key, expected[4 + idx].key) << "table " << table << " rank " << 4 + idx;
    }
  }
}

}  // namespace
}  // namespace motif
