// End-to-end test of `motifmine cluster`: synthesise a small archive with planted motifs, build
// its trellis, grow its paths and cluster them, as a user would, with the built binary.

#include <cstdio>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "engine/cluster/motifs_json.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

TEST(MotifmineCluster, FindsThePlantedMotifsAndWritesMotifsJson) {
  testing::TempDir dir;
  const std::string archive = dir.File("c.mfs");
  RunResult help = RunTool("cluster --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("usage: motifmine cluster"), std::string::npos);
  ASSERT_EQ(RunTool("synth " + archive + " --frames 8000 --motifs 2 --seed 5 " +
                    "--motif-seconds-max 1.5 --clip-seconds-min 10 --clip-seconds-max 20 --quiet")
                .exit_code,
            0);
  ASSERT_EQ(RunTool("trellis " + archive + " --exact --kmax 64 --quiet").exit_code, 0);
  EXPECT_EQ(RunTool("cluster " + archive + " --out " + dir.File("out")).exit_code, 11)
      << "no paths file yet";
  ASSERT_EQ(RunTool("grow " + archive + " --quiet").exit_code, 0);
  EXPECT_EQ(RunTool("cluster " + archive).exit_code, 2);  // --out is required
  EXPECT_EQ(RunTool("cluster " + archive + " --out x --groups none").exit_code, 2);

  RunResult cluster = RunTool("cluster " + archive + " --out " + dir.File("out") + " --truth " +
                              dir.File("c.truth.json") + " --quiet");
  ASSERT_EQ(cluster.exit_code, 0) << cluster.output;
  EXPECT_NE(cluster.output.find("wrote " + dir.File("out") + "/motifs.json"), std::string::npos)
      << cluster.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(cluster.output, match, std::regex("recall +([0-9.]+)")))
      << cluster.output;
  EXPECT_GE(std::stod(match[1]), 0.9) << cluster.output;
  ASSERT_TRUE(std::regex_search(cluster.output, match, std::regex("ARI +([-0-9.]+)")));
  EXPECT_GE(std::stod(match[1]), 0.9) << cluster.output;

  auto motifs = ReadMotifsJson(dir.File("out") + "/motifs.json");
  ASSERT_TRUE(motifs.ok()) << motifs.status().ToString();
  EXPECT_EQ(motifs->archive, archive);
  EXPECT_EQ(motifs->frames, 8000u);
  EXPECT_EQ(motifs->params.groups, 0u);
  EXPECT_EQ(motifs->params.min_length, 60u);
  ASSERT_FALSE(motifs->motifs.empty());
  for (const MotifsJsonMotif& motif : motifs->motifs) EXPECT_GE(motif.instances.size(), 2u);

  // A given G is honoured and recorded.
  RunResult given =
      RunTool("cluster " + archive + " --out " + dir.File("out2") + " --groups 3 --quiet");
  ASSERT_EQ(given.exit_code, 0) << given.output;
  auto three = ReadMotifsJson(dir.File("out2") + "/motifs.json");
  ASSERT_TRUE(three.ok());
  EXPECT_EQ(three->params.groups, 3u);
}

}  // namespace
}  // namespace motif
