// The distances the distance study compares (distance_study.cc; docs/design/motion_distance.md),
// built from one piece: a *column* distance (between two frames, two short windows or two motion
// words of one clip, as a trellis column would hold them), and a stretch distance made of it,
// either along the cheapest warp (the mean cell cost along the warping path, the rule of
// MeanWarpedDistance in engine/cluster/warped_similarity.h, which the clustering uses) or in
// lock step (the root mean square of the cell costs of the two stretches sampled at the same
// number of evenly spaced columns: the L2 distance of the concatenated column vectors, over the
// square root of their count).
//
//  * ColumnGrid: where a clip's columns sit, and which of them a stretch uses: on the frame
//    grid (a column every `spacing` frames), a stretch takes min(samples, its grid columns)
//    evenly spaced columns, first and last frame included (as the clustering samples an
//    instance); on the word grid (a word every word sample, 5 frames at 120 fps), a stretch
//    takes round(L / word_spacing) words (1 to samples), centred at (i + 1/2) L / m.
//  * ColumnDistance: d(a, b) between two columns, and ColumnMatrix: all of them for one clip,
//    so ranking thousands of stretches per query reads cells instead of computing them (the
//    study's timings are measured without the matrix, ColumnDistance::Distance directly).
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "bench/studies/body_frame_features.h"
#include "bench/studies/stretch_ranking.h"
#include "common/status.h"
#include "engine/distance/pose_features.h"
#include "engine/signature/word_distance.h"

namespace motif::testing {

struct ColumnGrid {
  enum class Kind { kFrames, kWords };
  Kind kind = Kind::kFrames;
  uint32_t count = 0;        // columns in the clip
  double first_centre = 0;   // clip frame of column 0
  double spacing = 1;        // clip frames between columns
  uint32_t samples = 32;     // most columns a stretch uses
  double word_spacing = 20;  // kWords: clip frames between a stretch's columns

  // The number of columns `span` uses by default.
  uint32_t DefaultCount(const Span& span) const;
  // `count` columns of `span`, as the header says (count 0: DefaultCount).
  std::vector<uint32_t> Columns(const Span& span, uint32_t count = 0) const;
  // The clip frame of column `column`.
  double Centre(uint32_t column) const { return first_centre + column * spacing; }
};

class ColumnDistance {
 public:
  virtual ~ColumnDistance() = default;
  virtual uint32_t count() const = 0;
  virtual float Distance(uint32_t a, uint32_t b) const = 0;
};

// The pose distance D (engine/distance/pose_features.h) between the frames of two columns of
// the frame grid; `first_frame` is the clip's first archive frame.
class QuatColumns : public ColumnDistance {
 public:
  QuatColumns(const PoseFeatures& features, uint64_t first_frame, const ColumnGrid& grid,
              uint64_t clip_frames);
  uint32_t count() const override { return static_cast<uint32_t>(frames_.size()); }
  float Distance(uint32_t a, uint32_t b) const override {
    return PoseDistance(*features_, frames_[a], frames_[b]);
  }

 private:
  const PoseFeatures* features_;
  std::vector<uint64_t> frames_;  // archive frame of each column
};

// A vector per column; d is the L2 distance, times sqrt(scale) (scale 1 / dims: the root mean
// square difference per value).
class VectorColumns : public ColumnDistance {
 public:
  VectorColumns(std::vector<float> values, uint32_t dims, double scale)
      : values_(std::move(values)), dims_(dims), scale_(static_cast<float>(scale)) {}
  uint32_t count() const override { return static_cast<uint32_t>(values_.size() / dims_); }
  uint32_t dims() const { return dims_; }
  const float* vector(uint32_t column) const { return &values_[size_t{column} * dims_]; }
  float Distance(uint32_t a, uint32_t b) const override {
    const float* x = vector(a);
    const float* y = vector(b);
    float sum = 0;
    for (uint32_t idx = 0; idx < dims_; ++idx) sum += (x[idx] - y[idx]) * (x[idx] - y[idx]);
    return std::sqrt(sum * scale_);
  }

 private:
  std::vector<float> values_;
  uint32_t dims_;
  float scale_;
};

// Frame-grid columns: `channels` of the body-frame features at each column's frame.
VectorColumns BodyColumns(const BodyFrameFeatures& body, const ChannelSet& channels,
                          const ColumnGrid& grid);

// Frame-grid columns: the window of `window_samples` frames `sample_frames` apart centred on
// each column's frame (clamped to the clip), each channel z-normalised over the window, its
// standard deviation taken as at least `floor` (as matrix-profile motif search does, with a floor
// so that a still channel is not blown up to unit variance).
VectorColumns ZNormalisedWindowColumns(const BodyFrameFeatures& body, const ChannelSet& channels,
                                       const ColumnGrid& grid, uint32_t window_samples,
                                       double sample_frames, double floor);

// Word-grid columns: the DTW between two motion words (engine/signature/word_distance.h, the
// distance `segment` compares words by), divided by the word's frames: a mean D per frame.
class WordDtwColumns : public ColumnDistance {
 public:
  WordDtwColumns(const WordDistance& distance, std::vector<PreparedWord> words)
      : distance_(&distance), words_(std::move(words)) {}
  uint32_t count() const override { return static_cast<uint32_t>(words_.size()); }
  float Distance(uint32_t a, uint32_t b) const override {
    return static_cast<float>(distance_->Dtw(words_[a], words_[b]) / distance_->word_frames());
  }

 private:
  const WordDistance* distance_;
  std::vector<PreparedWord> words_;
};

// All column distances of one clip (symmetric, n x n floats).
class ColumnMatrix {
 public:
  explicit ColumnMatrix(const ColumnDistance& distance);
  uint32_t count() const { return n_; }
  float at(uint32_t a, uint32_t b) const { return values_[size_t{a} * n_ + b]; }

 private:
  uint32_t n_ = 0;
  std::vector<float> values_;
};

// The mean cell cost along the cheapest warping path through an m x n grid of cells (steps
// (1,0), (0,1), (1,1); ties keep the diagonal, then the step from the row above: the rule of
// MeanWarpedDistance). m, n >= 1, n <= kMaxWarpColumns. With band >= 1, only cells within `band`
// columns of the straight line from (0, 0) to (m - 1, n - 1) (a Sakoe-Chiba band); band 0 (or
// negative): unconstrained, as the clustering warps.
inline constexpr uint32_t kMaxWarpColumns = 64;

template <class Cost>
double MeanWarp(uint32_t m, uint32_t n, const Cost& cost, int band = 0) {
  MOTIF_CHECK(n <= kMaxWarpColumns);
  constexpr double kInf = 1e300;
  double above[kMaxWarpColumns + 1];
  double here[kMaxWarpColumns + 1];
  uint32_t above_steps[kMaxWarpColumns + 1];
  uint32_t here_steps[kMaxWarpColumns + 1];
  above[0] = 0;
  above_steps[0] = 0;
  for (uint32_t j = 1; j <= n; ++j) above[j] = kInf, above_steps[j] = 0;
  const double slope = m > 1 ? static_cast<double>(n - 1) / (m - 1) : 0.0;
  for (uint32_t i = 1; i <= m; ++i) {
    here[0] = kInf;
    here_steps[0] = 0;
    const double centre = (i - 1) * slope;
    for (uint32_t j = 1; j <= n; ++j) {
      if (band > 0 && std::abs(static_cast<double>(j - 1) - centre) > band) {
        here[j] = kInf;
        here_steps[j] = 0;
        continue;
      }
      double best = above[j - 1];
      uint32_t steps = above_steps[j - 1];
      if (above[j] < best) best = above[j], steps = above_steps[j];
      if (here[j - 1] < best) best = here[j - 1], steps = here_steps[j - 1];
      here[j] = best + cost(i - 1, j - 1);
      here_steps[j] = steps + 1;
    }
    std::copy(here, here + n + 1, above);
    std::copy(here_steps, here_steps + n + 1, above_steps);
  }
  return above[n] / above_steps[n];
}

// The cells of that path, from (0, 0) to (m - 1, n - 1).
template <class Cost>
std::vector<std::pair<uint32_t, uint32_t>> WarpPath(uint32_t m, uint32_t n, const Cost& cost) {
  constexpr double kInf = 1e300;
  const size_t width = size_t{n} + 1;
  std::vector<double> total((size_t{m} + 1) * width, kInf);
  std::vector<uint8_t> from(total.size(), 0);  // 0 diagonal, 1 above, 2 left
  total[0] = 0;
  for (uint32_t i = 1; i <= m; ++i) {
    for (uint32_t j = 1; j <= n; ++j) {
      size_t best = (i - 1) * width + (j - 1);
      uint8_t step = 0;
      if (total[(i - 1) * width + j] < total[best]) best = (i - 1) * width + j, step = 1;
      if (total[i * width + j - 1] < total[best]) best = i * width + j - 1, step = 2;
      total[i * width + j] = total[best] + cost(i - 1, j - 1);
      from[i * width + j] = step;
    }
  }
  std::vector<std::pair<uint32_t, uint32_t>> path;
  uint32_t i = m;
  uint32_t j = n;
  while (i >= 1 && j >= 1) {
    path.push_back({i - 1, j - 1});
    const uint8_t step = from[i * width + j];
    if (step != 2) --i;
    if (step != 1) --j;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// The root mean square of cost(k, k) over k < m.
template <class Cost>
double LockStep(uint32_t m, const Cost& cost) {
  double sum = 0;
  for (uint32_t k = 0; k < m; ++k) {
    const double c = cost(k, k);
    sum += c * c;
  }
  return std::sqrt(sum / m);
}

// The matrix-profile distance between whole stretches: each stretch sampled at `samples` evenly
// spaced frames (first and last included: a uniform time scaling), each channel z-normalised
// over them (standard deviation at least `floor`), the vector's values in [channel][sample]
// order; d = the root mean square difference of two such vectors.
std::vector<float> ZNormalisedStretch(const BodyFrameFeatures& body, const ChannelSet& channels,
                                      const Span& span, uint32_t samples, double floor);
float RootMeanSquareDifference(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace motif::testing
