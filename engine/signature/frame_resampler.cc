#include "engine/signature/frame_resampler.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/distance/pose_features.h"

namespace motif {
namespace {

// PoseFeatures' quantisation (pose_features.cc), in the same float operations, so the features of
// a row are the bytes PoseFeatures::FromRows would store for it.
int16_t Quantise(float value) {
  const float scaled = std::round(std::clamp(value, -1.0f, 1.0f) * PoseFeatures::kQuantScale);
  return static_cast<int16_t>(scaled);
}

float Lerp(float a, float b, double alpha) {
  if (alpha == 0) return a;
  return static_cast<float>((1.0 - alpha) * a + alpha * b);
}

}  // namespace

void SlerpQuaternion(const float* a, const float* b, double alpha, float* out) {
  if (alpha == 0) {
    std::copy(a, a + 4, out);
    return;
  }
  double qa[4];
  double qb[4];
  double dot = 0;
  for (int component = 0; component < 4; ++component) {
    qa[component] = a[component];
    qb[component] = b[component];
    dot += qa[component] * qb[component];
  }
  if (dot < 0) {  // q and -q are one rotation: take the one on a's side (the shorter arc)
    for (double& value : qb) value = -value;
  }
  // The angle between the two 4-vectors, from the chord lengths: accurate for tiny angles, where
  // acos(dot) loses half of its digits.
  double minus = 0;
  double plus = 0;
  for (int component = 0; component < 4; ++component) {
    minus += (qa[component] - qb[component]) * (qa[component] - qb[component]);
    plus += (qa[component] + qb[component]) * (qa[component] + qb[component]);
  }
  const double angle = 2.0 * std::atan2(std::sqrt(minus), std::sqrt(plus));
  double weight_a = 1.0 - alpha;
  double weight_b = alpha;
  if (angle > 1e-12) {
    const double sine = std::sin(angle);
    weight_a = std::sin((1.0 - alpha) * angle) / sine;
    weight_b = std::sin(alpha * angle) / sine;
  }
  for (int component = 0; component < 4; ++component) {
    out[component] = static_cast<float>(weight_a * qa[component] + weight_b * qb[component]);
  }
}

Result<FrameResampler> FrameResampler::Create(FrameLayout layout,
                                              const std::vector<float>& joint_weights) {
  if (joint_weights.size() != layout.joint_count) {
    return Status::InvalidArgument("motion words: " + std::to_string(joint_weights.size()) +
                                   " joint weights for " + std::to_string(layout.joint_count) +
                                   " joints");
  }
  FrameResampler resampler;
  resampler.layout_ = layout;
  for (uint32_t joint_idx = 0; joint_idx < layout.joint_count; ++joint_idx) {
    const float weight = joint_weights[joint_idx];
    if (!std::isfinite(weight) || weight < 0) {
      return Status::InvalidArgument("motion words: joint " + std::to_string(joint_idx) +
                                     " has weight " + std::to_string(weight) +
                                     "; weights must be finite and non-negative");
    }
    if (weight > 0) {
      resampler.joints_.push_back(joint_idx);
      resampler.weights_.push_back(weight);
    }
  }
  if (resampler.joints_.empty()) {
    return Status::InvalidArgument("motion words: no joint has a positive weight");
  }
  return resampler;
}

void FrameResampler::InterpolateRow(const float* a, const float* b, double alpha,
                                    float* out) const {
  for (uint32_t joint_idx = 0; joint_idx < layout_.joint_count; ++joint_idx) {
    const size_t offset = layout_.quaternion_offset(joint_idx);
    SlerpQuaternion(a + offset, b + offset, alpha, out + offset);
  }
  for (size_t value_idx = layout_.height_offset(); value_idx < layout_.stride(); ++value_idx) {
    out[value_idx] = Lerp(a[value_idx], b[value_idx], alpha);
  }
}

void FrameResampler::InterpolateFeatures(const float* a, const float* b, double alpha,
                                         int16_t* out) const {
  float q[4];
  for (uint32_t joint : joints_) {
    const size_t offset = layout_.quaternion_offset(joint);
    SlerpQuaternion(a + offset, b + offset, alpha, q);
    for (int component = 0; component < 4; ++component) *out++ = Quantise(q[component]);
  }
}

void FrameResampler::RowFeatures(const float* row, int16_t* out) const {
  for (uint32_t joint : joints_) {
    const float* q = row + layout_.quaternion_offset(joint);
    for (int component = 0; component < 4; ++component) *out++ = Quantise(q[component]);
  }
}

}  // namespace motif
