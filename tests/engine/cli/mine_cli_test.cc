// End-to-end test of `motifmine mine`, the main job, with the built binary: the built-in
// synthetic archive mined with planted-motif scores, every output written, a second run reusing
// every stage, a changed parameter rerunning only what follows it, and bad parameters refused.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "common/file_lock.h"
#include "common/file_util.h"
#include "engine/cluster/instances_csv.h"
#include "engine/cluster/motifs_json.h"
#include "tests/testing/csv_rows.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

double Figure(const std::string& output, const std::string& name) {
  std::smatch match;
  if (!std::regex_search(output, match, std::regex("  " + name + " +([0-9.]+)"))) return -1;
  return std::stod(match[1]);
}

// Whether the summary's time line says `stage` was reused ("synth 0.2s (reused)"). The time is
// not matched: a loaded machine or a sanitizer build takes more than 0.0 s even to reuse.
bool StageReused(const std::string& output, const std::string& stage) {
  return std::regex_search(output, std::regex("[ ,]" + stage + " [0-9.]+s \\(reused\\)"));
}

// OUT/instances.csv holds motifs.json's instances, row for row in its order: the clip and file
// frames, the seconds in the file, the distance to the representative and the rank by it.
void ExpectCsvRowsAreTheInstances(const std::string& csv_path, const MotifsDocument& document) {
  const auto rows = testing::ParseCsvRows(ReadFileToString(csv_path).value());
  ASSERT_FALSE(rows.empty()) << csv_path;
  EXPECT_EQ(rows[0], (std::vector<std::string>{"motif", "rank", "clip", "source", "start", "end",
                                               "file_first_frame", "file_last_frame",
                                               "start_seconds", "end_seconds", "distance"}));
  size_t row_idx = 1;
  for (const MotifsJsonMotif& motif : document.motifs) {
    ASSERT_TRUE(motif.representative.has_value()) << "motif " << motif.id;
    EXPECT_EQ(motif.instances[*motif.representative].distance, std::optional<double>(0.0));
    const std::vector<uint32_t> ranks = InstanceRanks(motif);
    for (size_t inst = 0; inst < motif.instances.size(); ++inst, ++row_idx) {
      ASSERT_LT(row_idx, rows.size());
      const std::vector<std::string>& row = rows[row_idx];
      ASSERT_EQ(row.size(), 11u) << row_idx;
      const MotifsJsonInstance& instance = motif.instances[inst];
      const MotifsJsonClip& clip =
          *std::find_if(document.clips.begin(), document.clips.end(),
                        [&](const MotifsJsonClip& listed) { return listed.name == instance.clip; });
      EXPECT_EQ(row[0], std::to_string(motif.id));
      EXPECT_EQ(row[1], std::to_string(ranks[inst]));
      EXPECT_EQ(row[2], instance.clip);
      EXPECT_EQ(row[3], clip.source);
      EXPECT_EQ(row[4], std::to_string(instance.start));
      EXPECT_EQ(row[5], std::to_string(instance.end));
      EXPECT_EQ(row[6], std::to_string(FileFrameOf(clip, instance.start)));
      EXPECT_EQ(row[7], std::to_string(FileFrameOf(clip, instance.end - 1)));
      EXPECT_NEAR(std::stod(row[8]), static_cast<double>(instance.start) / clip.fps, 1e-6);
      EXPECT_NEAR(std::stod(row[9]), static_cast<double>(instance.end) / clip.fps, 1e-6);
      ASSERT_TRUE(instance.distance.has_value());
      EXPECT_EQ(std::stod(row[10]), *instance.distance);  // the same double
    }
  }
  EXPECT_EQ(row_idx, rows.size());
}

TEST(MotifmineMine, SyntheticArchiveEndToEndThenReuse) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  const std::string small = "--synth-frames 14000 --synth-motifs 3 --seed 4 --kmax 64 ";
  RunResult first = RunTool("mine --out " + out + " " + small + "--progress json");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  for (const char* name : {"archive.mfs", "archive.truth.json", "trellis.mtr", "paths.mpa",
                           "motifs.json", "instances.csv", "report.html"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + name)) << name;
  }
  // One progress stream across the stages.
  for (const char* stage : {"synth", "trellis", "grow", "cluster"}) {
    EXPECT_NE(first.output.find(std::string("\"stage\":\"") + stage + "\""), std::string::npos)
        << stage << "\n"
        << first.output;
  }
  // The summary scores the planted motifs; every planted instance of this small archive is found.
  EXPECT_EQ(Figure(first.output, "recall"), 1.0) << first.output;
  EXPECT_GT(Figure(first.output, "precision"), 0.0) << first.output;
  EXPECT_NE(first.output.find("peak resident"), std::string::npos);
  EXPECT_NE(first.output.find("14,000 frames (1.9 min at 120 fps)"), std::string::npos);
  auto document = ReadMotifsJson(out + "/motifs.json");
  ASSERT_TRUE(document.ok()) << document.status().ToString();
  EXPECT_EQ(document->frames, 14000u);
  EXPECT_EQ(document->params.kmax, 64u);
  EXPECT_FALSE(document->motifs.empty());
  ExpectCsvRowsAreTheInstances(out + "/instances.csv", *document);
  const std::string instances_csv = ReadFileToString(out + "/instances.csv").value();

  // `report` run again shows the overview mine's report showed: timings, peak memory, the
  // planted motifs (from OUT/run.json, which names this motifs.json).
  const std::string mine_report = ReadFileToString(out + "/report.html").value();
  ASSERT_EQ(RunTool("report " + out + " --out " + out + "/again.html").exit_code, 0);
  const std::string again_report = ReadFileToString(out + "/again.html").value();
  for (const char* shown : {"peak memory", "timings", "recall"}) {
    EXPECT_NE(mine_report.find(shown), std::string::npos) << shown;
  }
  EXPECT_EQ(again_report, mine_report) << "report run again differs from mine's";

  // The same again: every stage is reused and the motifs are the same.
  RunResult second = RunTool("mine --out " + out + " " + small + "--quiet");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(StageReused(second.output, "synth")) << second.output;
  EXPECT_NE(second.output.find("(reused), grow"), std::string::npos) << second.output;
  EXPECT_TRUE(StageReused(second.output, "cluster")) << second.output;
  auto again = ReadMotifsJson(out + "/motifs.json");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *document);
  EXPECT_EQ(ReadFileToString(out + "/instances.csv").value(), instances_csv);

  // Another branch factor: the trellis is reused, the paths and the motifs are not.
  RunResult branch = RunTool("mine --out " + out + " " + small + "--branch 3 --quiet");
  ASSERT_EQ(branch.exit_code, 0) << branch.output;
  EXPECT_NE(branch.output.find("(reused), grow"), std::string::npos) << branch.output;
  EXPECT_FALSE(StageReused(branch.output, "cluster")) << branch.output;
  auto changed = ReadMotifsJson(out + "/motifs.json");
  ASSERT_TRUE(changed.ok());
  EXPECT_EQ(changed->params.branch, 3u);
  ExpectCsvRowsAreTheInstances(out + "/instances.csv", *changed);

  // A motifs.json changed since: its run record is stale, said so, and not shown.
  std::string motifs = ReadFileToString(out + "/motifs.json").value();
  ASSERT_TRUE(AtomicWriteFile(out + "/motifs.json", motifs + " ").ok());
  const RunResult stale = RunTool("report " + out + " --out " + out + "/stale.html");
  ASSERT_EQ(stale.exit_code, 0) << stale.output;
  EXPECT_NE(stale.output.find("run.json not used"), std::string::npos) << stale.output;
  EXPECT_EQ(ReadFileToString(out + "/stale.html").value().find("peak memory"), std::string::npos);
}

TEST(MotifmineMine, RefusesBadParametersBeforeAnyWork) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  // Usage errors (exit 2) naming the flag: the option table's values.
  RunResult groups = RunTool("mine --out " + out + " --groups many --quiet");
  EXPECT_EQ(groups.exit_code, 2) << groups.output;
  EXPECT_NE(groups.output.find("--groups must be auto or a number of motifs >= 1, not 'many'"),
            std::string::npos)
      << groups.output;
  RunResult length = RunTool("mine --out " + out + " --min-length 0.5 --quiet");
  EXPECT_EQ(length.exit_code, 2) << length.output;
  EXPECT_NE(length.output.find("--min-length must be a number of frames (60) or of seconds"),
            std::string::npos)
      << length.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/archive.mfs"));
  RunResult no_out = RunTool("mine --quiet");
  EXPECT_EQ(no_out.exit_code, 2) << no_out.output;
  RunResult missing = RunTool("mine " + dir.File("nothing.bvh") + " --out " + out + " --quiet");
  EXPECT_NE(missing.exit_code, 0) << missing.output;
  EXPECT_NE(missing.output.find("nothing.bvh"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace motif
