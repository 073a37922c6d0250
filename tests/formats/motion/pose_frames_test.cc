#include "formats/motion/pose_frames.h"

#include <gtest/gtest.h>

#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

// A two-joint take: the root walks a curve while turning more than a full circle and bobbing.
Take TurningWalk(size_t frame_count) {
  std::vector<Joint> joints(2);
  joints[0].name = "hip";
  joints[1].name = "thigh";
  joints[1].parent = 0;
  joints[1].offset = {1, -2, 0.5};
  joints[1].has_end_site = true;
  joints[1].end_site = {0, -3, 0};
  Take take;
  take.name = "walk";
  take.fps = 60;
  take.skeleton = Skeleton("custom", joints);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const double t = static_cast<double>(frame_idx) / take.fps;
    const double heading = 2.5 * t;  // passes +-pi: the stored heading must unwrap
    take.root_positions.emplace_back(3 * std::sin(t), 16 + 0.2 * std::sin(5 * t), 4 * t);
    take.rotations.push_back(AxisRotation(Axis::kY, heading) * AxisRotation(Axis::kX, 0.1 * t));
    Eigen::Quaterniond knee = AxisRotation(Axis::kZ, std::sin(3 * t));
    if (frame_idx % 2 == 1) knee.coeffs() = -knee.coeffs();  // sign flips must not survive
    take.rotations.push_back(knee);
  }
  return take;
}

TEST(PoseFrames, RoundTripRestoresWorldMotion) {
  Take take = TurningWalk(200);
  ClipFrames clip = TakeToClipFrames(take);
  ASSERT_EQ(clip.rows.size(), 200 * FrameLayout{2}.stride());
  Take back = ClipFramesToTake(take.skeleton, clip.info, clip.rows.data(), 200);
  ASSERT_EQ(back.frame_count(), 200u);
  for (size_t frame_idx = 0; frame_idx < 200; ++frame_idx) {
    EXPECT_LT((back.root_positions[frame_idx] - take.root_positions[frame_idx]).norm(), 1e-3)
        << "frame " << frame_idx;
    for (size_t joint_idx = 0; joint_idx < 2; ++joint_idx) {
      EXPECT_LT(QuaternionDistance(back.rotation(frame_idx, joint_idx),
                                   take.rotation(frame_idx, joint_idx)),
                1e-6);
    }
  }
  EXPECT_EQ(back.skeleton.joint(1).offset[2], 0.5);
}

TEST(PoseFrames, StoresHeadingFreeRootContinuousSignsAndLocalVelocity) {
  Take take = TurningWalk(200);
  ClipFrames clip = TakeToClipFrames(take);
  const FrameLayout layout{2};
  for (size_t frame_idx = 1; frame_idx < 200; ++frame_idx) {
    const float* row = &clip.rows[frame_idx * layout.stride()];
    const float* previous = row - layout.stride();
    // Root swing has no Y component: the heading is separated out.
    EXPECT_NEAR(row[2], 0.0f, 1e-6);
    // Heading unwrapped: continuous although it passes pi.
    EXPECT_NEAR(row[layout.heading_offset()] - previous[layout.heading_offset()], 2.5 / 60, 1e-5);
    // Knee signs continuous.
    float dot = 0;
    for (int c = 0; c < 4; ++c) dot += row[4 + c] * previous[4 + c];
    EXPECT_GT(dot, 0.0f);
    EXPECT_NEAR(row[layout.height_offset()], take.root_positions[frame_idx].y(), 1e-5);
  }
  EXPECT_GT(clip.rows[199 * layout.stride() + layout.heading_offset()], kPi);
}

}  // namespace
}  // namespace motif
