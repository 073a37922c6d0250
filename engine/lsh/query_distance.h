// QueryDistance: the exact pose distance D (engine/distance/pose_features.h) from one query frame
// to any number of other frames, the verification step of every LSH candidate. The query's
// dequantised quaternions and norms are prepared once. To() processes four joints of one frame
// per SSE2 instruction; ToBatch() processes eight frames at once, one per AVX2 lane, on CPUs that
// have AVX2 (chosen at run time; query_distance_avx2.cc is the only file built with -mavx2).
// Both use the same IEEE single-precision operations, in the same order per joint, as
// PoseDistance, and sum the joints in the same order, so every result is bit-identical to
// PoseDistance(features, query, frame) (LshQueryDistance.BitIdenticalToPoseDistance). The
// engine/lsh library is built with -ffp-contract=off so that no multiply-add is fused here or
// there. Thread-safety: one QueryDistance per thread (it holds the query); `features` is shared.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/distance/pose_features.h"

namespace motif {

class QueryDistance {
 public:
  explicit QueryDistance(const PoseFeatures& features);

  void SetQuery(uint64_t query_frame);
  uint64_t query() const { return query_; }

  // D(query, frame).
  float To(uint64_t frame) const { return To(frame, INFINITY); }
  // D(query, frame) if it is <= limit; otherwise some value > limit (the joints are summed in
  // order and the sum is left as soon as it exceeds `limit`: a partial sum of non-negative terms
  // only grows, so the candidate could not be within `limit`).
  float To(uint64_t frame, float limit) const;

  // out[i] = To(frames[i], limit) for i < count (eight at a time where AVX2 is available).
  void ToBatch(const uint32_t* frames, uint32_t count, float limit, float* out) const;

  // Whether ToBatch uses the AVX2 path.
  bool batch_avx2() const { return batch_avx2_; }

  // Hints the cache that To(frame) will be called soon.
  void Prefetch(uint64_t frame) const {
    const char* address = reinterpret_cast<const char*>(features_.frame(frame));
    __builtin_prefetch(address);
    __builtin_prefetch(address + 64);
  }

 private:
  const PoseFeatures& features_;
  uint32_t joint_count_ = 0;
  uint32_t group_count_ = 0;  // groups of four joints
  uint64_t query_ = 0;
  // Per group of four joints, 4 components x 4 lanes (joint in lane) of the query's dequantised
  // quaternions, then 4 lanes of |q|^2, then 4 lanes of weights: 24 floats per group.
  std::vector<float> query_lanes_;
  // Per joint: w, x, y, z (dequantised), |q|^2, weight (the AVX2 batch path).
  std::vector<float> query_joints_;
  bool batch_avx2_ = false;
};

}  // namespace motif
