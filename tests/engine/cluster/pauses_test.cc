// Pauses: the per-frame speed of crafted motions with known rotation rates, and the still
// stretches FindPauses finds in an archive of them (clip boundaries, the read chunks).
#include "engine/cluster/pauses.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cluster/instance_builder.h"
#include "engine/distance/pose_features.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

constexpr double kFps = 120.0;

// Rows of `frame_count` frames in which every joint is turned about x by angles[t] degrees.
std::vector<float> RowsTurnedBy(const std::vector<double>& angles, uint32_t joint_count) {
  const FrameLayout layout{joint_count};
  std::vector<float> rows(angles.size() * layout.stride(), 0.0f);
  for (size_t t = 0; t < angles.size(); ++t) {
    const double half = angles[t] * std::numbers::pi / 360.0;
    for (uint32_t joint = 0; joint < joint_count; ++joint) {
      float* q = &rows[t * layout.stride() + layout.quaternion_offset(joint)];
      q[0] = static_cast<float>(std::cos(half));
      q[1] = static_cast<float>(std::sin(half));
    }
  }
  return rows;
}

// Still until frame `from`, then `step` degrees a frame for `frames` frames, then still.
std::vector<double> TurnOnce(size_t count, size_t from, size_t frames, double step) {
  std::vector<double> angles(count, 0.0);
  for (size_t t = 0; t < count; ++t) {
    const size_t moved = t <= from ? 0 : std::min(t - from, frames);
    angles[t] = step * static_cast<double>(moved);
  }
  return angles;
}

TEST(FrameSpeedsTest, DegreesPerSecondOfTheWeightedJoints) {
  const uint32_t joints = 3;
  const std::vector<float> weights = {1.0f, 0.0f, 2.0f};  // the unweighted joint is not counted
  // 2 degrees a frame = 240 degrees a second at 120 fps, from frame 100 to 200.
  const std::vector<float> rows = RowsTurnedBy(TurnOnce(300, 100, 100, 2.0), joints);
  const std::vector<double> speeds = FrameSpeeds(rows.data(), 300, joints, weights, kFps);
  ASSERT_EQ(speeds.size(), 300u);
  EXPECT_EQ(speeds[0], 0.0);
  EXPECT_EQ(speeds[96], 0.0);  // frames 93 and 99: both still (h = 3 frames at 120 fps)
  EXPECT_NEAR(speeds[98], 2.0 * kFps / 6.0, 1.0);  // one moving frame in its window of six
  EXPECT_NEAR(speeds[150], 240.0, 2.0);
  EXPECT_NEAR(speeds[202], 2.0 * kFps / 6.0, 1.0);
  EXPECT_EQ(speeds[203], 0.0);
  // The window is clamped at the ends: still a speed, not a read outside the rows.
  EXPECT_EQ(FrameSpeeds(rows.data(), 1, joints, weights, kFps), std::vector<double>{0.0});
}

// An archive of the synthesizer's skeleton whose clips turn as given.
std::unique_ptr<FrameFileReader> ArchiveTurning(const testing::TempDir& dir,
                                                const std::vector<std::vector<double>>& clips) {
  SynthOptions options;
  options.frames = 6000;
  options.motifs = 1;
  options.threads = 1;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok());
  const Skeleton& skeleton = (*synthesizer)->skeleton();
  ClipFrames model;
  EXPECT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) {
                    if (model.rows.empty()) model = clip;
                    return Status::Ok();
                  })
                  .ok());
  const std::string path = dir.File("turning.mfs");
  auto writer = FrameFileWriter::Create(path, skeleton, kFps);
  EXPECT_TRUE(writer.ok());
  for (size_t idx = 0; idx < clips.size(); ++idx) {
    ClipFrames clip = model;
    clip.info.name = "turn_" + std::to_string(idx);
    clip.info.frame_count = clips[idx].size();
    clip.rows = RowsTurnedBy(clips[idx], (*writer)->layout().joint_count);
    EXPECT_TRUE((*writer)->AppendClip(clip).ok());
  }
  EXPECT_TRUE((*writer)->Commit().ok());
  auto reader = FrameFileReader::Open(path);
  EXPECT_TRUE(reader.ok());
  return std::move(reader.value());
}

TEST(FindPausesTest, StillStretchesOfAtLeastTheShortestPauseInEachClip) {
  testing::TempDir dir;
  // Clip 0: still, a turn from 100 to 200, 12 still frames (0.1 s, too short), a turn to 300,
  // still to the end. Clip 1 (from global frame 400): turning from its first frame, so the
  // pause at the end of clip 0 stops there; 9,000 frames, so the pause from 8,150 to 8,300
  // crosses the 8,192-frame read chunk.
  std::vector<double> first = TurnOnce(400, 100, 100, 2.0);
  const std::vector<double> second_turn = TurnOnce(400, 212, 88, 2.0);
  for (size_t t = 212; t < 400; ++t) first[t] += second_turn[t];
  std::vector<double> second(9000, 0.0);
  for (size_t t = 0; t < second.size(); ++t) {
    const bool still = t >= 8150 && t < 8300;
    second[t] = still ? second[8149] : 1.5 * static_cast<double>(t < 8150 ? t : t - 150);
  }
  const std::unique_ptr<FrameFileReader> archive = ArchiveTurning(dir, {first, second});
  PauseOptions options;
  options.max_speed = 15.0;
  options.min_seconds = 0.2;  // 24 frames
  Result<std::vector<MotifInstance>> pauses = FindPauses(*archive, options);
  ASSERT_TRUE(pauses.ok()) << pauses.status().ToString();
  // Moving frames are those whose window [t - 3, t + 3] holds a turn: 98..202, 210..302 of
  // clip 0; the 7 still frames between them are no pause. Clip 1 holds one angle from its frame
  // 8149 to 8299, so frames 8152..8296 are still.
  const std::vector<MotifInstance> expected = {{0, 98}, {303, 400}, {400 + 8152, 400 + 8297}};
  EXPECT_EQ(*pauses, expected);

  // Near given ranges: only the pauses within 24 frames (the shortest pause) of them, cut there.
  EXPECT_EQ(*FindPausesNear(*archive, options, {{90, 150}}),
            (std::vector<MotifInstance>{{66, 98}}));
  EXPECT_TRUE(FindPausesNear(*archive, options, {{410, 500}})->empty());  // clip 1 moves there
  // Near [8700, 8710) only 21 frames of the pause show: too short, and it does not overlap.
  EXPECT_EQ(*FindPausesNear(*archive, options, {{8700, 8710}, {8560, 8600}}),
            (std::vector<MotifInstance>{{8552, 8624}}));
  // The pauses near an instance trim it as the whole archive's pauses do.
  for (const MotifInstance instance :
       {MotifInstance{20, 250}, MotifInstance{120, 390}, MotifInstance{290, 400},
        MotifInstance{8500, 8700}, MotifInstance{8560, 8600}, MotifInstance{8690, 9000}}) {
    EXPECT_EQ(MovingSpan(instance, *FindPausesNear(*archive, options, {instance}), 30),
              MovingSpan(instance, *pauses, 30))
        << instance.start << ".." << instance.end;
  }
  EXPECT_TRUE(FindPausesNear(*archive, options, {{9300, 9500}}).status().IsInvalidArgument());
  // The stretches scanned in parallel give the same pauses, in the same order.
  const std::vector<MotifInstance> near = {{8700, 8710}, {90, 150}, {8560, 8600}, {290, 400}};
  EXPECT_EQ(*FindPausesNear(*archive, options, near, 2), *FindPausesNear(*archive, options, near, 1));
  EXPECT_EQ(FindPausesNear(*archive, options, near, 2)->size(), 3u);

  options.max_speed = 0;
  EXPECT_TRUE(FindPauses(*archive, options)->empty());
  options.max_speed = std::nan("");
  EXPECT_TRUE(FindPauses(*archive, options).status().IsInvalidArgument());
  options.max_speed = 15.0;
  options.min_seconds = 0;
  EXPECT_TRUE(FindPauses(*archive, options).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
