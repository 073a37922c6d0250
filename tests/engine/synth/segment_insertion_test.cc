// WarpSegment, AddSmoothNoise and InsertSegment on a tiny two-joint take with known motion.
#include "engine/synth/segment_insertion.h"

#include <cmath>

#include <gtest/gtest.h>

namespace motif {
namespace {

// A take of `frames` frames: the root walks along x one unit a frame; joint 1 turns about z by
// one degree a frame.
Take TurningTake(size_t frames) {
  Take take;
  take.name = "turning";
  Joint root;
  root.name = "root";
  Joint arm;
  arm.name = "arm";
  arm.parent = 0;
  arm.offset = {1, 0, 0};
  take.skeleton = Skeleton("test", {root, arm});
  for (size_t frame = 0; frame < frames; ++frame) {
    take.root_positions.push_back({static_cast<double>(frame), 1.0, 0.0});
    take.rotations.push_back(Eigen::Quaterniond::Identity());
    take.rotations.push_back(Eigen::Quaterniond(
        Eigen::AngleAxisd(static_cast<double>(frame) * M_PI / 180, Eigen::Vector3d::UnitZ())));
  }
  return take;
}

double ArmDegrees(const Eigen::Quaterniond& rotation) {
  return Eigen::AngleAxisd(rotation).angle() * 180 / M_PI;
}

TEST(SegmentInsertion, AWarpPlaysTheSourceAtTheGivenSpeed) {
  const Take source = TurningTake(100);
  // Frames [10, 30) at half speed: 39 output frames cover source frames 10..29.
  const Segment slow = WarpSegment(source, 10, 20, 39, [](size_t k) { return k / 2.0; });
  ASSERT_EQ(slow.frame_count(), 39u);
  EXPECT_NEAR(ArmDegrees(slow.rotations[2 * 0 + 1]), 10.0, 1e-9);
  EXPECT_NEAR(ArmDegrees(slow.rotations[2 * 1 + 1]), 10.5, 1e-9);  // halfway, by slerp
  EXPECT_NEAR(ArmDegrees(slow.rotations[2 * 38 + 1]), 29.0, 1e-9);
  EXPECT_NEAR(slow.root_positions[1].x(), 10.5, 1e-12);
}

TEST(SegmentInsertion, TheInsertedSegmentContinuesTheRootPathWithoutAJump) {
  const Take host = TurningTake(50);
  const Segment segment =
      WarpSegment(TurningTake(100), 60, 10, 10, [](size_t k) { return static_cast<double>(k); });
  const Take result = InsertSegment(host, 20, segment);
  ASSERT_EQ(result.frame_count(), 60u);
  // Host frames before, the segment (its arm at 60..69 degrees), the rest of the host after.
  EXPECT_NEAR(ArmDegrees(result.rotation(19, 1)), 19.0, 1e-9);
  EXPECT_NEAR(ArmDegrees(result.rotation(20, 1)), 60.0, 1e-9);
  EXPECT_NEAR(ArmDegrees(result.rotation(30, 1)), 20.0, 1e-9);
  // The root moves one unit a frame throughout, and keeps its height.
  for (size_t frame = 1; frame < result.frame_count(); ++frame) {
    if (frame == 30) continue;  // the host resumes where the segment's last frame was
    EXPECT_NEAR((result.root_positions[frame] - result.root_positions[frame - 1]).x(), 1.0, 1e-9)
        << frame;
  }
  EXPECT_NEAR(result.root_positions[30].x(), result.root_positions[29].x(), 1e-9);
  EXPECT_EQ(result.root_positions[25].y(), 1.0);
}

TEST(SegmentInsertion, NoiseIsSmallSmoothAndTheSameForASeed) {
  const Segment clean =
      WarpSegment(TurningTake(200), 0, 200, 200, [](size_t k) { return static_cast<double>(k); });
  Segment a = clean;
  Segment b = clean;
  Segment c = clean;
  AddSmoothNoise(&a, 1.0, 30, 7);
  AddSmoothNoise(&b, 1.0, 30, 7);
  AddSmoothNoise(&c, 1.0, 30, 8);
  double largest = 0;
  double largest_step = 0;
  bool differs_from_other_seed = false;
  for (size_t idx = 0; idx < a.rotations.size(); ++idx) {
    EXPECT_EQ(a.rotations[idx].coeffs(), b.rotations[idx].coeffs());
    differs_from_other_seed |= a.rotations[idx].coeffs() != c.rotations[idx].coeffs();
    const double off = clean.rotations[idx].angularDistance(a.rotations[idx]) * 180 / M_PI;
    largest = std::max(largest, off);
    if (idx >= 2) {
      const double noise_now = off;
      const double noise_before =
          clean.rotations[idx - 2].angularDistance(a.rotations[idx - 2]) * 180 / M_PI;
      largest_step = std::max(largest_step, std::abs(noise_now - noise_before));
    }
  }
  EXPECT_TRUE(differs_from_other_seed);
  EXPECT_GT(largest, 0.5);       // there is noise
  EXPECT_LT(largest, 8.0);       // of a few degrees at most (1 degree per component)
  EXPECT_LT(largest_step, 0.5);  // and it changes slowly from frame to frame
}

}  // namespace
}  // namespace motif
