#include "formats/import/first_frame.h"

#include <gtest/gtest.h>

#include <cmath>

#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

constexpr size_t kJoints = 8;

// A take whose joints swing smoothly (about 0.02 rad per frame each), like captured motion.
Take SmoothTake(size_t frame_count) {
  Take take;
  std::vector<Joint> joints(kJoints);
  for (size_t joint_idx = 0; joint_idx < kJoints; ++joint_idx) {
    joints[joint_idx].name = std::string(1, 'j');
    joints[joint_idx].name += std::to_string(joint_idx);
    joints[joint_idx].parent = static_cast<int>(joint_idx) - 1;
  }
  take.skeleton = Skeleton("custom", joints);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    take.root_positions.emplace_back(0, 1, 0);
    for (size_t joint_idx = 0; joint_idx < kJoints; ++joint_idx) {
      const double angle = 0.4 * std::sin(0.05 * frame_idx + joint_idx);
      take.rotations.push_back(AxisRotation(static_cast<Axis>(joint_idx % 3), angle));
    }
  }
  return take;
}

void SetPose(Take* take, size_t frame_idx, const Eigen::Quaterniond& rotation) {
  for (size_t joint_idx = 0; joint_idx < take->joint_count(); ++joint_idx) {
    take->rotation(frame_idx, joint_idx) = rotation;
  }
}

TEST(FirstFrame, SmoothTakeIsContinuous) {
  FirstFrameCheck check = CheckFirstFrame(SmoothTake(200));
  EXPECT_FALSE(check.discontinuous);
  EXPECT_EQ(check.body_start, 1u);
  EXPECT_GT(check.median_step, 0);
}

TEST(FirstFrame, AConverterPoseInFrontIsDiscontinuous) {
  Take take = SmoothTake(200);
  SetPose(&take, 0, AxisRotation(Axis::kZ, 1.2));  // far from every captured pose
  FirstFrameCheck check = CheckFirstFrame(take);
  EXPECT_TRUE(check.discontinuous);
  EXPECT_EQ(check.body_start, 1u);
  EXPECT_GT(check.first_jump, kFirstFrameStepRatio * check.median_step);
  DropFirstFrame(&take);
  EXPECT_EQ(take.frame_count(), 199u);
  EXPECT_EQ(take.rotations.size(), 199u * kJoints);
  EXPECT_FALSE(CheckFirstFrame(take).discontinuous);
}

TEST(FirstFrame, ConverterPoseFollowedByNullFramesIsDiscontinuous) {
  // Like bvh/09_10: the T-pose, then four identical null frames, then the motion. Frame 0 is
  // close to frame 1 but far from where the motion begins.
  Take take = SmoothTake(200);
  const Eigen::Quaterniond null_pose = AxisRotation(Axis::kY, 1.0);
  SetPose(&take, 0, null_pose * AxisRotation(Axis::kX, 0.08));
  for (size_t frame_idx = 1; frame_idx <= 4; ++frame_idx) SetPose(&take, frame_idx, null_pose);
  FirstFrameCheck check = CheckFirstFrame(take);
  EXPECT_EQ(check.body_start, 5u);
  EXPECT_TRUE(check.discontinuous);
}

TEST(FirstFrame, AGlitchLaterInTheTakeDoesNotDropTheFirstFrame) {
  Take take = SmoothTake(200);
  SetPose(&take, 7, AxisRotation(Axis::kZ, 2.0));  // a one-frame spike after the first steps
  FirstFrameCheck check = CheckFirstFrame(take);
  EXPECT_EQ(check.body_start, 1u);
  EXPECT_FALSE(check.discontinuous);
}

TEST(FirstFrame, StaticTakeNeedsAnAbsoluteJump) {
  // Median step 0: tiny sensor noise in frame 0 is not a discontinuity.
  Take take = SmoothTake(50);
  for (size_t frame_idx = 0; frame_idx < 50; ++frame_idx) {
    SetPose(&take, frame_idx, Eigen::Quaterniond::Identity());
  }
  SetPose(&take, 0, AxisRotation(Axis::kX, 0.01));
  EXPECT_FALSE(CheckFirstFrame(take).discontinuous);
  SetPose(&take, 0, AxisRotation(Axis::kX, 0.5));
  EXPECT_TRUE(CheckFirstFrame(take).discontinuous);
}

TEST(FirstFrame, ShortTakesAreNeverDiscontinuous) {
  Take take = SmoothTake(2);
  SetPose(&take, 0, AxisRotation(Axis::kZ, 1.2));
  EXPECT_FALSE(CheckFirstFrame(take).discontinuous);
  Take empty = SmoothTake(0);
  EXPECT_FALSE(CheckFirstFrame(empty).discontinuous);
  DropFirstFrame(&empty);
  EXPECT_EQ(empty.frame_count(), 0u);
}

}  // namespace
}  // namespace motif
