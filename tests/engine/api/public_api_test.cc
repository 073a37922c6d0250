// motifmine::Mine, the library's whole job: the same motifs as `motifmine mine` on the same input,
// its defaults those of the tool, and a failing call's Status with the tool's code and message;
// a mined folder loaded back, and an archive's root and pose.
#include <memory>
#include <string>
#include <tuple>
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

TEST(PublicApi, LoadMineResultGivesBackTheMinedResult) {
  motif::testing::TempDir dir;
  motifmine::MineOptions options;
  options.out_dir = dir.File("out");
  options.synth_frames = 15000;
  options.synth_motifs = 2;
  options.write_report = false;
  motifmine::MineResult mined;
  ASSERT_TRUE(motifmine::Mine({}, options, &mined).ok());
  motifmine::MineResult loaded;
  const motifmine::Status status = motifmine::LoadMineResult(dir.File("out"), &loaded);
  ASSERT_TRUE(status.ok()) << status.ToString();
  ASSERT_EQ(loaded.motifs.size(), mined.motifs.size());
  for (size_t m = 0; m < mined.motifs.size(); ++m) {
    ASSERT_EQ(loaded.motifs[m].instances.size(), mined.motifs[m].instances.size());
    for (size_t i = 0; i < mined.motifs[m].instances.size(); ++i) {
      const motifmine::Instance& a = loaded.motifs[m].instances[i];
      const motifmine::Instance& b = mined.motifs[m].instances[i];
      EXPECT_EQ(std::tie(a.clip, a.start, a.end, a.fps), std::tie(b.clip, b.start, b.end, b.fps));
      EXPECT_EQ(a.fps, 120.0);
    }
  }
  EXPECT_EQ(loaded.parameters.eps, mined.parameters.eps);
  EXPECT_EQ(loaded.parameters.eps_how, mined.parameters.eps_how);
  EXPECT_EQ(loaded.parameters.k_max, mined.parameters.k_max);
  EXPECT_EQ(loaded.archive_path, mined.archive_path);
  ASSERT_EQ(loaded.timings.size(), mined.timings.size());
  EXPECT_EQ(loaded.timings[0].stage, "synth");

  EXPECT_EQ(motifmine::LoadMineResult(dir.File("absent"), &loaded).code(),
            motifmine::Status::Code::kNotFound);
  const motifmine::Status empty = motifmine::LoadMineResult(dir.path(), &loaded);
  EXPECT_EQ(empty.code(), motifmine::Status::Code::kNotFound);
  EXPECT_NE(empty.message().find(dir.File("motifs.json")), std::string::npos) << empty.ToString();
}

TEST(PublicApi, AnArchivesRootIsWhereItsPoseStands) {
  motif::testing::TempDir dir;
  ASSERT_EQ(RunTool("synth " + dir.File("s.mfs") + " --frames 15000 --motifs 2 --quiet").exit_code,
            0);
  std::unique_ptr<motifmine::Archive> archive;
  ASSERT_TRUE(motifmine::Archive::Open(dir.File("s.mfs"), &archive).ok());
  const std::string clip = archive->clips()[0].name;
  motifmine::RootMotion root;
  ASSERT_TRUE(archive->Root(clip, 100, 110, &root).ok());
  std::vector<double> positions;
  ASSERT_TRUE(archive->WorldPositions(clip, 100, 110, &positions).ok());
  const size_t joints = archive->joint_names().size();
  ASSERT_EQ(root.positions.size(), 30u);
  ASSERT_EQ(root.rotations.size(), 40u);
  ASSERT_EQ(root.headings.size(), 10u);
  ASSERT_EQ(positions.size(), 10 * joints * 3);
  for (size_t frame = 0; frame < 10; ++frame) {  // joint 0 of a pose is the root
    for (size_t axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(positions[frame * joints * 3 + axis], root.positions[frame * 3 + axis]);
    }
  }
  motifmine::Skeleton skeleton;
  ASSERT_TRUE(archive->ClipSkeleton(clip, &skeleton).ok());
  EXPECT_EQ(skeleton.family, "cmu31");
  EXPECT_EQ(skeleton.joint_names, archive->joint_names());
  EXPECT_EQ(skeleton.parents[0], -1);
  EXPECT_EQ(archive->ClipSkeleton("no_such_clip", &skeleton).code(),
            motifmine::Status::Code::kNotFound);
  EXPECT_EQ(archive->Root(clip, 0, archive->clips()[0].frames + 1, &root).code(),
            motifmine::Status::Code::kInvalidArgument);
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
