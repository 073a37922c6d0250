// WordDistance: the distance between two motion words that the paper's DTW positives come from
// (Aristidou et al. 2018, section 4.2: words similar "after DTW alignment" under a weighted
// joint-rotation distance), here the trellis's pose distance D (pose_features.h):
//
//   D(a_i, b_j) = sum_k w_k min(|q_ik - p_jk|, |q_ik + p_jk|)     (JointTerm, same bits)
//
// between frames of two words a, b of W frames each (frame_resampler.h features), aligned by
// dynamic time warping (Sakoe & Chiba 1978) with a Sakoe-Chiba band of radius r:
//
//   C(0, 0) = D(a_0, b_0)
//   C(i, j) = D(a_i, b_j) + min(C(i-1, j), C(i, j-1), C(i-1, j-1))   for |i - j| <= r
//   DTW(a, b) = C(W-1, W-1)
//
// i.e. the least total D along a monotone, continuous path from (0, 0) to (W-1, W-1) that never
// strays more than r frames from the diagonal. Not normalised by the path length, because:
//  * the plain sum is what the recurrence minimises; dividing the optimum by its own path's
//    length is not the optimum of the ratio, and the true least ratio (every path has W to
//    2W - 1 cells, whatever r >= 1) would favour long zig-zag paths through cheap cells;
//  * both words have W frames, so the sums of different pairs are on one scale already (divide
//    by W for a mean D per frame, comparable with the trellis's eps);
//  * it equals the lock-step sum sum_i D(a_i, b_i) when r = 0, and it only grows along a path,
//    which makes exact early abandoning possible.
// docs/design/signatures.md, "Word distance", gives the band choice: r = 2 at W = 16 absorbs the
// augmentation's speeds 0.8 - 1.25 and phase offsets of up to 2 frames (83 ms), and no more.
//
// Early abandoning, for nearest-word search: Dtw(a, b, threshold) stops as soon as a lower bound
// of the result exceeds the threshold and returns +infinity. The bounds: D(a_0, b_0) +
// D(a_{W-1}, b_{W-1}) (both cells are on every path), then after each row i the least C(i, j)
// of the row (every path crosses row i, and C only grows). So a result <= threshold is exact,
// identical to the unbounded call bit for bit; a result above it is either exact or +infinity.
// Cost: W (2r + 1) - r (r + 1) frame distances at most (74 at W = 16, r = 2), computed a row at a
// time over runs of 4 adjacent columns in SIMD lanes, each bit for bit FrameDistance(); two rows
// of W doubles on the stack. About 1.7 us per DTW at W = 16, r = 2 on prepared words, 3 us from
// raw features (docs/design/signatures.md, "Word distance").
// Thread-safety: immutable; const methods are safe from many threads (the raw-feature Dtw keeps
// per-thread scratch).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace motif {

// A word dequantised for the DTW (WordDistance::Prepare): its frames as floats in the two layouts
// the cell loop reads, so a word compared with many others (a nearest-word search) is converted
// once. Thread-safety: a value type.
class PreparedWord {
 public:
  uint32_t frames() const { return frames_; }

 private:
  friend class WordDistance;
  uint32_t frames_ = 0;
  uint32_t padded_frames_ = 0;  // frames rounded up to whole SIMD runs
  std::vector<float> rows_;     // per frame, per joint: w x y z |q|^2
  std::vector<float> columns_;  // per joint: 5 runs of padded_frames_ floats (w, x, y, z, |q|^2)
};

class WordDistance {
 public:
  static constexpr uint32_t kDefaultBandFrames = 2;

  // `weights`: one per weighted joint, in feature order (FrameResampler::weights()); words of
  // `word_frames` frames (1 to kMaxWordFrames); `band_frames` r (r >= W - 1: unconstrained).
  // Preconditions checked (abort): weights not empty, word_frames in range.
  WordDistance(std::vector<float> weights, uint32_t word_frames,
               uint32_t band_frames = kDefaultBandFrames);

  uint32_t word_frames() const { return word_frames_; }
  uint32_t band_frames() const { return band_frames_; }
  const std::vector<float>& weights() const { return weights_; }
  // int16 values per frame: 4 per weighted joint.
  size_t feature_values() const { return 4 * weights_.size(); }

  // D between two frames (feature_values() int16 each): PoseDistance's operations, so the same
  // bits as the trellis's D on the same features.
  float FrameDistance(const int16_t* a, const int16_t* b) const;
  // The lock-step sum: sum_i D(a_i, b_i), in double, i ascending (= DTW with r = 0).
  double LockStep(const int16_t* a, const int16_t* b) const;

  // DTW(a, b) as above; +infinity if abandoned because it exceeds `threshold`. Words of
  // word_frames() frames of feature_values() int16; both are prepared on each call (per-thread
  // scratch), which costs about as much as the DTW itself at W = 16: prepare words used more
  // than once.
  double Dtw(const int16_t* a, const int16_t* b,
             double threshold = std::numeric_limits<double>::infinity()) const;
  // Converts a word for the DTW below (`out` is reused: no allocation once it has the size).
  void Prepare(const int16_t* word, PreparedWord* out) const;
  // The same DTW on prepared words (prepared by a WordDistance with the same weights and word
  // length); the same bits as the other form.
  double Dtw(const PreparedWord& a, const PreparedWord& b,
             double threshold = std::numeric_limits<double>::infinity()) const;

 private:
  std::vector<float> weights_;
  uint32_t word_frames_ = 0;
  uint32_t band_frames_ = 0;
};

}  // namespace motif
