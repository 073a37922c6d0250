// motifmine::Mine, the library's whole job: the same motifs as `motifmine mine` on the same input,
// its defaults those of the tool, and a failing call's Status with the tool's code and message.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "motifmine/motifmine.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace {

using motif::testing::RunTool;

// (clip, start, end) of every instance of every motif, in rank order, from a motifs.json.
std::vector<std::vector<std::tuple<std::string, uint64_t, uint64_t>>> MotifsOf(
    const std::string& motifs_json) {
  const nlohmann::json json = nlohmann::json::parse(motif::ReadFileToString(motifs_json).value());
  std::vector<std::vector<std::tuple<std::string, uint64_t, uint64_t>>> motifs;
  for (const nlohmann::json& motif : json["motifs"]) {
    motifs.emplace_back();
    for (const nlohmann::json& instance : motif["instances"]) {
      motifs.back().emplace_back(instance["clip"], instance["start"], instance["end"]);
    }
  }
  return motifs;
}

TEST(PublicApi, MineFindsTheToolsMotifsOnTheSyntheticArchive) {
  motif::testing::TempDir dir;
  ASSERT_EQ(RunTool("mine --out " + dir.File("cli") +
                    " --synth-frames 20000 --synth-motifs 3 "
                    "--quiet --no-report")
                .exit_code,
            0);

  motifmine::MineOptions options;
  options.out_dir = dir.File("api");
  options.synth_frames = 20000;
  options.synth_motifs = 3;
  options.write_report = false;
  std::vector<std::string> stages;
  options.progress = [&](const std::string& stage, uint64_t, uint64_t) {
    if (stages.empty() || stages.back() != stage) stages.push_back(stage);
  };
  motifmine::MineResult result;
  const motifmine::Status status = motifmine::Mine({}, options, &result);
  ASSERT_TRUE(status.ok()) << status.ToString();

  const auto expected = MotifsOf(dir.File("cli/motifs.json"));
  ASSERT_EQ(result.motifs.size(), expected.size());
  ASSERT_GE(result.motifs.size(), 3u);
  for (size_t m = 0; m < expected.size(); ++m) {
    EXPECT_EQ(result.motifs[m].id, m);
    ASSERT_EQ(result.motifs[m].instances.size(), expected[m].size()) << "motif " << m;
    for (size_t i = 0; i < expected[m].size(); ++i) {
      const motifmine::Instance& instance = result.motifs[m].instances[i];
      EXPECT_EQ(std::make_tuple(instance.clip, instance.start, instance.end), expected[m][i]);
    }
  }
  EXPECT_EQ(MotifsOf(result.motifs_path), expected);
  EXPECT_EQ(result.archive_path, dir.File("api") + "/archive.mfs");
  EXPECT_FALSE(result.clips.empty());
  EXPECT_EQ(result.parameters.k_max, 256u);
  EXPECT_EQ(result.parameters.min_length_frames, 60u);  // 0.5 s at 120 fps
  EXPECT_GT(result.parameters.eps, 0);
  EXPECT_EQ(stages,
            (std::vector<std::string>{"synth", "trellis features", "trellis", "grow", "cluster"}));
  ASSERT_EQ(result.timings.size(), 4u);
  EXPECT_EQ(result.timings[0].stage, "synth");
}

TEST(PublicApi, DefaultsAreTheTools) {
  const motifmine::MineOptions options;
  EXPECT_EQ(options.eps, 0);
  EXPECT_EQ(options.eps_rule, "joint-angle");
  EXPECT_EQ(options.eps_angle_degrees, 12);
  EXPECT_EQ(options.k_max, 256u);
  EXPECT_EQ(options.branch, 5u);
  EXPECT_EQ(options.min_length_seconds, 0.5);
  EXPECT_EQ(options.groups, 0u);
  EXPECT_EQ(options.seed, 1u);
  EXPECT_EQ(options.synth_frames, 120000u);
  EXPECT_EQ(options.synth_motifs, 12u);
}

TEST(PublicApi, AFailedCallCarriesTheCodeAndTheMessage) {
  motif::testing::TempDir dir;
  motifmine::MineOptions options;
  options.out_dir = dir.File("out");
  motifmine::MineResult result;
  options.k_max = 0;
  motifmine::Status status = motifmine::Mine({}, options, &result);
  EXPECT_EQ(status.code(), motifmine::Status::Code::kInvalidArgument);
  // The library names the option as the option table does, not as a flag.
  EXPECT_EQ(status.ToString(),
            "InvalidArgument: kmax must be a whole number in [1, 65535], not '0'");

  options = motifmine::MineOptions();
  options.out_dir = dir.File("out");
  options.eps_rule = "guess";
  EXPECT_EQ(motifmine::Mine({}, options, &result).code(),
            motifmine::Status::Code::kInvalidArgument);

  options = motifmine::MineOptions();
  options.out_dir = dir.File("out");
  status = motifmine::Mine({dir.File("absent.mfs")}, options, &result);
  EXPECT_EQ(status.code(), motifmine::Status::Code::kNotFound) << status.ToString();
  EXPECT_NE(status.message().find("absent.mfs"), std::string::npos) << status.ToString();
  EXPECT_TRUE(motifmine::Status().ok());
  EXPECT_EQ(motifmine::Status().ToString(), "OK");
}

}  // namespace
