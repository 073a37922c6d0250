// Exported motif clips round-trip: every instance written by `motifmine export-motif` as BVH,
// imported with `motifmine import` into a new archive, has the source archive's frames, joint by
// joint, within the quantisation bound of the archive.
//
// The bound (docs/formats/frame_file.md, "Error bound"): a joint quaternion is stored with
// uniform step s = 2^-15 and renormalised on decoding, so a decoded quaternion lies within an
// angle asin(s) in 4-space of the quaternion that was written, and the sign-independent chord
// QuaternionDistance = 2 sin(angle / 2) is at most that angle. Export writes the source archive's
// decoded frames; re-import quantises them once more, so each re-imported quaternion is within
// asin(s) of the source's decoded one, plus the BVH text: docs/import.md measured 9.0e-7 for
// CMU's 4-decimal text, and the writer prints 6 decimals of a degree, so 1e-6 is generous. The
// root's stored rotation (its swing, heading removed) has the same bound; its heading, extracted
// again from the full root rotation, is within half a heading step (5e-6 rad) plus that
// rotation's error as an angle (at most twice the chord). The root height is stored with step
// 1e-4: within 5e-5 of the source's decoded value, plus the text (5e-7) and float rounding.
// Measured (printed by the test): joints 2.2e-5 of 3.2e-5, root 3.7e-6, heading 4.9e-6, height 0.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "engine/cluster/motifs_json.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

constexpr double kRotationStep = 1.0 / 32768.0;  // 2^-15, the default quaternion step
const double kJointBound = std::asin(kRotationStep) + 1e-6;
const double kHeadingBound = 5e-6 + 2 * kJointBound;
constexpr double kHeightBound = 5e-5 + 5e-7 + 4e-6;

Eigen::Quaterniond QuaternionAt(const std::vector<float>& rows, size_t row, size_t stride,
                                size_t offset) {
  const float* q = rows.data() + row * stride + offset;
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

TEST(ExportReimport, ExportedInstancesMatchTheSourceFramesWithinTheQuantisationBound) {
  testing::TempDir dir;
  const std::string archive = dir.File("s.mfs");
  RunResult synth =
      RunTool("synth " + archive + " --frames 6000 --motifs 2 --seed 5 " +
              "--motif-seconds-max 1.5 --clip-seconds-min 10 " + "--clip-seconds-max 20 --quiet");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  auto truth = ReadTruthJson(dir.File("s.truth.json"));
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  auto source = FrameFileReader::Open(archive);
  ASSERT_TRUE(source.ok()) << source.status().ToString();

  // motifs.json written by hand: the planted instances as the mined motifs.
  MotifsDocument document;
  document.archive = archive;
  document.frames = (*source)->frame_count();
  std::map<std::string, ClipInfo> source_clips;
  for (const ClipInfo& clip : (*source)->clips()) {
    document.clips.push_back(
        {clip.name, clip.source_path, clip.frame_count, clip.fps, clip.first_frame});
    source_clips[clip.name] = clip;
  }
  document.params = {1.0, 64, 4, 60, 0, 1};
  std::map<uint32_t, std::vector<MotifsJsonInstance>> by_motif;
  for (const PlantedInstance& planted : truth->instances) {
    by_motif[planted.motif].push_back({planted.clip, planted.start, planted.end,
                                       source_clips[planted.clip].first_frame + planted.start});
  }
  for (auto& [motif_id, instances] : by_motif) document.motifs.push_back({motif_id, instances});
  std::filesystem::create_directories(dir.File("out"));
  ASSERT_TRUE(WriteMotifsJson(dir.File("out/motifs.json"), document).ok());

  // Every motif exported; the file name says which instance it is.
  struct Exported {
    const MotifsJsonInstance* instance;
    uint32_t motif;
  };
  std::map<std::string, Exported> by_stem;
  for (const MotifsJsonMotif& motif : document.motifs) {
    RunResult run = RunTool("export-motif " + dir.File("out") + " --motif " +
                            std::to_string(motif.id) + " --out " + dir.File("bvh"));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    for (size_t idx = 0; idx < motif.instances.size(); ++idx) {
      const MotifsJsonInstance& instance = motif.instances[idx];
      const std::string stem = "motif" + std::to_string(motif.id) + "_" + std::to_string(idx) +
                               "_" + instance.clip + "_" + std::to_string(instance.start) + "-" +
                               std::to_string(instance.end);
      ASSERT_TRUE(std::filesystem::exists(dir.File("bvh/" + stem + ".bvh"))) << stem;
      by_stem[stem] = {&instance, motif.id};
    }
  }
  ASSERT_EQ(by_stem.size(), truth->instances.size());

  // Re-imported into a new archive. The writer adds no T-pose frame, and --first-frame keep stops
  // the importer from dropping a first frame that it might take for one: every frame of the file
  // is an instance frame.
  const std::string reimported_path = dir.File("re.mfs");
  RunResult import =
      RunTool("import " + reimported_path + " " + dir.File("bvh") + " --first-frame keep --quiet");
  ASSERT_EQ(import.exit_code, 0) << import.output;
  auto reimported = FrameFileReader::Open(reimported_path);
  ASSERT_TRUE(reimported.ok()) << reimported.status().ToString();
  ASSERT_EQ((*reimported)->clips().size(), by_stem.size());
  ASSERT_EQ((*reimported)->skeleton().joint_count(), (*source)->skeleton().joint_count());
  EXPECT_NEAR((*reimported)->fps(), (*source)->fps(), 1e-6);

  // The default import (--first-frame auto) keeps every frame too: the first frame of an
  // exported clip is continuous with the rest, so it is not taken for a converter's T-pose.
  RunResult import_auto =
      RunTool("import " + dir.File("auto.mfs") + " " + dir.File("bvh") + " --quiet");
  ASSERT_EQ(import_auto.exit_code, 0) << import_auto.output;
  auto auto_reader = FrameFileReader::Open(dir.File("auto.mfs"));
  ASSERT_TRUE(auto_reader.ok());
  EXPECT_EQ((*auto_reader)->frame_count(), (*reimported)->frame_count())
      << "--first-frame auto dropped the first frame of an exported clip";

  const size_t joints = (*source)->skeleton().joint_count();
  const FrameLayout layout = (*source)->layout();
  const size_t stride = layout.stride();
  double worst_joint = 0, worst_root = 0, worst_height = 0, worst_heading = 0;
  uint64_t frames_compared = 0;
  for (const ClipInfo& clip : (*reimported)->clips()) {
    auto found = by_stem.find(clip.name);
    ASSERT_NE(found, by_stem.end()) << "unexpected clip " << clip.name;
    const MotifsJsonInstance& instance = *found->second.instance;
    SCOPED_TRACE(clip.name);
    ASSERT_EQ(clip.frame_count, instance.length()) << "a frame was added or dropped";
    std::vector<float> expected, actual;
    ASSERT_TRUE((*source)->ReadFrames(instance.frame, instance.length(), &expected).ok());
    ASSERT_TRUE((*reimported)->ReadFrames(clip.first_frame, clip.frame_count, &actual).ok());
    // The heading may come back shifted by whole turns (it is unwrapped from the clip's start).
    const double turns =
        std::round((actual[layout.heading_offset()] - expected[layout.heading_offset()]) /
                   (2 * std::numbers::pi));
    for (size_t frame = 0; frame < clip.frame_count; ++frame) {
      for (size_t joint = 0; joint < joints; ++joint) {
        const double distance = QuaternionDistance(QuaternionAt(expected, frame, stride, 4 * joint),
                                                   QuaternionAt(actual, frame, stride, 4 * joint));
        double& worst = joint == 0 ? worst_root : worst_joint;
        worst = std::max(worst, distance);
        ASSERT_LE(distance, kJointBound) << "frame " << frame << " joint " << joint << " ("
                                         << (*source)->skeleton().joint(joint).name << ")";
      }
      const double height = std::abs(actual[frame * stride + layout.height_offset()] -
                                     expected[frame * stride + layout.height_offset()]);
      worst_height = std::max(worst_height, height);
      ASSERT_LE(height, kHeightBound) << "root height, frame " << frame;
      const double heading = std::abs(actual[frame * stride + layout.heading_offset()] -
                                      expected[frame * stride + layout.heading_offset()] -
                                      turns * 2 * std::numbers::pi);
      worst_heading = std::max(worst_heading, heading);
      ASSERT_LE(heading, kHeadingBound) << "heading, frame " << frame;
      ++frames_compared;
    }
  }
  std::cout << "[ compared ] " << frames_compared << " frames of " << by_stem.size()
            << " instances; worst quaternion distance: joints " << worst_joint << ", root "
            << worst_root << " (bound " << kJointBound << "); root height " << worst_height
            << " (bound " << kHeightBound << "); heading " << worst_heading << " rad (bound "
            << kHeadingBound << ")\n";
}

}  // namespace
}  // namespace motif
