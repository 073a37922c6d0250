// Internal to QueryDistance (query_distance.cc): the AVX2 batch path, eight candidates at once,
// one per lane. Built only on x86-64, in its own translation unit compiled with -mavx2 (and no
// FMA contraction), and called only on CPUs that have AVX2. Plain data in.
#pragma once

#include <cstdint>

namespace motif::lsh_internal {

struct BatchArgs {
  const int16_t* const* candidates = nullptr;  // 8 frames' quantised quaternions (4 J int16)
  uint32_t joint_count = 0;
  const float* query = nullptr;  // per joint: w, x, y, z (dequantised), |q|^2, weight
  float limit = 0;               // may stop once every lane's partial sum exceeds it
  float* out = nullptr;          // 8 results, in candidate order
};

// out[i] = D(query, candidate i) bit for bit as PoseDistance computes it, or a value above
// `limit` (a partial sum) when the distance exceeds it.
void DistanceBatch8Avx2(const BatchArgs& args);

}  // namespace motif::lsh_internal
