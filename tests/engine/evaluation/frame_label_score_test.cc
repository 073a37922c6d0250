// The one-to-one assignment (label_assignment.h) and the frame-label scorer
// (frame_label_score.h) on small cases worked out by hand.
#include "engine/evaluation/frame_label_score.h"

#include <gtest/gtest.h>

#include <fstream>

#include "engine/evaluation/label_assignment.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TEST(MaximumAgreementAssignment, FindsThePairingGreedyChoiceMisses) {
  Eigen::MatrixXd agreement(3, 3);
  agreement << 5, 4, 0,  //
      4, 0, 0,           //
      0, 0, 1;
  // Greedy takes the 5 and is left with 0 + 1; the best pairing is 4 + 4 + 1.
  EXPECT_EQ(MaximumAgreementAssignment(agreement), (std::vector<int32_t>{1, 0, 2}));
}

TEST(MaximumAgreementAssignment, LeavesTheSurplusRowsOrColumnsUnmatched) {
  Eigen::MatrixXd wide(2, 3);
  wide << 1, 7, 2,  //
      6, 8, 0;
  EXPECT_EQ(MaximumAgreementAssignment(wide), (std::vector<int32_t>{1, 0}));
  Eigen::MatrixXd tall(3, 2);
  tall << 1, 6,  //
      7, 8,      //
      2, 0;
  EXPECT_EQ(MaximumAgreementAssignment(tall), (std::vector<int32_t>{1, 0, kUnmatched}));
  EXPECT_EQ(MaximumAgreementAssignment(Eigen::MatrixXd(2, 0)),
            (std::vector<int32_t>{kUnmatched, kUnmatched}));
}

const std::vector<TruthOccurrence> kJumpThenWalk = {{"a", "jump", 0, 10}, {"a", "walk", 10, 20}};

TEST(ScoreFrameLabels, MajorityLetsTwoGroupsTakeOneLabelOneToOneDoesNot) {
  // Three groups for two actions: majority scores every frame right; one-to-one pairs walk with
  // one of its two groups (the first of equals), and the other's 5 frames score nothing.
  Result<FrameLabelScore> score = ScoreFrameLabels(
      {{"a", 0, 10, "g1"}, {"a", 10, 15, "g2"}, {"a", 15, 20, "g3"}}, kJumpThenWalk);
  ASSERT_TRUE(score.ok()) << score.status().ToString();
  EXPECT_EQ(score->frames, 20u);
  EXPECT_EQ(score->labels, (std::vector<std::string>{"jump", "walk"}));
  EXPECT_EQ(score->groups, (std::vector<std::string>{"g1", "g2", "g3"}));
  EXPECT_DOUBLE_EQ(score->majority.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(score->majority.macro_f1, 1.0);
  EXPECT_EQ(score->majority.label_of_group, (std::vector<std::string>{"jump", "walk", "walk"}));
  EXPECT_DOUBLE_EQ(score->one_to_one.accuracy, 0.75);
  // jump F1 1; walk: 5 right of 5 scored walk and 10 walk frames: 2 * 5 / 15.
  EXPECT_DOUBLE_EQ(score->one_to_one.macro_f1, (1.0 + 10.0 / 15.0) / 2);
  EXPECT_EQ(score->one_to_one.label_of_group.size(), 3u);
  EXPECT_EQ(score->one_to_one.label_of_group[0], "jump");
}

TEST(ScoreFrameLabels, AGroupSpanningTwoActionsTakesItsMajority) {
  // g1 holds 6 jump and 10 walk frames, g2 4 jump frames: both rules give g1 walk, g2 jump.
  Result<FrameLabelScore> score =
      ScoreFrameLabels({{"a", 0, 6, "g1"}, {"a", 6, 10, "g2"}, {"a", 10, 20, "g1"}}, kJumpThenWalk);
  ASSERT_TRUE(score.ok()) << score.status().ToString();
  EXPECT_DOUBLE_EQ(score->majority.accuracy, 0.7);
  EXPECT_DOUBLE_EQ(score->one_to_one.accuracy, 0.7);
  // jump: 2 * 4 / (4 + 10); walk: 2 * 10 / (16 + 10).
  EXPECT_DOUBLE_EQ(score->majority.macro_f1, (8.0 / 14.0 + 20.0 / 26.0) / 2);
  EXPECT_DOUBLE_EQ(score->one_to_one.macro_f1, score->majority.macro_f1);
}

TEST(ScoreFrameLabels, GroupsSpanTakesUngroupedFramesCountAndOtherTakesAreLeftOut) {
  const std::vector<TruthOccurrence> labels = {
      {"a", "jump", 0, 10}, {"b", "jump", 0, 10}, {"b", "walk", 10, 20}, {"c", "walk", 0, 50}};
  // b's last 4 frames have no group; clip c was not segmented.
  Result<FrameLabelScore> score = ScoreFrameLabels(
      {{"a", 0, 10, "g1"}, {"b", 0, 10, "g1"}, {"b", 10, 16, "g2"}, {"b", 16, 20, ""}}, labels);
  ASSERT_TRUE(score.ok()) << score.status().ToString();
  EXPECT_EQ(score->frames, 30u);
  EXPECT_EQ(score->frames_ungrouped, 4u);
  EXPECT_EQ(score->frames_elsewhere, 50u);
  EXPECT_DOUBLE_EQ(score->majority.accuracy, 26.0 / 30.0);
  EXPECT_DOUBLE_EQ(score->one_to_one.accuracy, 26.0 / 30.0);
  ASSERT_EQ(score->clips.size(), 2u);
  EXPECT_EQ(score->clips[0].clip, "a");
  EXPECT_DOUBLE_EQ(score->clips[0].majority_accuracy, 1.0);
  EXPECT_EQ(score->clips[1].frames, 20u);
  EXPECT_DOUBLE_EQ(score->clips[1].one_to_one_accuracy, 16.0 / 20.0);
}

TEST(ScoreFrameLabels, AFrameWithTwoLabelsIsAnErrorNamingIt) {
  Result<FrameLabelScore> score = ScoreFrameLabels(
      {{"a", 0, 20, "g1"}}, {{"a", "jump", 0, 10}, {"a", "walk", 9, 20}});
  ASSERT_FALSE(score.ok());
  EXPECT_TRUE(score.status().IsInvalidArgument());
  EXPECT_NE(score.status().message().find("frame 9 of clip a"), std::string::npos)
      << score.status().ToString();
}

TEST(ReadSegmentsJson, ReadsSegmentsWithTheirGroupsAndRefusesAnotherFile) {
  testing::TempDir dir;
  const std::string path = dir.path() + "/segments.json";
  std::ofstream(path) << R"({"version": 1, "segments": [
      {"clip": "a", "start": 0, "end": 12, "label": "group 1", "words": 2},
      {"clip": "a", "start": 12, "end": 30, "label": null, "words": 3}]})";
  Result<std::vector<GroupedSegment>> segments = ReadSegmentsJson(path);
  ASSERT_TRUE(segments.ok()) << segments.status().ToString();
  ASSERT_EQ(segments->size(), 2u);
  EXPECT_EQ((*segments)[0].group, "group 1");
  EXPECT_EQ((*segments)[1].start, 12u);
  EXPECT_EQ((*segments)[1].group, "");
  const std::string motifs = dir.path() + "/motifs.json";
  std::ofstream(motifs) << R"({"version": 1, "motifs": []})";
  Result<std::vector<GroupedSegment>> refused = ReadSegmentsJson(motifs);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find(motifs), std::string::npos);
}

}  // namespace
}  // namespace motif
