// The input of the word embedding (embedding_net.h): what the network sees of a motion word.
//
// A word (word_grid.h: W frames at 24 Hz) is kept compactly as its features (frame_resampler.h:
// the weighted joints' quaternions, int16) and its root motion, 4 floats a frame:
//   height             the root's height (length units)
//   velocity x, z      the root's horizontal velocity in the heading frame (units per second)
//   turn rate          d heading / dt (radians per second), by forward differences between the
//                      word's frames, the last frame repeating the one before
// A time-warped copy played `speed` times as fast (time_warp.h) has its velocities multiplied by
// `speed` (its turn rate is so by construction), so a faster copy moves faster.
//
// The network input of a word is a W x C matrix, frame-major, C = 6 J_w + 4: for each weighted
// joint the first two columns of its rotation matrix (Zhou et al. 2019, "On the continuity of
// rotation representations": continuous, and the same for q and -q, which quaternion
// components are not), then the root motion. Standardisation per channel is the network's.
// Thread-safety: pure functions.
#pragma once

#include <cstddef>
#include <cstdint>

#include "formats/motion/pose_frames.h"

namespace motif {

inline constexpr uint32_t kRootMotionChannels = 4;
inline constexpr uint32_t kRotationChannels = 6;

// C: input channels for `weighted_joints` joints.
inline uint32_t WordInputChannels(uint32_t weighted_joints) {
  return kRotationChannels * weighted_joints + kRootMotionChannels;
}

// The root motion of a word from its W resampled rows (`layout` rows, frame-major) sampled at
// `word_fps`, played at `speed` (1 for the word itself): W x 4 floats into `out`.
void RootMotionFromRows(const FrameLayout& layout, const float* rows, uint32_t word_frames,
                        double word_fps, double speed, float* out);

// The W x C network input of a word from its features (W x 4 J_w int16) and root motion
// (W x 4 floats), into `out` (W x C floats).
void EncodeWordInput(const int16_t* features, const float* root_motion, uint32_t word_frames,
                     uint32_t weighted_joints, float* out);

}  // namespace motif
