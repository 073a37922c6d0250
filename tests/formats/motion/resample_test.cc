#include "formats/motion/resample.h"

#include <gtest/gtest.h>

#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

Take Spinning(double fps, size_t frame_count) {
  std::vector<Joint> joints(1);
  joints[0].name = "root";
  Take take;
  take.fps = fps;
  take.skeleton = Skeleton("custom", joints);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const double t = frame_idx / fps;
    take.root_positions.emplace_back(t, 0, 0);
    take.rotations.push_back(AxisRotation(Axis::kY, t));
  }
  return take;
}

TEST(ResampleTake, SlerpsToTheNewRate) {
  Take take = Spinning(120, 121);  // one second
  Take out = ResampleTake(take, 30);
  ASSERT_EQ(out.frame_count(), 31u);
  EXPECT_EQ(out.fps, 30);
  for (size_t frame_idx = 0; frame_idx < 31; ++frame_idx) {
    EXPECT_NEAR(out.root_positions[frame_idx].x(), frame_idx / 30.0, 1e-12);
    EXPECT_NEAR(HeadingOf(out.rotation(frame_idx, 0)), frame_idx / 30.0, 1e-9);
  }
  Take up = ResampleTake(Spinning(30, 31), 120);
  ASSERT_EQ(up.frame_count(), 121u);
  EXPECT_NEAR(HeadingOf(up.rotation(61, 0)), 61 / 120.0, 1e-9);  // between source frames
}

TEST(ResampleTake, SameRateIsUnchanged) {
  EXPECT_TRUE(SameFrameRate(120, 1 / 0.0083333));
  EXPECT_FALSE(SameFrameRate(120, 119));
  Take take = Spinning(120.0005, 50);
  EXPECT_EQ(ResampleTake(take, 120).frame_count(), 50u);
}

}  // namespace
}  // namespace motif
