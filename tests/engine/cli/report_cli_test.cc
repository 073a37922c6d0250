// End-to-end tests of `motifmine export-motif` and `motifmine report` with the built binary, on
// a small synthetic archive whose planted instances are written as the mined motifs.

#include <cstdio>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/cluster/motifs_json.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/import/bvh_parser.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

class ReportCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    archive_ = dir_.File("s.mfs");
    ASSERT_EQ(RunTool("synth " + archive_ + " --frames 6000 --motifs 2 --seed 5 " +
                      "--motif-seconds-max 1.5 --clip-seconds-min 10 --clip-seconds-max 20 --quiet")
                  .exit_code,
              0);
    auto truth = ReadTruthJson(dir_.File("s.truth.json"));
    ASSERT_TRUE(truth.ok()) << truth.status().ToString();
    auto reader = FrameFileReader::Open(archive_);
    ASSERT_TRUE(reader.ok());
    document_.archive = archive_;
    document_.frames = (*reader)->frame_count();
    std::map<std::string, uint64_t> first_frames;
    for (const ClipInfo& clip : (*reader)->clips()) {
      document_.clips.push_back(
          {clip.name, clip.source_path, clip.frame_count, clip.fps, clip.first_frame});
      first_frames[clip.name] = clip.first_frame;
    }
    document_.params = {1.0, 64, 4, 60, 0, 1};
    std::map<uint32_t, std::vector<MotifsJsonInstance>> by_motif;
    for (const PlantedInstance& planted : truth->instances) {
      by_motif[planted.motif].push_back(
          {planted.clip, planted.start, planted.end, first_frames[planted.clip] + planted.start});
    }
    for (auto& [motif_id, instances] : by_motif) document_.motifs.push_back({motif_id, instances});
    std::filesystem::create_directories(dir_.File("out"));
    ASSERT_TRUE(WriteMotifsJson(dir_.File("out/motifs.json"), document_).ok());
  }

  testing::TempDir dir_;
  std::string archive_;
  MotifsDocument document_;
};

TEST_F(ReportCliTest, ExportMotifWritesOneBvhPerInstance) {
  RunResult help = RunTool("export-motif --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("usage: motifmine export-motif"), std::string::npos);

  const MotifsJsonMotif& motif = document_.motifs[1];
  const std::string folder = dir_.File("bvh");
  RunResult run = RunTool("export-motif " + dir_.File("out") + " --motif " +
                          std::to_string(motif.id) + " --out " + folder);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, motif.instances.size());
  for (size_t idx = 0; idx < motif.instances.size(); ++idx) {
    const MotifsJsonInstance& instance = motif.instances[idx];
    const std::string name = "motif" + std::to_string(motif.id) + "_" + std::to_string(idx) + "_" +
                             instance.clip + "_" + std::to_string(instance.start) + "-" +
                             std::to_string(instance.end) + ".bvh";
    auto text = ReadFileToString(folder + "/" + name);
    ASSERT_TRUE(text.ok()) << name << "\n" << run.output;
    auto take = ParseBvh(*text, name);
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    EXPECT_EQ(take->frame_count(), instance.length()) << name;
    EXPECT_EQ(take->skeleton.joint_count(), 31u);
  }
}

TEST_F(ReportCliTest, ExportMotifErrorsAreClear) {
  const std::string out = dir_.File("out");
  EXPECT_EQ(RunTool("export-motif " + out + " --motif 0").exit_code, 2) << "--out is required";
  RunResult missing = RunTool("export-motif " + dir_.File("nowhere") + " --motif 0 --out x");
  EXPECT_EQ(missing.exit_code, 11);
  EXPECT_NE(missing.output.find("motifs.json does not exist"), std::string::npos) << missing.output;
  RunResult unknown = RunTool("export-motif " + out + " --motif 99 --out " + dir_.File("x"));
  EXPECT_EQ(unknown.exit_code, 11);
  EXPECT_NE(unknown.output.find("no motif 99"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("motifs are 0 to 1"), std::string::npos) << unknown.output;

  // The archive has moved: its path in motifs.json is gone, --archive finds it.
  std::filesystem::rename(archive_, dir_.File("moved.mfs"));
  RunResult moved = RunTool("export-motif " + out + " --motif 0 --out " + dir_.File("x"));
  EXPECT_EQ(moved.exit_code, 11);
  EXPECT_NE(moved.output.find("--archive"), std::string::npos) << moved.output;
  EXPECT_EQ(RunTool("export-motif " + out + " --motif 0 --out " + dir_.File("x") + " --archive " +
                    dir_.File("moved.mfs"))
                .exit_code,
            0);

  // Motifs mined from another archive (another frame count) are refused.
  MotifsDocument other = document_;
  other.frames += 10;
  other.clips.back().frames += 10;
  std::filesystem::create_directories(dir_.File("other"));
  ASSERT_TRUE(WriteMotifsJson(dir_.File("other/motifs.json"), other).ok());
  RunResult mismatch = RunTool("export-motif " + dir_.File("other") + " --motif 0 --out " +
                               dir_.File("y") + " --archive " + dir_.File("moved.mfs"));
  EXPECT_EQ(mismatch.exit_code, 13);
  EXPECT_NE(mismatch.output.find("another archive"), std::string::npos) << mismatch.output;
}

TEST_F(ReportCliTest, ReportWritesTheHtmlFile) {
  RunResult run = RunTool("report " + dir_.File("out") + " --truth " + dir_.File("s.truth.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto html = ReadFileToString(dir_.File("out/report.html"));
  ASSERT_TRUE(html.ok()) << run.output;
  size_t rects = 0;
  for (size_t at = html->find("<rect"); at != std::string::npos; at = html->find("<rect", at + 1)) {
    ++rects;
  }
  size_t instances = 0;
  for (const MotifsJsonMotif& motif : document_.motifs) instances += motif.instances.size();
  EXPECT_EQ(rects, instances);
  EXPECT_NE(html->find("recall 1.000"), std::string::npos);
  EXPECT_EQ(RunTool("report " + dir_.File("out") + " --view top").exit_code, 13);
  EXPECT_EQ(
      RunTool("report " + dir_.File("out") + " --out " + dir_.File("front.html") + " --view front")
          .exit_code,
      0);
  EXPECT_TRUE(std::filesystem::exists(dir_.File("front.html")));
}

}  // namespace
}  // namespace motif
