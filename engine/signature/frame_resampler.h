// FrameResampler: makes one frame of a motion word from the two archive frames around its time
// (word_grid.h says which two and at what fraction alpha), and reduces it to what the word
// distance needs.
//
// Interpolation of an archive row (FrameLayout: J quaternions, height, velocity x z, heading):
//  * each joint's quaternion by slerp along the shortest arc: when a.b < 0, b is replaced by -b
//    (the same rotation) before interpolating, so the path never takes the long way round;
//    computed in double, written as float. alpha = 0 copies a, bit for bit.
//  * the root's height, horizontal velocity and heading linearly (the heading is unwrapped along
//    a clip, so a linear blend never jumps by 2 pi). The archive keeps no absolute root position:
//    height and velocity are what the row holds of it.
//
// Features: the per-frame representation of a word for distances is the trellis's (PoseFeatures,
// engine/distance/pose_features.h): the quaternions of the joints with a positive weight, in
// archive joint order, each component quantised to int16 (round(value * 32767)), so the word
// distance uses the trellis's JointTerm and its weights on exactly the numbers PoseFeatures would
// hold for the same rows. The sample's sign follows a's (a.slerp keeps a's hemisphere), so signs
// stay continuous along a clip as in the archive; the distance does not depend on them anyway.
// Thread-safety: immutable after construction; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "formats/motion/pose_frames.h"

namespace motif {

// out = slerp(a, b, alpha) for quaternions (w, x, y, z), shortest arc; alpha in [0, 1].
// alpha = 0 gives a exactly; a (nearly) zero angle falls back to a linear blend.
void SlerpQuaternion(const float* a, const float* b, double alpha, float* out);

class FrameResampler {
 public:
  FrameResampler() = default;
  // `joint_weights`: one weight per archive joint (the skeleton's defaults, or
  // LoadDistanceWeights); the joints with a positive weight make the features, as in
  // PoseFeatures. InvalidArgument: a weight count that is not layout.joint_count, a negative or
  // non-finite weight, no joint with a positive weight.
  static Result<FrameResampler> Create(FrameLayout layout, const std::vector<float>& joint_weights);

  FrameLayout layout() const { return layout_; }
  // The weighted joints (archive indices, ascending) and their weights.
  const std::vector<uint32_t>& joints() const { return joints_; }
  const std::vector<float>& weights() const { return weights_; }
  uint32_t weighted_joint_count() const { return static_cast<uint32_t>(joints_.size()); }
  // int16 values of one word frame: 4 per weighted joint (w, x, y, z).
  size_t feature_values() const { return 4 * joints_.size(); }

  // A whole row (layout().stride() floats) at alpha between rows a and b, as described above.
  void InterpolateRow(const float* a, const float* b, double alpha, float* out) const;
  // The features of that row (feature_values() int16), without computing the rest of it;
  // identical to InterpolateRow followed by RowFeatures.
  void InterpolateFeatures(const float* a, const float* b, double alpha, int16_t* out) const;
  // The features of one row: its weighted joints' quaternions quantised as PoseFeatures does.
  void RowFeatures(const float* row, int16_t* out) const;

 private:
  FrameLayout layout_;
  std::vector<uint32_t> joints_;
  std::vector<float> weights_;
};

}  // namespace motif
