#include "engine/evaluation/planted_motif_score.h"

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(AdjustedRandIndexTest, KnownValues) {
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({0, 0, 1, 1, 2}, {0, 0, 1, 1, 2}), 1.0);
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({0, 0, 1, 1, 2}, {5, 5, 3, 3, 9}), 1.0);  // renamed labels
  // Textbook (scikit-learn's adjusted_rand_score examples): 4/7 and -1/2.
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 1, 1}, {0, 0, 1, 2}), 4.0 / 7.0, 1e-12);
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 1, 1}, {0, 1, 0, 1}), -0.5, 1e-12);
  // By hand: contingency [[2, 1, 0], [0, 1, 2]]: index 2, rows 6, columns 3, pairs 15:
  // expected 6·3/15 = 1.2, max 4.5, ARI = 0.8 / 3.3 = 8/33.
  EXPECT_NEAR(AdjustedRandIndex({0, 0, 0, 1, 1, 1}, {0, 0, 1, 1, 2, 2}), 8.0 / 33.0, 1e-12);
  // Everything together against everything apart: no agreement beyond chance.
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({0, 0, 0, 0}, {0, 1, 2, 3}), 0.0);
  // Degenerate cases.
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({}, {}), 1.0);
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({3}, {4}), 1.0);
  EXPECT_DOUBLE_EQ(AdjustedRandIndex({1, 1, 1}, {2, 2, 2}), 1.0);
}

TEST(InstancesHitTest, HalfOfTheShorterIsEnough) {
  EXPECT_TRUE(InstancesHit(0, 100, 50, 150));    // 50 of 100
  EXPECT_FALSE(InstancesHit(0, 100, 51, 151));   // 49 of 100
  EXPECT_TRUE(InstancesHit(0, 1000, 400, 420));  // a short one inside a long one
  EXPECT_TRUE(InstancesHit(0, 9, 4, 100));       // 5 of 9: 2 * 5 >= 9
  EXPECT_FALSE(InstancesHit(0, 9, 5, 100));      // 4 of 9
}

TEST(ScorePlantedMotifsTest, RecallPrecisionAndAri) {
  const std::vector<PlantedInstance> planted = {
      {"a", 100, 200, 0}, {"a", 500, 600, 0}, {"b", 100, 200, 0},
      {"b", 400, 460, 1}, {"c", 0, 60, 1},    {"c", 300, 360, 1},
  };
  const std::vector<FoundInstance> found = {
      {"a", 120, 220, 4},  // hits a:100-200 (80 of 100)
      {"a", 540, 700, 4},  // hits a:500-600 (60 of 100)
      {"b", 100, 140, 4},  // 40 of 40 (the shorter): hits b:100-200
      {"b", 430, 500, 5},  // hits b:400-460 (30 of 60)
      {"c", 31, 90, 5},    // 29 of 59: misses c:0-60
      {"a", 400, 460, 5},  // nothing planted there
      {"d", 0, 60, 6},     // another clip
  };
  PlantedMotifScore score = ScorePlantedMotifs(found, planted);
  EXPECT_EQ(score.planted, 6u);
  EXPECT_EQ(score.found, 7u);
  EXPECT_EQ(score.planted_hit, 4u);
  EXPECT_EQ(score.found_hitting, 4u);
  EXPECT_DOUBLE_EQ(score.recall, 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(score.precision, 4.0 / 7.0);
  EXPECT_DOUBLE_EQ(score.adjusted_rand_index, 1.0);  // {0,0,0,1} vs {4,4,4,5}
  EXPECT_EQ(score.planted_motifs, 2u);
  EXPECT_EQ(score.found_motifs, 3u);
}

TEST(ScorePlantedMotifsTest, TheLargestOverlapLabelsAPlantedInstance) {
  const std::vector<PlantedInstance> planted = {
      {"a", 0, 100, 0}, {"a", 200, 300, 0}, {"a", 400, 500, 1}, {"a", 600, 700, 1}};
  const std::vector<FoundInstance> found = {
      {"a", 0, 60, 2},    {"a", 40, 100, 3},   // 60 and 60: a tie, the lower motif id (2) wins
      {"a", 200, 300, 3}, {"a", 180, 260, 2},  // 100 beats 60: motif 3
      {"a", 400, 500, 4}, {"a", 600, 700, 4}};
  PlantedMotifScore score = ScorePlantedMotifs(found, planted);
  EXPECT_EQ(score.planted_hit, 4u);
  EXPECT_EQ(score.found_hitting, 6u);
  // Labels {0, 0, 1, 1} vs {2, 3, 4, 4}: index 1, rows 2, columns 1, pairs 6: expected 1/3,
  // max 1.5, ARI = (2/3) / (7/6) = 4/7.
  EXPECT_NEAR(score.adjusted_rand_index, 4.0 / 7.0, 1e-12);
}

TEST(ScorePlantedMotifsTest, NothingFound) {
  PlantedMotifScore score = ScorePlantedMotifs({}, {{"a", 0, 10, 0}});
  EXPECT_EQ(score.recall, 0.0);
  EXPECT_EQ(score.precision, 0.0);
}

}  // namespace
}  // namespace motif
