// PositionCodeRanker: the estimate tables hold, per pair of coded coordinates, the squared
// distance (1/128 cell^2 units) from the query's position to the centre of each quarter of the
// probed cell, plus the boundaries crossed along uncoded coordinates; the gathered entries come
// back by estimate bin, in gathering order within a bin. Positions are chosen so that every
// value is exact in binary.
#include "engine/lsh/position_code_ranker.h"

#include <gtest/gtest.h>

#include <vector>

namespace motif {
namespace {

HashFamily FamilyOf(uint32_t hashes) {
  return HashFamily::Draw(std::vector<float>(12, 1.0f), 1, hashes, 1.0f, 3);
}

BucketProbe ProbeWithMasks(uint32_t minus_mask, uint32_t plus_mask) {
  return {0, 0, 0, 0, minus_mask, plus_mask};
}

TEST(PositionCodeRanker, EstimatesTheSquaredDistanceToEachQuarterCentre) {
  const HashFamily family = FamilyOf(2);
  PositionCodeRanker ranker(family);
  // Positions 0.125 and 0.625 within their cells; the third value is the sort value.
  const float coordinates[] = {3.125f, -1.375f, 0.0f};
  // The query's own cell: coordinate 0's quarters at 0, 1, 2, 3 quarter-cells (0, 8, 32, 72),
  // coordinate 1's at -2, -1, 0, 1 (32, 8, 0, 8).
  ranker.FillEstimateTable(ProbeWithMasks(0, 0), coordinates, 0);
  // Coordinate 0 one cell below (-4..-1 quarters: 128, 72, 32, 8), coordinate 1 one above
  // (2..5: 32, 72, 128, 200).
  ranker.FillEstimateTable(ProbeWithMasks(1, 2), coordinates, 1);
  const uint16_t own0[] = {0, 8, 32, 72}, own1[] = {32, 8, 0, 8};
  const uint16_t below0[] = {128, 72, 32, 8}, above1[] = {32, 72, 128, 200};
  for (uint32_t value = 0; value < 16; ++value) {
    EXPECT_EQ(ranker.estimate(0, 0, value), own0[value & 3] + own1[value >> 2]) << value;
    EXPECT_EQ(ranker.estimate(1, 0, value), below0[value & 3] + above1[value >> 2]) << value;
    for (uint32_t nibble = 1; nibble < 8; ++nibble) {  // no coordinates there
      EXPECT_EQ(ranker.estimate(0, nibble, value), 0u);
    }
  }
}

TEST(PositionCodeRanker, UncodedCoordinatesAddTheBoundariesCrossed) {
  const HashFamily family = FamilyOf(18);
  PositionCodeRanker ranker(family);
  std::vector<float> coordinates(19, 0.5f);  // every coded one mid-cell: 18, 2, 2, 18
  coordinates[16] = 7.25f;                   // uncoded; its lower boundary at 1/4 cell: 8
  ranker.FillEstimateTable(ProbeWithMasks(1u << 16, 1u << 17), coordinates.data(), 0);
  const uint16_t mid[] = {18, 2, 2, 18};
  const uint16_t base = 8 + 32;  // coordinate 17's upper boundary at 1/2 cell: 32
  for (uint32_t nibble = 0; nibble < 8; ++nibble) {
    for (uint32_t value = 0; value < 16; ++value) {
      EXPECT_EQ(ranker.estimate(0, nibble, value),
                mid[value & 3] + mid[value >> 2] + (nibble == 0 ? base : 0))
          << nibble << " " << value;
    }
  }
}

TEST(PositionCodeRanker, RanksByEstimateInGatheringOrderWithinABin) {
  const HashFamily family = FamilyOf(2);
  PositionCodeRanker ranker(family);
  const float coordinates[] = {3.125f, -1.375f, 0.0f};
  ranker.FillEstimateTable(ProbeWithMasks(0, 0), coordinates, 0);
  ranker.FillEstimateTable(ProbeWithMasks(1, 2), coordinates, 1);
  EXPECT_EQ(ranker.Add(10, 1.0f, 0, 0x0, 0), 1u);         // 0 + 32
  EXPECT_EQ(ranker.Add(11, 2.0f, 0, 0xabcdef02, 0), 2u);  // 32 + 32 (no coordinate above 1)
  EXPECT_EQ(ranker.Add(12, 3.0f, 1, 0x3, 0), 3u);         // 8 + 32
  EXPECT_EQ(ranker.Add(13, 4.0f, 0, 0x8, 0), 4u);         // 0 + 0
  EXPECT_EQ(ranker.Add(14, 5.0f, 0, 0x0, 100.0f), 5u);    // a far sort value: the last bin
  EXPECT_EQ(ranker.Add(15, 6.0f, 1, 0xb, 0), 6u);         // 8 + 128
  EXPECT_EQ(ranker.Add(16, 7.0f, 0, 0x0, 0), 7u);         // 32, after frame 10
  const std::vector<PositionCodeRanker::Ranked>& ranked = ranker.Rank();
  std::vector<uint32_t> frames;
  std::vector<float> lower;
  for (const PositionCodeRanker::Ranked& entry : ranked) {
    frames.push_back(entry.frame);
    lower.push_back(entry.lower_squared);
  }
  // Bins: 13 at 0, 10 and 16 at 32, 12 at 40, 11 at 64, 15 at 136, 14 at 1023.
  EXPECT_EQ(frames, (std::vector<uint32_t>{13, 10, 16, 12, 11, 15, 14}));
  EXPECT_EQ(lower, (std::vector<float>{4, 1, 7, 3, 2, 6, 5}));
  ranker.Clear();
  EXPECT_TRUE(ranker.Rank().empty());
}

}  // namespace
}  // namespace motif
