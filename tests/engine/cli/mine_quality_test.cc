// What `motifmine mine` finds with its defaults on real takes where a person repeats a movement,
// scored with `motifmine score` against the labelled occurrences of tests/data/repetitions
// (docs/design/motif_quality.md), and the stability of the motifs when a take is added.
// Skipped with a message when the real takes are absent.

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunTool;

nlohmann::json ScoreJson(const std::string& motifs, const std::string& truth) {
  RunResult score = RunTool("score " + motifs + " " + truth + " --json");
  EXPECT_EQ(score.exit_code, 0) << score.output;
  return nlohmann::json::parse(score.output, nullptr, /*allow_exceptions=*/false);
}

// Two takes mined alone with the defaults: 08_01 (two gait cycles: the top motif is exactly
// them) and 90_30 (four squat-bounce cycles, ASF/AMC: the top motif is three of them, nothing
// else).
TEST(MineQuality, TheTopMotifOfASingleTakeIsItsRepeatedCycle) {
  MOTIF_REQUIRE_MOCAP_DATA();
  testing::TempDir dir;
  struct Take {
    std::string clip;
    std::string file;
    double least_recall;
  };
  for (const Take& take :
       {Take{"08_01", "bvh/08_01.bvh", 1.0}, Take{"90_30", "asfamc/90/90_30.amc", 0.75}}) {
    const std::string out = dir.File(take.clip);
    RunResult mined = RunTool("mine " + testing::MocapDir() + "/" + take.file + " --out " + out +
                              " --quiet --no-report");
    ASSERT_EQ(mined.exit_code, 0) << mined.output;
    EXPECT_NE(mined.output.find("joint-angle rule: 12 degrees"), std::string::npos) << mined.output;
    const std::string truth = std::string(MOTIF_REPETITIONS_DIR) + "/" + take.clip + ".tsv";
    const nlohmann::json score = ScoreJson(out + "/motifs.json", truth);
    ASSERT_TRUE(score.is_object()) << take.clip;
    EXPECT_DOUBLE_EQ(score["top1"]["precision"].get<double>(), 1.0) << take.clip << score.dump();
    EXPECT_GE(score["top1"]["recall"].get<double>(), take.least_recall)
        << take.clip << score.dump();
  }
}

// A folder mined, then mined again with one more take: the radius does not move, and every
// motif of the first run has a motif in the second hitting all its instances.
TEST(MineQuality, AddingATakeKeepsEveryMotif) {
  MOTIF_REQUIRE_MOCAP_DATA();
  testing::TempDir dir;
  const std::string bvh = testing::MocapDir() + "/bvh/";
  const std::string takes =
      bvh + "06_08.bvh " + bvh + "08_01.bvh " + bvh + "02_05.bvh " + bvh + "09_12.bvh";
  RunResult before = RunTool("mine " + takes + " --out " + dir.File("a") + " --quiet --no-report");
  ASSERT_EQ(before.exit_code, 0) << before.output;
  RunResult after = RunTool("mine " + takes + " " + bvh + "05_03.bvh --out " + dir.File("b") +
                            " --quiet --no-report");
  ASSERT_EQ(after.exit_code, 0) << after.output;
  EXPECT_NE(before.output.find("eps 1.256"), std::string::npos) << before.output;
  EXPECT_NE(after.output.find("eps 1.256"), std::string::npos) << after.output;
  const nlohmann::json score =
      ScoreJson(dir.File("b") + "/motifs.json", dir.File("a") + "/motifs.json");
  ASSERT_TRUE(score.is_object());
  ASSERT_GE(score["per_movement"].size(), 2u) << "the first run found too little to compare";
  for (const nlohmann::json& motif : score["per_movement"]) {
    EXPECT_GE(motif["motif"].get<int64_t>(), 0) << motif.dump();
    EXPECT_DOUBLE_EQ(motif["recall"].get<double>(), 1.0) << motif.dump();
  }
}

TEST(MotifmineScore, RefusesMissingArgumentsAndMalformedTruthNamingTheLine) {
  testing::TempDir dir;
  EXPECT_EQ(RunTool("score").exit_code, 2);
  const std::string truth = dir.File("t.tsv");
  ASSERT_EQ(
      testing::RunShell("printf 'clip\\tmovement\\tstart\\tend\\na\\tstep\\t9\\t3\\n' > " + truth)
          .exit_code,
      0);
  // A motifs.json is needed first: the smallest synthetic mine.
  RunResult mined = RunTool("mine --out " + dir.File("m") +
                            " --synth-frames 13000 --synth-motifs 3 --seed 4 --quiet --no-report");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  RunResult bad = RunTool("score " + dir.File("m") + "/motifs.json " + truth);
  EXPECT_EQ(bad.exit_code, 13) << bad.output;
  EXPECT_NE(bad.output.find("t.tsv: line 2: end must be greater than start"), std::string::npos)
      << bad.output;
  // The synthetic truth scores as planted-m movements.
  const nlohmann::json planted =
      ScoreJson(dir.File("m") + "/motifs.json", dir.File("m") + "/archive.truth.json");
  ASSERT_TRUE(planted.is_object());
  EXPECT_EQ(planted["movements"], 3);
  EXPECT_EQ(planted["top1"]["movement"].get<std::string>().rfind("planted-", 0), 0u);
  // Planted instances lie apart: the phase-free figures are the plain ones.
  EXPECT_EQ(planted["top1_phase_free"]["back_to_back"], false);
  EXPECT_EQ(planted["top1_phase_free"]["shift"], 0);
  EXPECT_EQ(planted["top1_phase_free"]["precision"], planted["top1"]["precision"]);
}

}  // namespace
}  // namespace motif
