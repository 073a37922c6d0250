#include "engine/words/signature_change.h"

#include <cmath>

#include <gtest/gtest.h>

namespace motif::testing {
namespace {

TEST(SignatureChange, ScoresCompareTheWordsBeforeAndAfterEachBoundary) {
  // Words 0..9 of "value" 0, words 10..19 of value 1: the score is the difference of the sides'
  // means, largest at the change.
  const auto value = [](uint64_t word) { return word < 10 ? 0.0 : 1.0; };
  const auto mean = [&](uint64_t first, uint64_t end) {
    double sum = 0;
    for (uint64_t word = first; word < end; ++word) sum += value(word);
    return sum / static_cast<double>(end - first);
  };
  const std::vector<double> scores =
      ChangeScores(20, 4, [&](uint64_t a0, uint64_t a1, uint64_t b0, uint64_t b1) {
        EXPECT_EQ(a1, b0);
        return std::abs(mean(b0, b1) - mean(a0, a1));
      });
  ASSERT_EQ(scores.size(), 19u);
  EXPECT_TRUE(std::isnan(scores[0]));  // boundary 1: one word before, fewer than 2
  EXPECT_DOUBLE_EQ(scores[1], 0.0);    // boundary 2: [0, 2) against [2, 6)
  EXPECT_DOUBLE_EQ(scores[9], 1.0);    // boundary 10: [6, 10) against [10, 14)
  EXPECT_DOUBLE_EQ(scores[8], 0.75);   // boundary 9: [5, 9) against [9, 13)
  EXPECT_DOUBLE_EQ(scores[17], 0.0);   // boundary 18: [14, 18) against [18, 20)
  EXPECT_TRUE(std::isnan(scores[18]));
  EXPECT_EQ(PickBoundaries(scores, 0.5, 4), std::vector<uint64_t>{10});
  EXPECT_TRUE(PickBoundaries(scores, 1.0, 4).empty());  // above the threshold, not at it
}

TEST(SignatureChange, BoundariesArePeaksWithinTheWindowTheEarlierOnATie) {
  const double nan = std::nan("");
  const std::vector<double> scores = {nan, 1, 5, 2, 5, 1, 1, 1, 4, 1, 1, 0.5, 3, nan};
  // 5 at index 2 and 4 tie within 2: the earlier (boundary 3). 4 at index 8 and 3 at index 12
  // are 4 apart: both peaks.
  EXPECT_EQ(PickBoundaries(scores, 2.5, 2), (std::vector<uint64_t>{3, 9, 13}));
  // With a window of 4 the 4 at index 8 is within 4 of the 5 at index 4, and the 3 at index 12
  // within 4 of that 4.
  EXPECT_EQ(PickBoundaries(scores, 2.5, 4), std::vector<uint64_t>{3});
}

TEST(SignatureChange, TheThresholdIsTheMeanPlusOneStandardDeviation) {
  const double nan = std::nan("");
  // Scores 1, 2, 3, 4 over two takes: mean 2.5, population sd sqrt(1.25).
  EXPECT_DOUBLE_EQ(ChangeThreshold({{1, nan, 2}, {3, 4}}), 2.5 + std::sqrt(1.25));
  EXPECT_TRUE(std::isinf(ChangeThreshold({{nan}, {}})));
  // Other numbers of standard deviations, as the affinity profiles' rules use.
  EXPECT_DOUBLE_EQ(ChangeThreshold({{1, nan, 2}, {3, 4}}, 0.5), 2.5 + 0.5 * std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(ChangeThreshold({{1, nan, 2}, {3, 4}}, 0.0), 2.5);
}

// 0, 1, 2 close together (but 0-2 at 1.5); 3, 4 close; 5 far from all.
Eigen::MatrixXd ThreeTwoOne() {
  Eigen::MatrixXd d(6, 6);
  d << 0, 1, 1.5, 9, 9, 9,  //
      1, 0, 1, 9, 9, 9,     //
      1.5, 1, 0, 9, 9, 9,   //
      9, 9, 9, 0, 0.5, 9,   //
      9, 9, 9, 0.5, 0, 9,   //
      9, 9, 9, 9, 9, 0;
  return d;
}

TEST(SignatureChange, CompleteLinkageNeverJoinsItemsFartherThanTheThreshold) {
  const Eigen::MatrixXd d = ThreeTwoOne();
  EXPECT_EQ(CompleteLinkageGroups(d, 2.0), (std::vector<uint32_t>{0, 0, 0, 1, 1, 2}));
  // At 1.2, 0-1 join first (ties go to the lower pair), then 2 cannot join them (1.5 from 0).
  EXPECT_EQ(CompleteLinkageGroups(d, 1.2), (std::vector<uint32_t>{0, 0, 1, 2, 2, 3}));
  EXPECT_EQ(CompleteLinkageGroups(d, 0.1), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(CompleteLinkageGroups(d, 100), (std::vector<uint32_t>(6, 0)));
}


TEST(SignatureChange, AverageLinkageJoinsAtTheMeanDistanceAcrossTheGroups) {
  const Eigen::MatrixXd d = ThreeTwoOne();
  // 3-4 (0.5), then 0-1 (1, before 1-2 on the tie); 2 is then (1.5 + 1) / 2 = 1.25 from {0, 1}.
  EXPECT_EQ(LinkageGroups(d, 1.2, 0, Linkage::kAverage),
            (std::vector<uint32_t>{0, 0, 1, 2, 2, 3}));
  EXPECT_EQ(LinkageGroups(d, 1.3, 0, Linkage::kAverage),
            (std::vector<uint32_t>{0, 0, 0, 1, 1, 2}));
  // Complete linkage keeps 2 apart at 1.3: its largest distance to {0, 1} is 1.5.
  EXPECT_EQ(LinkageGroups(d, 1.3, 0, Linkage::kComplete),
            (std::vector<uint32_t>{0, 0, 1, 2, 2, 3}));
  // {0, 1, 2} to {3, 4}: the mean of six 9s.
  EXPECT_EQ(LinkageGroups(d, 8.9, 0, Linkage::kAverage),
            (std::vector<uint32_t>{0, 0, 0, 1, 1, 2}));
}

TEST(SignatureChange, AGivenNumberOfGroupsIgnoresTheThreshold) {
  const Eigen::MatrixXd d = ThreeTwoOne();
  EXPECT_EQ(CompleteLinkageGroups(d, 0.0, 3), (std::vector<uint32_t>{0, 0, 0, 1, 1, 2}));
  // The three groups are all 9 apart: the tie goes to the lower pair.
  EXPECT_EQ(CompleteLinkageGroups(d, 0.0, 2), (std::vector<uint32_t>{0, 0, 0, 0, 0, 1}));
  EXPECT_EQ(LinkageGroups(d, 100, 1, Linkage::kAverage), (std::vector<uint32_t>(6, 0)));
  EXPECT_EQ(CompleteLinkageGroups(d, 100, 10), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace motif::testing
