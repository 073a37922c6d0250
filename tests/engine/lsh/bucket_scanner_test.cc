// BucketCursor and BucketScanner over a hand-made table: a bucket is read outward from the
// query's sort value, nearer side first (ties up), and left where the lower bound leaves the
// reach; a small bucket is read in stored order; max_bucket_scan caps a bucket; the scanner
// reads all probed buckets breadth first in rounds of growing depth and stops at the first probe
// beyond reach or when a round says so.
#include "engine/lsh/bucket_scanner.h"

#include <gtest/gtest.h>

#include <tuple>
#include <vector>

namespace motif {
namespace {

// One table of 410 frames: bucket 10 holds frames 0..6 with sort values -5 -2 0 0 3 4 10; buckets
// 20 and 30 hold 200 frames each (7..206 and 207..406) with sort values 0..199; bucket 40 holds
// frames 407..409 with sort values 1 2 8. A frame's entry is at the position of its id.
LshIndex HandMadeIndex() {
  LshTableEntries table;
  auto add = [&](uint32_t key, int16_t sort_value) {
    table.keys.push_back(key);
    table.sort_values.push_back(sort_value);
    table.frames.push_back(static_cast<uint32_t>(table.frames.size()));
  };
  for (int16_t sort_value : {-5, -2, 0, 0, 3, 4, 10}) add(10, sort_value);
  for (int16_t sort_value = 0; sort_value < 200; ++sort_value) add(20, sort_value);
  for (int16_t sort_value = 0; sort_value < 200; ++sort_value) add(30, sort_value);
  for (int16_t sort_value : {1, 2, 8}) add(40, sort_value);
  auto index = LshIndex::FromTables(table.size(), {table}, false);
  EXPECT_TRUE(index.ok()) << index.status().ToString();
  return index.ok() ? std::move(*index) : LshIndex();
}

BucketProbe ProbeOf(uint32_t key, float score = 0) { return {score, 0, 0, key, 0, 0}; }

struct Read {
  std::vector<uint32_t> positions;
  std::vector<float> gaps;
  uint32_t skipped = 0;
};

// Every step of `cursor` until kDone.
Read ReadAll(BucketCursor* cursor, const LshIndex& index, float score, float sort_step,
             float limit_squared) {
  Read read;
  const int16_t* sort_values = index.table(0).sort_values.data();
  for (;;) {
    uint32_t position = 0;
    float gap = 0;
    const BucketCursor::Step step =
        cursor->Next(score, sort_values, sort_step, limit_squared, &position, &gap);
    if (step == BucketCursor::Step::kDone) break;
    if (step == BucketCursor::Step::kSkipped) {
      ++read.skipped;
      continue;
    }
    read.positions.push_back(position);
    read.gaps.push_back(gap);
  }
  return read;
}

LshOptions ScanOptions(uint32_t first_round_scan, uint32_t max_bucket_scan) {
  LshOptions options;
  options.first_round_scan = first_round_scan;
  options.max_bucket_scan = max_bucket_scan;
  return options;
}

TEST(BucketCursor, ReadsOutwardFromTheQuerysSortValueNearerSideFirst) {
  const LshIndex index = HandMadeIndex();
  BucketCursor cursor = BucketCursor::Open(index, ProbeOf(10), 1, ScanOptions(4, 2048));
  EXPECT_FALSE(cursor.done);
  EXPECT_FALSE(cursor.linear);
  EXPECT_EQ(cursor.scan_limit, 7u);
  const Read read = ReadAll(&cursor, index, 0, 1.0f, 1e9f);
  // Sort values 0 0 (gap 1, below), 3 (2), 4 (3, up wins the tie), -2 (3), -5 (6), 10 (9).
  EXPECT_EQ(read.positions, (std::vector<uint32_t>{3, 2, 4, 5, 1, 0, 6}));
  EXPECT_EQ(read.gaps, (std::vector<float>{1, 1, 2, 3, 3, 6, 9}));
  EXPECT_TRUE(cursor.done);
  EXPECT_EQ(cursor.examined, 7u);
}

TEST(BucketCursor, EndsWhereTheLowerBoundLeavesTheReach) {
  const LshIndex index = HandMadeIndex();
  // score 0.5 + gap^2 <= 4.5: gaps up to 2.
  BucketCursor cursor = BucketCursor::Open(index, ProbeOf(10, 0.5f), 1, ScanOptions(4, 2048));
  Read read = ReadAll(&cursor, index, 0.5f, 1.0f, 4.5f);
  EXPECT_EQ(read.positions, (std::vector<uint32_t>{3, 2, 4}));
  EXPECT_EQ(read.skipped, 0u);
  EXPECT_EQ(cursor.examined, 3u);
  EXPECT_TRUE(cursor.done);
  // Half a unit per sort-value step: gaps up to 4 steps.
  cursor = BucketCursor::Open(index, ProbeOf(10, 0.5f), 1, ScanOptions(4, 2048));
  read = ReadAll(&cursor, index, 0.5f, 0.5f, 4.5f);
  EXPECT_EQ(read.positions, (std::vector<uint32_t>{3, 2, 4, 5, 1}));
  EXPECT_EQ(read.gaps, (std::vector<float>{0.5f, 0.5f, 1.0f, 1.5f, 1.5f}));
}

TEST(BucketCursor, ReadsASmallBucketInStoredOrderSkippingWhatIsOutOfReach) {
  const LshIndex index = HandMadeIndex();
  BucketCursor cursor = BucketCursor::Open(index, ProbeOf(40), 5, ScanOptions(4, 2048));
  EXPECT_TRUE(cursor.linear);
  // Sort values 1 (gap 4, beyond 10), 2 (3), 8 (3).
  const Read read = ReadAll(&cursor, index, 0, 1.0f, 10.0f);
  EXPECT_EQ(read.positions, (std::vector<uint32_t>{408, 409}));
  EXPECT_EQ(read.skipped, 1u);
  EXPECT_EQ(cursor.examined, 3u);
}

TEST(BucketCursor, AnEmptyBucketIsDoneAtOnce) {
  const LshIndex index = HandMadeIndex();
  const BucketCursor cursor = BucketCursor::Open(index, ProbeOf(99), 0, ScanOptions(4, 2048));
  EXPECT_TRUE(cursor.done);
}

TEST(BucketCursor, EndRoundClosesACursorAtItsScanLimit) {
  const LshIndex index = HandMadeIndex();
  const int16_t* sort_values = index.table(0).sort_values.data();
  uint32_t position = 0;
  float gap = 0;
  uint64_t capped = 0;
  BucketCursor cursor = BucketCursor::Open(index, ProbeOf(10), 1, ScanOptions(4, 4));
  EXPECT_EQ(cursor.scan_limit, 4u);
  for (int step = 0; step < 3; ++step) cursor.Next(0, sort_values, 1.0f, 1e9f, &position, &gap);
  EXPECT_TRUE(cursor.EndRound(&capped));  // one entry left before the limit
  cursor.Next(0, sort_values, 1.0f, 1e9f, &position, &gap);
  EXPECT_FALSE(cursor.EndRound(&capped));
  EXPECT_TRUE(cursor.done);
  EXPECT_EQ(capped, 1u);  // three of the bucket's entries were left unread
  // A bucket read whole at its limit is not capped.
  cursor = BucketCursor::Open(index, ProbeOf(40), 0, ScanOptions(4, 4));
  EXPECT_EQ(cursor.scan_limit, 3u);
  for (int step = 0; step < 3; ++step) cursor.Next(0, sort_values, 1.0f, 1e9f, &position, &gap);
  EXPECT_FALSE(cursor.EndRound(&capped));
  EXPECT_EQ(capped, 1u);
}

// A visitor that reads every entry of each round and records the rounds.
struct RecordingVisitor {
  const LshIndex* index = nullptr;
  float reach_squared = 1e9f;
  int stop_after_rounds = -1;  // negative: never stop
  std::vector<size_t> opened;
  std::vector<std::tuple<size_t, uint32_t, uint32_t>> rounds;  // cursor, limit, examined after

  float ReachSquared() const { return reach_squared; }
  void Opened(const BucketProbe&, size_t cursor_idx) { opened.push_back(cursor_idx); }
  bool Round(const BucketProbe& probe, size_t cursor_idx, uint32_t round_limit,
             BucketCursor* cursor) {
    const int16_t* sort_values = index->table(0).sort_values.data();
    while (cursor->examined < round_limit) {
      uint32_t position = 0;
      float gap = 0;
      if (cursor->Next(probe.score, sort_values, 1.0f, reach_squared, &position, &gap) ==
          BucketCursor::Step::kDone) {
        break;
      }
    }
    rounds.emplace_back(cursor_idx, round_limit, cursor->examined);
    return static_cast<int>(rounds.size()) == stop_after_rounds;
  }
};

TEST(BucketScanner, ReadsEveryProbedBucketBreadthFirstInGrowingRounds) {
  const LshIndex index = HandMadeIndex();
  const std::vector<BucketProbe> probes = {ProbeOf(99), ProbeOf(20, 0.1f), ProbeOf(30, 0.2f)};
  const int16_t query_sort_values[] = {100};
  const LshOptions options = ScanOptions(64, 2048);
  BucketScanner scanner(index, options);
  RecordingVisitor visitor;
  visitor.index = &index;
  // From probe 1 on: cursor 0 is bucket 20, cursor 1 bucket 30.
  BucketScanner::Outcome outcome = scanner.Scan(probes, 1, query_sort_values, &visitor);
  using Round = std::tuple<size_t, uint32_t, uint32_t>;
  EXPECT_EQ(visitor.rounds,
            (std::vector<Round>{{0, 64, 64}, {1, 64, 64}, {0, 200, 200}, {1, 200, 200}}));
  EXPECT_EQ(visitor.opened, (std::vector<size_t>{0, 1}));
  EXPECT_EQ(outcome.buckets_opened, 2u);
  EXPECT_EQ(outcome.scans_capped, 0u);
  EXPECT_FALSE(outcome.stopped);
  EXPECT_FALSE(outcome.beyond_reach);

  // All three probes: the empty bucket is looked up but never read.
  visitor = RecordingVisitor();
  visitor.index = &index;
  outcome = scanner.Scan(probes, 0, query_sort_values, &visitor);
  EXPECT_EQ(outcome.buckets_opened, 3u);
  EXPECT_EQ(visitor.opened, (std::vector<size_t>{1, 2}));
  EXPECT_EQ(visitor.rounds.size(), 4u);
  EXPECT_EQ(std::get<0>(visitor.rounds[0]), 1u);

  // max_bucket_scan 128: 64, then 128 and capped.
  const LshOptions capped_options = ScanOptions(64, 128);
  BucketScanner capped_scanner(index, capped_options);
  visitor = RecordingVisitor();
  visitor.index = &index;
  outcome = capped_scanner.Scan(probes, 1, query_sort_values, &visitor);
  EXPECT_EQ(visitor.rounds,
            (std::vector<Round>{{0, 64, 64}, {1, 64, 64}, {0, 128, 128}, {1, 128, 128}}));
  EXPECT_EQ(outcome.scans_capped, 2u);
}

TEST(BucketScanner, StopsAtTheFirstProbeBeyondReach) {
  const LshIndex index = HandMadeIndex();
  const std::vector<BucketProbe> probes = {ProbeOf(40), ProbeOf(20, 5.0f), ProbeOf(30, 6.0f)};
  const int16_t query_sort_values[] = {0};
  const LshOptions options = ScanOptions(64, 2048);
  BucketScanner scanner(index, options);
  RecordingVisitor visitor;
  visitor.index = &index;
  visitor.reach_squared = 4.0f;
  const BucketScanner::Outcome outcome = scanner.Scan(probes, 0, query_sort_values, &visitor);
  using Round = std::tuple<size_t, uint32_t, uint32_t>;
  // Bucket 40 (sort values 1 2 8; gap 8 beyond the reach) is read, the others are not opened.
  EXPECT_EQ(visitor.rounds, (std::vector<Round>{{0, 3, 3}}));
  EXPECT_TRUE(outcome.beyond_reach);
  EXPECT_EQ(outcome.buckets_opened, 1u);
}

TEST(BucketScanner, StopsWhenARoundSaysSo) {
  const LshIndex index = HandMadeIndex();
  const std::vector<BucketProbe> probes = {ProbeOf(20), ProbeOf(30, 0.1f)};
  const int16_t query_sort_values[] = {0};
  const LshOptions options = ScanOptions(64, 2048);
  BucketScanner scanner(index, options);
  RecordingVisitor visitor;
  visitor.index = &index;
  visitor.stop_after_rounds = 3;
  const BucketScanner::Outcome outcome = scanner.Scan(probes, 0, query_sort_values, &visitor);
  EXPECT_EQ(visitor.rounds.size(), 3u);
  EXPECT_TRUE(outcome.stopped);
  EXPECT_FALSE(outcome.beyond_reach);
}

}  // namespace
}  // namespace motif
