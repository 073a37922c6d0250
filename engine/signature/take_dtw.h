// Dynamic time warping between whole takes over their frames: the baseline the motion signatures
// are compared with (Aristidou et al. 2018, section 6: "DTW over the raw frames"). Each take is
// its sequence of frames (every `step`-th frame of the archive; 1: every frame), the local cost
// the trellis's pose distance D (pose_features.h), no band (takes of very different lengths
// must still align), and the cost of the best monotone, continuous path from the first frames to
// the last is divided by n + m (the two lengths), the usual symmetric normalisation, so takes of
// different lengths are compared on one scale:
//
//   C(0, 0) = D(a_0, b_0)
//   C(i, j) = D(a_i, b_j) + min(C(i-1, j), C(i, j-1), C(i-1, j-1))
//   DTW(a, b) = C(n-1, m-1) / (n + m)
//
// The local costs come a block of 64 rows at a time from the distance kernel (distance_kernel.h,
// AVX2 where available; the same bits as PoseDistance); the recurrence keeps one row. Time
// O(n m) per pair, memory O(64 m).
// Thread-safety: pure functions; the matrix runs in its own task_arena over fixed rows (the
// result does not depend on the thread count).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/distance/pose_features.h"

namespace motif {

// A take: frames [first_frame, end_frame) of the archive.
struct TakeFrames {
  uint64_t first_frame = 0;
  uint64_t end_frame = 0;
};

// DTW between two takes (each at least one frame after subsampling). Precondition (checked):
// step >= 1, ranges inside `features`.
double TakeDtw(const PoseFeatures& features, const TakeFrames& a, const TakeFrames& b,
               uint32_t step);

// Every pair. InvalidArgument: step 0, an empty take or one outside the archive.
// `progress(done, total)` counts rows.
Result<Eigen::MatrixXd> TakeDtwMatrix(
    const PoseFeatures& features, const std::vector<TakeFrames>& takes, uint32_t step, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

}  // namespace motif
