// Detecting the converter-made T-pose at the start of a take. The cgspeed BVH conversions of the
// CMU data put a T-pose in front of the captured motion (not an all-zero frame: e.g.
// bvh/05_01.bvh frame 0 holds -21, 21, -16 on some joints, with the root at frame 1's position).
// It is detected generically, by discontinuity: frame 0 is far from where the take's continuous
// motion begins, measured against the take's typical frame-to-frame step.
//
// Definitions (s_k = FramePoseDistance(k, k + 1), m = median of s_k over k >= 1):
//   body start b: the first frame b in [1, kFirstFrameMaxBodyStart] from which the next
//     kFirstFrameBodySteps steps are all typical (s_k <= kFirstFrameStepRatio * m); 1 if none.
//   frame 0 is discontinuous when first_jump = FramePoseDistance(0, b) > kFirstFrameStepRatio * m
//     and first_jump > kFirstFrameMinJump.
// Usually b = 1 and the test is "step 0 is > 10x the median step". The body start matters for
// takes whose first captured frames are themselves not motion: bvh/07_12 and bvh/09_10 follow the
// T-pose with one resp. four frames whose channels are all 0 (a null pose at the start of the
// source data; kept, only the converter's frame is dropped), so the T-pose is close to frame 1
// (0.92, about 3.5x the median step) but far from the motion that follows (24x); the Daz
// conversions ease from their T-pose into the capture over about 5 frames (steps 1.1, 1.08,
// 0.95, 0.66, 0.27, then 0.06-0.14).
// Measured on ../shared/data/mocap (checked by tests/formats/import/real_data_test.cc):
// first_jump / m is 18x to 78x on all 62 bvh/ and 10 bvh_daz/ takes (first_jump >= 2.19), and
// at most 2.5x on the 34 AMC takes (first_jump <= 0.67), where the body start is 1 for every take.
// Only frame 0 is ever dropped: the converters add exactly one frame.
// Thread-safety: pure functions.
#pragma once

#include <cstddef>

#include "formats/motion/take.h"

namespace motif {

// The pose distance used here: the sum over all joints (root included) of QuaternionDistance
// between the two frames' rotations. Root translation is not used (the cgspeed T-pose keeps
// frame 1's root position).
double FramePoseDistance(const Take& take, size_t frame_a, size_t frame_b);

inline constexpr double kFirstFrameStepRatio = 10.0;
inline constexpr double kFirstFrameMinJump = 0.5;
inline constexpr size_t kFirstFrameMaxBodyStart = 10;
inline constexpr size_t kFirstFrameBodySteps = 4;
inline constexpr size_t kFirstFrameMinFrames = 8;

struct FirstFrameCheck {
  double median_step = 0;  // m
  size_t body_start = 1;   // b
  double first_jump = 0;   // FramePoseDistance(0, b)
  bool discontinuous = false;
};

// The check above. A take with fewer than kFirstFrameMinFrames frames is never discontinuous:
// a few steps do not tell what is typical.
FirstFrameCheck CheckFirstFrame(const Take& take);

// Removes frame 0 (rotations and root position). No-op on an empty take.
void DropFirstFrame(Take* take);

}  // namespace motif
