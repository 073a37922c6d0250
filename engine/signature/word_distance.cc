#include "engine/signature/word_distance.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/status.h"
#include "engine/distance/pose_features.h"
#include "engine/signature/word_grid.h"

namespace motif {

WordDistance::WordDistance(std::vector<float> weights, uint32_t word_frames, uint32_t band_frames)
    : weights_(std::move(weights)), word_frames_(word_frames), band_frames_(band_frames) {
  MOTIF_CHECK(!weights_.empty());
  MOTIF_CHECK(word_frames_ >= 1 && word_frames_ <= kMaxWordFrames);
}

float WordDistance::FrameDistance(const int16_t* a, const int16_t* b) const {
  // PoseDistance's loop (pose_features.cc), operation for operation.
  float total = 0;
  const uint32_t joint_count = static_cast<uint32_t>(weights_.size());
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    total += weights_[joint_idx] * JointTerm(a, b, joint_idx);
  }
  return total;
}

double WordDistance::LockStep(const int16_t* a, const int16_t* b) const {
  const size_t values = feature_values();
  double sum = 0;
  for (uint32_t frame = 0; frame < word_frames_; ++frame) {
    sum += FrameDistance(a + frame * values, b + frame * values);
  }
  return sum;
}

namespace {

constexpr uint32_t kLanes = 4;  // cells are computed in aligned runs of this many columns

// The DTW fills one row of cells at a time: frame a_i against a run of consecutive frames of b.
// So a prepared word also holds its frames as structure-of-arrays (per weighted joint, five runs
// of padded floats over the frames: w, x, y, z and |q|^2), and a run of columns is a loop over
// contiguous floats that the compiler vectorises (sqrt stays the exact instruction). Each column
// performs JointTerm's operations in JointTerm's order with the joints in PoseDistance's order,
// so a cell is FrameDistance() bit for bit (the tests compare them); only the columns, not the
// joints, run side by side.
//
// out[col] = D(a frame, b frame col) for col in [first, end): `a` is one frame of a prepared
// word's rows, `b` a prepared word's columns.
void CellRun(const float* __restrict a, const float* __restrict b, size_t padded,
             const float* __restrict weights, uint32_t joints, size_t first, size_t end,
             float* __restrict out) {
  // size_t indices and one pointer per component: the loads are contiguous in `col`, which the
  // vectoriser must be able to prove (32-bit index arithmetic could wrap).
  for (size_t col = first; col < end; ++col) out[col] = 0;
  for (uint32_t joint = 0; joint < joints; ++joint) {
    const float* __restrict q = a + 5 * static_cast<size_t>(joint);
    const float* __restrict w = b + static_cast<size_t>(joint) * 5 * padded;
    const float* __restrict x = w + padded;
    const float* __restrict y = x + padded;
    const float* __restrict z = y + padded;
    const float* __restrict norm = z + padded;
    const float qw = q[0];
    const float qx = q[1];
    const float qy = q[2];
    const float qz = q[3];
    const float q_norm = q[4];
    const float weight = weights[joint];
    // Runs are whole, aligned groups of kLanes columns: a fixed-width body the compiler maps
    // onto one SIMD register per group, with no remainder loop.
    for (size_t group = first; group < end; group += kLanes) {
      for (size_t col = group; col < group + kLanes; ++col) {
        float dot = 0;
        dot += qw * w[col];
        dot += qx * x[col];
        dot += qy * y[col];
        dot += qz * z[col];
        out[col] += weight * JointTermFromSums<ScalarLanes>(q_norm, norm[col], dot);
      }
    }
  }
}

}  // namespace

void WordDistance::Prepare(const int16_t* word, PreparedWord* out) const {
  const uint32_t joints = static_cast<uint32_t>(weights_.size());
  const uint32_t frames = word_frames_;
  const uint32_t padded = (frames + kLanes - 1) / kLanes * kLanes;
  out->frames_ = frames;
  out->padded_frames_ = padded;
  out->rows_.resize(static_cast<size_t>(frames) * joints * 5);
  out->columns_.assign(static_cast<size_t>(padded) * joints * 5, 0.0f);
  const float inverse = 1.0f / PoseFeatures::kQuantScale;  // JointTerm's dequantisation
  float* rows = out->rows_.data();
  float* columns = out->columns_.data();
  for (uint32_t frame = 0; frame < frames; ++frame) {
    for (uint32_t joint = 0; joint < joints; ++joint) {
      const int16_t* in = word + (static_cast<size_t>(frame) * joints + joint) * 4;
      float* row = rows + (static_cast<size_t>(frame) * joints + joint) * 5;
      float* column = columns + static_cast<size_t>(joint) * 5 * padded + frame;
      float norm = 0;
      for (uint32_t component = 0; component < 4; ++component) {
        const float value = in[component] * inverse;
        row[component] = value;
        column[component * padded] = value;
        norm += value * value;
      }
      row[4] = norm;
      column[4 * padded] = norm;
    }
  }
}

double WordDistance::Dtw(const int16_t* a, const int16_t* b, double threshold) const {
  thread_local PreparedWord prepared_a;
  thread_local PreparedWord prepared_b;
  Prepare(a, &prepared_a);
  Prepare(b, &prepared_b);
  return Dtw(prepared_a, prepared_b, threshold);
}

double WordDistance::Dtw(const PreparedWord& a, const PreparedWord& b, double threshold) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  MOTIF_CHECK(a.frames_ == word_frames_ && b.frames_ == word_frames_);
  const uint32_t joints = static_cast<uint32_t>(weights_.size());
  const uint32_t n = word_frames_;
  const uint32_t last = n - 1;
  const uint32_t band = std::min(band_frames_, last);
  const uint32_t padded = b.padded_frames_;
  alignas(64) float cells[kMaxWordFrames];
  const float* weights = weights_.data();
  // Fills cells[col] for col in [low, high] (and its neighbours up to whole runs of kLanes).
  auto fill_row = [&](uint32_t row, uint32_t low, uint32_t high) {
    const uint32_t first = low / kLanes * kLanes;
    const uint32_t end = std::min(padded, (high / kLanes + 1) * kLanes);
    CellRun(a.rows_.data() + static_cast<size_t>(row) * 5 * joints, b.columns_.data(), padded,
            weights, joints, first, end, cells);
  };

  if (n == 1) {
    fill_row(0, 0, 0);
    return cells[0];
  }
  // Both corner cells lie on every path: their sum bounds the result from below for free.
  fill_row(last, last, last);
  const double last_cell = cells[last];
  fill_row(0, 0, band);
  const double first_cell = cells[0];
  if (first_cell + last_cell > threshold) return kInfinity;

  double rows[2][kMaxWordFrames];
  double* previous = rows[0];
  double* current = rows[1];
  // Row 0: only moves to the right.
  uint32_t previous_low = 0;
  uint32_t previous_high = band;
  previous[0] = first_cell;
  double row_min = first_cell;
  for (uint32_t col = 1; col <= previous_high; ++col) {
    previous[col] = previous[col - 1] + cells[col];
    row_min = std::min(row_min, previous[col]);
  }
  if (row_min > threshold) return kInfinity;

  for (uint32_t row = 1; row <= last; ++row) {
    const uint32_t low = row > band ? row - band : 0;
    const uint32_t high = std::min(last, row + band);
    fill_row(row, low, high);
    row_min = kInfinity;
    for (uint32_t col = low; col <= high; ++col) {
      double best = kInfinity;
      if (col <= previous_high) best = previous[col];                    // from above
      if (col > previous_low) best = std::min(best, previous[col - 1]);  // diagonal
      if (col > low) best = std::min(best, current[col - 1]);            // from the left
      current[col] = static_cast<double>(cells[col]) + best;
      row_min = std::min(row_min, current[col]);
    }
    // Every path crosses this row and C only grows along a path.
    if (row_min > threshold) return kInfinity;
    std::swap(previous, current);
    previous_low = low;
    previous_high = high;
  }
  return previous[last];
}

}  // namespace motif
