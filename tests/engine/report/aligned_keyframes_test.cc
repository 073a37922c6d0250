#include "engine/report/aligned_keyframes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <regex>
#include <string>
#include <vector>

#include "engine/report/instance_playback.h"
#include "engine/report/report_html.h"
#include "engine/synth/cmu_body_model.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TEST(AlignedKeyframes, ReferenceKeysAreEvenlySpacedSamples) {
  EXPECT_EQ(ReferenceKeySamples(61, 5), (std::vector<uint32_t>{0, 15, 30, 45, 60}));
  EXPECT_EQ(ReferenceKeySamples(10, 4), (std::vector<uint32_t>{0, 3, 6, 9}));
  EXPECT_EQ(ReferenceKeySamples(3, 5), (std::vector<uint32_t>{0, 1, 1, 2, 2}));
  EXPECT_EQ(ReferenceKeySamples(7, 1), (std::vector<uint32_t>{0}));
}

TEST(AlignedKeyframes, FramesAreTheAlignedSamplesOfTheInstance) {
  const std::vector<uint32_t> keys = {0, 2, 4};
  // The reference itself: its own samples.
  EXPECT_EQ(AlignedKeyframeFrames(keys, {}, 100, 4), (std::vector<uint64_t>{100, 108, 116}));
  // An instance that pauses after its first sample: keyframe 1 is where it moves on.
  EXPECT_EQ(AlignedKeyframeFrames(keys, {0, 1, 5, 6, 7}, 10, 1),
            (std::vector<uint64_t>{10, 15, 17}));
}

// A take of the CMU skeleton that holds its rest pose for `hold` frames, then turns its left
// femur and right humerus at `radians_per_frame` about X for `frames` frames.
Take Sweep(const std::string& name, size_t hold, size_t frames, double radians_per_frame,
           double fps) {
  Take take;
  take.name = name;
  take.fps = fps;
  take.source_fps = fps;
  take.skeleton = CmuBodyModel::Get().skeleton();
  const int femur = take.skeleton.FindJoint("lfemur");
  const int humerus = take.skeleton.FindJoint("rhumerus");
  take.root_positions.assign(hold + frames, Eigen::Vector3d(0, 17, 0));
  take.rotations.assign((hold + frames) * take.joint_count(), Eigen::Quaterniond::Identity());
  for (size_t frame = 0; frame < frames; ++frame) {
    const double angle = radians_per_frame * static_cast<double>(frame);
    take.rotation(hold + frame, femur) = AxisRotation(Axis::kX, angle);
    take.rotation(hold + frame, humerus) = AxisRotation(Axis::kX, -angle);
  }
  return take;
}

// The clip frames under each strip's label ("frames a · b · ..."), in page order.
std::vector<std::vector<uint64_t>> StripFrames(const std::string& html) {
  std::vector<std::vector<uint64_t>> strips;
  const std::regex label("class=\"kf\">frames ([^<]*)</span>");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), label);
       it != std::sregex_iterator(); ++it) {
    std::vector<uint64_t> frames;
    const std::string text = (*it)[1];
    const std::regex number("[0-9]+");
    for (auto at = std::sregex_iterator(text.begin(), text.end(), number);
         at != std::sregex_iterator(); ++at) {
      frames.push_back(std::stoull((*at)[0]));
    }
    strips.push_back(frames);
  }
  return strips;
}

// The motif's second instance is its first held still for 30 samples and then played at half
// the speed (a warp that is not linear: even spacing would show other frames): figure k of its
// strip is the warped image of the first's, exactly, at 30 fps (a sample a frame) and at 120 fps
// (a sample every 4 frames); the player's alignment says the same.
TEST(AlignedKeyframes, AHeldThenHalfSpeedInstanceShowsTheSameMoments) {
  for (const double fps : {30.0, 120.0}) {
    testing::TempDir dir;
    const std::string path = dir.File("half.mfs");
    const uint32_t step = PlaybackStep(fps);
    const size_t frames = 60 * step + 1;  // 61 samples
    const size_t hold = 30 * step;        // 30 samples
    const size_t slow_frames = hold + 2 * frames - 1;
    {
      auto writer = FrameFileWriter::Create(path, CmuBodyModel::Get().skeleton(), fps);
      ASSERT_TRUE(writer.ok()) << writer.status().ToString();
      ASSERT_TRUE(
          (*writer)->AppendClip(TakeToClipFrames(Sweep("ref", 0, frames, 0.6 / frames, fps))).ok());
      ASSERT_TRUE(
          (*writer)
              ->AppendClip(TakeToClipFrames(Sweep("slow", hold, 2 * frames - 1, 0.3 / frames, fps)))
              .ok());
      ASSERT_TRUE((*writer)->Commit().ok());
    }
    auto reader = FrameFileReader::Open(path);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    MotifsDocument document;
    document.archive = path;
    document.frames = (*reader)->frame_count();
    for (const ClipInfo& clip : (*reader)->clips()) {
      document.clips.push_back(
          {clip.name, clip.source_path, clip.frame_count, clip.fps, clip.first_frame});
    }
    document.params = {1.0, 64, 4, 60, 0, 1};
    const uint64_t slow_first = (*reader)->clips()[1].first_frame;
    document.motifs.push_back({0, {{"ref", 0, frames, 0}, {"slow", 0, slow_frames, slow_first}}});
    auto html = ReportHtmlText(document, **reader, {});
    ASSERT_TRUE(html.ok()) << html.status().ToString();

    const std::vector<std::vector<uint64_t>> strips = StripFrames(*html);
    ASSERT_EQ(strips.size(), 2u);
    const std::vector<uint64_t> reference = {0, 15 * step, 30 * step, 45 * step, 60 * step};
    EXPECT_EQ(strips[0], reference) << "fps " << fps;
    // Reference sample r is the slow one's sample 30 + 2r (r > 0); the held pose's earliest, 0.
    const std::vector<uint64_t> warped = {0, 60 * step, 90 * step, 120 * step, 150 * step};
    EXPECT_EQ(strips[1], warped) << "fps " << fps;

    // The player shows the same moments: its alignment of the slow instance.
    const size_t block = html->find("id=\"play-0\">");
    ASSERT_NE(block, std::string::npos);
    const size_t begin = html->find('>', block) + 1;
    const nlohmann::json data =
        nlohmann::json::parse(html->substr(begin, html->find("</script>", begin) - begin));
    const std::vector<uint32_t> align = data["instances"][1]["align"];
    ASSERT_EQ(align.size(), 61u);
    EXPECT_EQ(align[0], 0u);
    for (uint32_t sample = 1; sample < 61; ++sample) EXPECT_EQ(align[sample], 30 + 2 * sample);
  }
}

}  // namespace
}  // namespace motif
