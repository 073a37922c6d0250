// A BVH take exported back from the archive is that take: `motifmine import` of a real CMU BVH
// take (whose joints the import renames to the canonical CMU names, and whose converter T-pose it
// drops), then `motifmine export` of the whole clip, must give the source file's joint names and
// hierarchy (the default --names source), and its frames, frame by frame: exported frame k is
// source frame k + the clip's file frame (`info --json`: source_first_frame), every joint's
// rotation within the archive's quantisation (chord 2^-15 plus the BVH text, as in
// export_reimport_test.cc) and the root within 1e-3 of the source's units. --names canonical
// gives the archive's names. Skips when the real takes are absent.

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "formats/import/bvh_parser.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

Take ParseFile(const std::string& path) {
  auto text = ReadFileToString(path);
  EXPECT_TRUE(text.ok()) << path;
  auto take = ParseBvh(text.ok() ? *text : "", path);
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? *take : Take();
}

// name -> (index, parent name)
std::map<std::string, std::pair<size_t, std::string>> Hierarchy(const Skeleton& skeleton) {
  std::map<std::string, std::pair<size_t, std::string>> joints;
  for (size_t idx = 0; idx < skeleton.joint_count(); ++idx) {
    const int parent = skeleton.joint(idx).parent;
    joints[skeleton.joint(idx).name] = {idx, parent < 0 ? "" : skeleton.joint(parent).name};
  }
  return joints;
}

TEST(ExportSourceFidelity, ABvhTakeExportsWithItsJointNamesAndItsFrames) {
  MOTIF_REQUIRE_MOCAP_DATA();
  testing::TempDir dir;
  const std::string source = testing::MocapDir() + "/bvh/01_01.bvh";
  const std::string archive = dir.File("a.mfs");
  testing::RunResult imported = testing::RunTool("import " + archive + " " + source + " --quiet");
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  testing::RunResult info = testing::RunTool("info " + archive + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  const nlohmann::json clip = nlohmann::json::parse(info.output)["clips"][0];
  const uint64_t file_frame = clip["source_first_frame"].get<uint64_t>();
  EXPECT_EQ(file_frame, 1u) << "the cgspeed converter's T-pose is frame 0 of the file";

  testing::RunResult exported =
      testing::RunTool("export " + archive + " --clip 01_01 --out " + dir.File("out.bvh"));
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const Take original = ParseFile(source);
  const Take copy = ParseFile(dir.File("out.bvh"));
  const auto original_joints = Hierarchy(original.skeleton);
  const auto copy_joints = Hierarchy(copy.skeleton);
  ASSERT_EQ(copy_joints.size(), original_joints.size());
  for (const auto& [name, joint] : original_joints) {
    auto found = copy_joints.find(name);
    ASSERT_NE(found, copy_joints.end()) << "the export lost the joint name " << name;
    EXPECT_EQ(found->second.second, joint.second) << name << "'s parent";
  }
  EXPECT_EQ(copy.skeleton.joint(0).name, original.skeleton.joint(0).name);

  ASSERT_EQ(copy.frame_count() + file_frame, original.frame_count());
  const double rotation_bound = std::asin(1.0 / 32768.0) + 2e-6;
  double worst_rotation = 0, worst_root = 0;
  for (size_t frame = 0; frame < copy.frame_count(); ++frame) {
    const size_t source_frame = frame + file_frame;
    for (const auto& [name, joint] : original_joints) {
      const size_t copy_idx = copy_joints.at(name).first;
      worst_rotation = std::max(worst_rotation,
                                QuaternionDistance(copy.rotation(frame, copy_idx),
                                                   original.rotation(source_frame, joint.first)));
    }
    worst_root = std::max(
        worst_root,
        (copy.root_positions[frame] - original.root_positions[source_frame]).cwiseAbs().maxCoeff());
  }
  std::printf("[ measured ] %zu frames: rotations within %.2e (bound %.2e), root within %.2e\n",
              copy.frame_count(), worst_rotation, rotation_bound, worst_root);
  EXPECT_LE(worst_rotation, rotation_bound);
  EXPECT_LE(worst_root, 1e-3);

  testing::RunResult canonical = testing::RunTool("export " + archive + " --clip 01_01 --end 2 " +
                                                  "--names canonical --out " + dir.File("c.bvh"));
  ASSERT_EQ(canonical.exit_code, 0) << canonical.output;
  const Take renamed = ParseFile(dir.File("c.bvh"));
  EXPECT_EQ(renamed.skeleton.joint(0).name, "root");
  EXPECT_GE(renamed.skeleton.FindJoint("lfemur"), 0);
  testing::RunResult bad = testing::RunTool("export " + archive + " --clip 01_01 --names x " +
                                            "--out " + dir.File("x.bvh"));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--names"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace motif
