// The ground-truth reader (motif_truth.h) and the scorer (truth_score.h) on small cases whose
// figures are worked out by hand.
#include "engine/evaluation/truth_score.h"

#include <gtest/gtest.h>

#include <fstream>

#include "engine/evaluation/motif_truth.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

MotifsDocument Document(const std::vector<std::vector<MotifsJsonInstance>>& motifs) {
  MotifsDocument document;
  document.clips = {{"a", "a.bvh", 1000, 120, 0}, {"b", "b.bvh", 1000, 120, 1000}};
  for (size_t motif_idx = 0; motif_idx < motifs.size(); ++motif_idx) {
    document.motifs.push_back({static_cast<uint32_t>(motif_idx), motifs[motif_idx]});
  }
  return document;
}

TEST(IntervalIoU, CountsFramesOfTheIntersectionOverTheUnion) {
  EXPECT_DOUBLE_EQ(IntervalIoU(0, 100, 0, 100), 1.0);
  EXPECT_DOUBLE_EQ(IntervalIoU(0, 100, 50, 150), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(IntervalIoU(0, 100, 25, 75), 0.5);
  EXPECT_DOUBLE_EQ(IntervalIoU(0, 100, 100, 200), 0.0);
  EXPECT_DOUBLE_EQ(IntervalIoU(0, 0, 0, 10), 0.0);
}

TEST(MotifTruth, ParsesTheAnnotationTsv) {
  Result<std::vector<TruthOccurrence>> truth = ParseTruthTsv(
      "# a comment\nclip\tmovement\tstart\tend\na\tstep\t10\t50\r\n\nb\thop\t0\t7\n", "t.tsv");
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  ASSERT_EQ(truth->size(), 2u);
  EXPECT_EQ((*truth)[0], (TruthOccurrence{"a", "step", 10, 50}));
  EXPECT_EQ((*truth)[1], (TruthOccurrence{"b", "hop", 0, 7}));
}

TEST(MotifTruth, RejectsMalformedLinesNamingTheFileAndLine) {
  const auto message = [](const std::string& text) {
    Result<std::vector<TruthOccurrence>> truth = ParseTruthTsv(text, "t.tsv");
    EXPECT_FALSE(truth.ok());
    EXPECT_EQ(truth.status().code(), Status::Code::kInvalidArgument);
    return truth.status().message();
  };
  EXPECT_NE(message("a\tstep\t1\t2\n").find("t.tsv: line 1: expected the header"),
            std::string::npos);
  EXPECT_NE(message("clip\tmovement\tstart\tend\na\tstep\t1\n").find("line 2: expected 4"),
            std::string::npos);
  EXPECT_NE(message("clip\tmovement\tstart\tend\na\tstep\tx\t2\n").find("frame numbers"),
            std::string::npos);
  EXPECT_NE(message("clip\tmovement\tstart\tend\na\tstep\t-1\t2\n").find("frame numbers"),
            std::string::npos);
  EXPECT_NE(message("clip\tmovement\tstart\tend\na\tstep\t5\t5\n").find("greater than start"),
            std::string::npos);
  EXPECT_NE(message("").find("no header"), std::string::npos);
}

TEST(TruthScore, AHitNeedsTheSameClipAndIoUOfAtLeastHalf) {
  const std::vector<TruthOccurrence> truth = {{"a", "step", 100, 200}};
  // IoU 0.5 exactly: [100, 200) against [100, 150) hits; [100, 149) does not; clip b never.
  EXPECT_EQ(
      ScoreAgainstTruth(Document({{{"a", 100, 150}, {"a", 500, 560}}}), truth).occurrences_hit, 1u);
  EXPECT_EQ(
      ScoreAgainstTruth(Document({{{"a", 100, 149}, {"a", 500, 560}}}), truth).occurrences_hit, 0u);
  EXPECT_EQ(
      ScoreAgainstTruth(Document({{{"b", 100, 200}, {"b", 500, 560}}}), truth).occurrences_hit, 0u);
}

TEST(TruthScore, TheTopMotifIsScoredAgainstTheMovementItMatchesBest) {
  const std::vector<TruthOccurrence> truth = {
      {"a", "step", 0, 100},  {"a", "step", 200, 300}, {"b", "step", 0, 100},
      {"a", "hop", 400, 450}, {"b", "hop", 400, 450},  {"c", "hop", 0, 50},
  };
  // Motif 0: two steps and one miss. Motif 1: both hops of a and b.
  const MotifsDocument document = Document(
      {{{"a", 0, 100}, {"b", 10, 100}, {"b", 600, 700}}, {{"a", 400, 450}, {"b", 405, 450}}});
  const TruthScore score = ScoreAgainstTruth(document, truth);
  EXPECT_EQ(score.occurrences, 5u);
  EXPECT_EQ(score.occurrences_elsewhere, 1u);  // clip c is not in the document
  EXPECT_EQ(score.movements, 2u);
  EXPECT_EQ(score.instances, 5u);
  EXPECT_EQ(score.instances_hitting, 4u);
  EXPECT_EQ(score.occurrences_hit, 4u);
  EXPECT_DOUBLE_EQ(score.precision, 4.0 / 5.0);
  EXPECT_DOUBLE_EQ(score.recall, 4.0 / 5.0);
  EXPECT_EQ(score.top1.motif, 0);
  EXPECT_EQ(score.top1.movement, "step");
  EXPECT_DOUBLE_EQ(score.top1.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(score.top1.recall, 2.0 / 3.0);
  ASSERT_EQ(score.per_movement.size(), 2u);
  EXPECT_EQ(score.per_movement[0].movement, "hop");
  EXPECT_EQ(score.per_movement[0].motif, 1);
  EXPECT_DOUBLE_EQ(score.per_movement[0].precision, 1.0);
  EXPECT_DOUBLE_EQ(score.per_movement[0].recall, 1.0);
  EXPECT_EQ(score.per_movement[1].movement, "step");
  EXPECT_EQ(score.per_movement[1].motif, 0);
}

TEST(TruthScore, NothingFoundScoresZeroAndAMovementWithoutMotifSaysNone) {
  const TruthScore score = ScoreAgainstTruth(Document({}), {{"a", "step", 0, 100}});
  EXPECT_EQ(score.top1.motif, -1);
  EXPECT_DOUBLE_EQ(score.top1.precision, 0.0);
  EXPECT_DOUBLE_EQ(score.top1.recall, 0.0);
  ASSERT_EQ(score.per_movement.size(), 1u);
  EXPECT_EQ(score.per_movement[0].motif, -1);
  EXPECT_EQ(score.per_movement[0].occurrences, 1u);
}

TEST(TruthScore, PlantedMotifsOfATruthJsonBecomeMovements) {
  testing::TempDir dir;
  const std::string path = dir.File("s.truth.json");
  std::ofstream(path) << R"({"version": 1, "archive": "s.mfs", "frames": 2000, "instances": [
      {"clip": "a", "start": 0, "end": 100, "motif": 3},
      {"clip": "a", "start": 300, "end": 420, "motif": 3}]})";
  Result<std::vector<TruthOccurrence>> truth = ReadTruthOccurrences(path);
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  EXPECT_EQ(*truth, (std::vector<TruthOccurrence>{{"a", "planted-3", 0, 100},
                                                  {"a", "planted-3", 300, 420}}));
  const TruthScore score = ScoreAgainstTruth(Document({{{"a", 0, 100}, {"a", 300, 400}}}), *truth);
  EXPECT_EQ(score.top1.movement, "planted-3");
  EXPECT_DOUBLE_EQ(score.top1.precision, 1.0);
  EXPECT_DOUBLE_EQ(score.top1.recall, 1.0);
}

TEST(TruthScore, AMovementIsBackToBackWhenHalfItsOccurrencesEndWhereAnotherStarts) {
  const std::vector<TruthOccurrence> cycles = {
      {"a", "walk", 0, 100}, {"a", "walk", 100, 200}, {"a", "walk", 202, 300}};
  const std::vector<TruthOccurrence> apart = {
      {"a", "jump", 0, 100}, {"a", "jump", 103, 200}, {"b", "jump", 200, 300}};
  const std::vector<TruthOccurrence> one_pair = {{"a", "kick", 0, 100},
                                                 {"a", "kick", 100, 200},
                                                 {"a", "kick", 400, 500},
                                                 {"a", "kick", 700, 800},
                                                 {"a", "kick", 900, 1000}};
  const auto pointers = [](const std::vector<TruthOccurrence>& occurrences) {
    std::vector<const TruthOccurrence*> result;
    for (const TruthOccurrence& occurrence : occurrences) result.push_back(&occurrence);
    return result;
  };
  EXPECT_TRUE(IsBackToBack(pointers(cycles)));     // gaps 0 and 2 frames
  EXPECT_FALSE(IsBackToBack(pointers(apart)));     // a gap of 3; the next in another clip
  EXPECT_FALSE(IsBackToBack(pointers(one_pair)));  // 2 of 5 follow one another
  EXPECT_FALSE(IsBackToBack(pointers({cycles[0]})));
}

TEST(TruthScore, PhaseFreeScoresBackToBackCyclesAtTheBestCommonShift) {
  // Three 100-frame cycles; the motif finds each 37 frames late: IoU 63/137 < 0.5, so the hit
  // rule finds nothing. 33 frames late is the most IoU 0.5 allows (67/133): shifted 4 frames
  // back (the least shift that does it) all three hit.
  const std::vector<TruthOccurrence> truth = {
      {"a", "walk", 100, 200}, {"a", "walk", 200, 300}, {"a", "walk", 300, 400}};
  const MotifsDocument document = Document({{{"a", 137, 237}, {"a", 237, 337}, {"a", 337, 437}}});
  const TruthScore score = ScoreAgainstTruth(document, truth);
  EXPECT_DOUBLE_EQ(score.top1.precision, 0.0);
  EXPECT_EQ(score.top1_phase_free.movement, "walk");
  EXPECT_TRUE(score.top1_phase_free.back_to_back);
  EXPECT_DOUBLE_EQ(score.top1_phase_free.precision, 1.0);
  EXPECT_DOUBLE_EQ(score.top1_phase_free.recall, 1.0);
  EXPECT_EQ(score.top1_phase_free.shift, -4);
}

TEST(TruthScore, PhaseFreeShiftsAtMostHalfACycleAndNeverMovesApartMovements) {
  // Cycles of 100 frames: a motif past them would need a shift of 137 frames or more.
  const std::vector<TruthOccurrence> cycles = {{"a", "walk", 100, 200}, {"a", "walk", 200, 300}};
  const TruthScore late = ScoreAgainstTruth(Document({{{"a", 370, 470}, {"a", 470, 570}}}), cycles);
  EXPECT_TRUE(late.top1_phase_free.back_to_back);
  EXPECT_DOUBLE_EQ(late.top1_phase_free.precision, 0.0);
  EXPECT_EQ(late.top1_phase_free.shift, 0);
  // Jumps apart: no shift is tried, the phase-free match is the plain one.
  const std::vector<TruthOccurrence> jumps = {{"a", "jump", 100, 200}, {"a", "jump", 400, 500}};
  const TruthScore shifted =
      ScoreAgainstTruth(Document({{{"a", 140, 240}, {"a", 440, 540}}}), jumps);
  EXPECT_FALSE(shifted.top1_phase_free.back_to_back);
  EXPECT_EQ(shifted.top1_phase_free.shift, 0);
  EXPECT_DOUBLE_EQ(shifted.top1_phase_free.precision, 0.0);
  EXPECT_DOUBLE_EQ(shifted.top1.precision, 0.0);
}

}  // namespace
}  // namespace motif
