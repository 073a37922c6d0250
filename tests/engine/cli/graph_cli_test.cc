// End-to-end tests of `motifmine graph` with the built binary: on an archive of periodic motion
// (three classes of swinging clips, so that the graph has cycles), the walk, its pieces and the
// graph it writes, with and without the signature constraint, and clear errors on bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/byte_files.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

nlohmann::json ReadJson(const std::string& path) {
  auto text = ReadFileToString(path);
  EXPECT_TRUE(text.ok()) << path;
  return text.ok() ? nlohmann::json::parse(*text) : nlohmann::json();
}

class GraphCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    archive_ = dir_->File("classes.mfs");
    const ClassClips classes = MakeClassClips(3, 3, 8.0, 17);
    WriteClips(archive_, classes.skeleton, classes.clips, 120.0);
    ASSERT_EQ(
        RunTool("words " + archive_ + " --epochs 2 --channels 16 --dims 8 --motifs 12 " + "--quiet")
            .exit_code,
        0);
  }
  static void TearDownTestSuite() { delete dir_; }
  static TempDir* dir_;
  static std::string archive_;
};
TempDir* GraphCliTest::dir_ = nullptr;
std::string GraphCliTest::archive_;

TEST_F(GraphCliTest, GraphWritesTheWalkItsPiecesAndTheGraph) {
  for (const char* mode : {"", " --unconstrained"}) {
    const std::string out = dir_->File(std::string("graph") + (*mode ? "-free" : ""));
    RunResult run = RunTool("graph " + archive_ + " --start class0_0 --seconds 10 --out " + out +
                            mode + " --seed 3");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const nlohmann::json walk = ReadJson(out + "/walk.json");
    EXPECT_EQ(walk["frames"], 1200);
    EXPECT_EQ(walk["start"], "class0_0");
    EXPECT_EQ(walk["constrained"], *mode == 0);
    ASSERT_FALSE(walk["pieces"].empty());
    EXPECT_EQ(walk["pieces"][0]["clip"], "class0_0");
    uint64_t frames = 0;
    for (const nlohmann::json& piece : walk["pieces"]) {
      frames += piece["end"].get<uint64_t>() - piece["start"].get<uint64_t>();
    }
    EXPECT_EQ(frames - 30 * (walk["pieces"].size() - 1), 1200u);
    const std::string bvh = ReadBytes(out + "/walk.bvh");
    EXPECT_NE(bvh.find("Frames: 1200\n"), std::string::npos);
    const nlohmann::json graph = ReadJson(out + "/graph.json");
    uint64_t kept = 0;
    for (const nlohmann::json& t : graph["transitions"]) kept += t["fate"] == "kept";
    EXPECT_EQ(graph["counts"]["kept"].get<uint64_t>(), kept);
    EXPECT_EQ(graph["counts"]["transitions"].get<uint64_t>(), graph["transitions"].size());
    EXPECT_EQ(graph["constrained"], *mode == 0);
    EXPECT_GT(kept, 0u);
  }
  // A trellis the user built with other options is used as it is, not replaced.
  ASSERT_EQ(RunTool("trellis " + archive_ + " --eps 0.9 --quiet").exit_code, 0);
  const std::string trellis = archive_.substr(0, archive_.size() - 4) + ".mtr";
  const std::string before = ReadBytes(trellis);
  RunResult own =
      RunTool("graph " + archive_ + " --start class0_0 --seconds 5 --unconstrained --out " +
              dir_->File("graph-own"));
  ASSERT_EQ(own.exit_code, 0) << own.output;
  EXPECT_EQ(ReadBytes(trellis), before);
  auto expect = [&](const std::string& args, int code, const std::string& text) {
    RunResult result = RunTool("graph " + archive_ + " --out " + dir_->File("graph-bad") + args);
    EXPECT_EQ(result.exit_code, code) << args << "\n" << result.output;
    EXPECT_NE(result.output.find(text), std::string::npos) << args << "\n" << result.output;
    EXPECT_FALSE(FileExists(dir_->File("graph-bad/walk.json"))) << args;
  };
  expect(" --start nope --seconds 5", 11, "no clip named 'nope'");
  expect(" --start class0_0 --seconds 0", 2, "--seconds");
  expect(" --start class0_0 --seconds 5 --window 0", 2, "--window");
  expect(" --seconds 5", 2, "start");
}

// A folder `mine` wrote stands for its archive (graph, info, export), and graph walks on the
// trellis mine left there instead of building a second one beside the archive.
TEST_F(GraphCliTest, AMinedFolderStandsForItsArchiveAndGraphUsesItsTrellis) {
  const std::string mined = dir_->File("mined");
  ASSERT_EQ(RunTool("mine " + archive_ + " --out " + mined + " --quiet").exit_code, 0);
  ASSERT_TRUE(FileExists(mined + "/trellis.mtr"));
  const std::string trellis_bytes = ReadBytes(mined + "/trellis.mtr");
  const std::string beside = archive_.substr(0, archive_.size() - 4) + ".mtr";
  std::remove(beside.c_str());
  RunResult run = RunTool("graph " + mined + " --start class0_0 --seconds 5 --out " +
                          dir_->File("graph-mined") + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(ReadJson(dir_->File("graph-mined/graph.json"))["trellis"], mined + "/trellis.mtr");
  EXPECT_FALSE(FileExists(beside)) << "graph built a second trellis";
  EXPECT_EQ(ReadBytes(mined + "/trellis.mtr"), trellis_bytes);
  const RunResult info = RunTool("info " + mined + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_EQ(nlohmann::json::parse(info.output)["archive"], archive_);
  EXPECT_EQ(RunTool("export " + mined + " --clip class0_0 --out " + dir_->File("c.bvh")).exit_code,
            0);
}

}  // namespace
}  // namespace motif::testing
