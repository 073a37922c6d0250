#include "engine/embedding/word_input.h"

#include "engine/distance/pose_features.h"

namespace motif {

void RootMotionFromRows(const FrameLayout& layout, const float* rows, uint32_t word_frames,
                        double word_fps, double speed, float* out) {
  const size_t stride = layout.stride();
  for (uint32_t frame = 0; frame < word_frames; ++frame) {
    const float* row = rows + frame * stride;
    float* channels = out + frame * kRootMotionChannels;
    channels[0] = row[layout.height_offset()];
    channels[1] = static_cast<float>(row[layout.velocity_offset()] * speed);
    channels[2] = static_cast<float>(row[layout.velocity_offset() + 1] * speed);
    // Forward difference; the last frame repeats the one before (a one-frame word turns at 0).
    const uint32_t from = frame + 1 < word_frames ? frame : (frame > 0 ? frame - 1 : frame);
    const uint32_t to = from + 1 < word_frames ? from + 1 : from;
    channels[3] =
        static_cast<float>((static_cast<double>(rows[to * stride + layout.heading_offset()]) -
                            rows[from * stride + layout.heading_offset()]) *
                           word_fps);
  }
}

void EncodeWordInput(const int16_t* features, const float* root_motion, uint32_t word_frames,
                     uint32_t weighted_joints, float* out) {
  const float inverse = 1.0f / PoseFeatures::kQuantScale;
  const uint32_t channels = WordInputChannels(weighted_joints);
  for (uint32_t frame = 0; frame < word_frames; ++frame) {
    const int16_t* quaternions = features + frame * 4 * weighted_joints;
    float* row = out + frame * channels;
    for (uint32_t joint = 0; joint < weighted_joints; ++joint) {
      const float w = quaternions[4 * joint] * inverse;
      const float x = quaternions[4 * joint + 1] * inverse;
      const float y = quaternions[4 * joint + 2] * inverse;
      const float z = quaternions[4 * joint + 3] * inverse;
      // Quantised quaternions are unit to ~1e-4: divide by the squared norm so the matrix is a
      // rotation's. Columns 0 and 1 of R(q).
      const float norm2 = w * w + x * x + y * y + z * z;
      const float s = norm2 > 0 ? 2.0f / norm2 : 0.0f;
      float* out6 = row + kRotationChannels * joint;
      out6[0] = 1.0f - s * (y * y + z * z);
      out6[1] = s * (x * y + w * z);
      out6[2] = s * (x * z - w * y);
      out6[3] = s * (x * y - w * z);
      out6[4] = 1.0f - s * (x * x + z * z);
      out6[5] = s * (y * z + w * x);
    }
    const float* root = root_motion + frame * kRootMotionChannels;
    for (uint32_t channel = 0; channel < kRootMotionChannels; ++channel) {
      row[kRotationChannels * weighted_joints + channel] = root[channel];
    }
  }
}

}  // namespace motif
