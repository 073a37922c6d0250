// End-to-end test of `motifmine grow`: synthesise a small archive, build its trellis, grow it,
// as a user would, with the built binary.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "formats/paths_file/paths_file_reader.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

TEST(MotifmineGrow, SynthTrellisGrowThenReuse) {
  testing::TempDir dir;
  const std::string archive = dir.File("g.mfs");
  RunResult synth = RunTool("synth " + archive +
                            " --frames 6000 --motifs 2 --seed 5 --motif-seconds-max 1.5 "
                            "--clip-seconds-min 10 --clip-seconds-max 20 --quiet");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  RunResult no_trellis = RunTool("grow " + archive + " --quiet");
  EXPECT_EQ(no_trellis.exit_code, 11) << no_trellis.output;  // not found, naming the trellis
  EXPECT_NE(no_trellis.output.find("g.mtr"), std::string::npos) << no_trellis.output;
  RunResult trellis = RunTool("trellis " + archive + " --exact --kmax 64 --quiet");
  ASSERT_EQ(trellis.exit_code, 0) << trellis.output;

  RunResult grow = RunTool("grow " + archive + " --progress json");
  ASSERT_EQ(grow.exit_code, 0) << grow.output;
  EXPECT_NE(grow.output.find("wrote " + dir.File("g.mpa")), std::string::npos) << grow.output;
  EXPECT_NE(grow.output.find("\"stage\":\"grow\""), std::string::npos) << grow.output;
  EXPECT_NE(grow.output.find("peak resident"), std::string::npos) << grow.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      grow.output, match,
      std::regex("candidates +([0-9,]+) paths of at least 60 frames on both sides \\(the "
                 "longest of each tree\\)")))
      << grow.output;
  std::string printed = match[1];
  printed.erase(std::remove(printed.begin(), printed.end(), ','), printed.end());
  auto paths = PathsFileReader::Open(dir.File("g.mpa"));
  ASSERT_TRUE(paths.ok()) << paths.status().ToString();
  EXPECT_EQ(std::to_string((*paths)->candidates().size()), printed);
  EXPECT_GT((*paths)->candidates().size(), 0u);
  EXPECT_EQ((*paths)->params().branch, 5u);

  RunResult again = RunTool("grow " + archive + " --quiet");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("up to date"), std::string::npos) << again.output;

  // Lambda in frames or seconds, another branch factor, another output.
  RunResult frames = RunTool("grow " + archive + " --min-length 30 --branch 3 --out " +
                             dir.File("b3.mpa") + " --quiet");
  ASSERT_EQ(frames.exit_code, 0) << frames.output;
  RunResult seconds = RunTool("grow " + archive + " --min-length 0.25s --branch 3 --out " +
                              dir.File("b3.mpa") + " --quiet");
  ASSERT_EQ(seconds.exit_code, 0) << seconds.output;
  EXPECT_NE(seconds.output.find("up to date"), std::string::npos)  // 0.25 s = 30 frames
      << seconds.output;
  auto b3 = PathsFileReader::Open(dir.File("b3.mpa"));
  ASSERT_TRUE(b3.ok());
  EXPECT_EQ((*b3)->params().min_length, 30u);
  EXPECT_GT((*b3)->candidates().size(), 0u);
  RunResult all =
      RunTool("grow " + archive + " --all-branches --out " + dir.File("all.mpa") + " --quiet");
  ASSERT_EQ(all.exit_code, 0) << all.output;
  EXPECT_NE(all.output.find("(every branch)"), std::string::npos) << all.output;
  auto all_paths = PathsFileReader::Open(dir.File("all.mpa"));
  ASSERT_TRUE(all_paths.ok());
  EXPECT_TRUE((*all_paths)->params().all_branches);
  EXPECT_GT((*all_paths)->candidates().size(), (*paths)->candidates().size());

  // Impossible values are usage errors naming the flag (the option table's ranges).
  EXPECT_EQ(RunTool("grow " + archive + " --min-length abc").exit_code, 2);
  EXPECT_EQ(RunTool("grow " + archive + " --min-length 2.5").exit_code, 2);
  const RunResult branch = RunTool("grow " + archive + " --branch 0 --quiet");
  EXPECT_EQ(branch.exit_code, 2);
  EXPECT_NE(branch.output.find("--branch must be a whole number in [1, 1000], not '0'"),
            std::string::npos)
      << branch.output;
  EXPECT_EQ(RunTool("grow").exit_code, 2);
  RunResult help = RunTool("grow --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("usage: motifmine grow"), std::string::npos);
}

}  // namespace
}  // namespace motif
