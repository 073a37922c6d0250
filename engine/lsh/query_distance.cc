#include "engine/lsh/query_distance.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "engine/distance/joint_term.h"

#if defined(MOTIF_LSH_AVX2)
#include "engine/lsh/query_distance_avx2.h"
#endif

namespace motif {

QueryDistance::QueryDistance(const PoseFeatures& features)
    : features_(features),
      joint_count_(features.weighted_joint_count()),
      group_count_(features.weighted_joint_count() / 4),
      query_lanes_(static_cast<size_t>(features.weighted_joint_count() / 4) * 24 + 4),
      query_joints_(static_cast<size_t>(features.weighted_joint_count()) * 6) {
#if defined(MOTIF_LSH_AVX2)
  batch_avx2_ = __builtin_cpu_supports("avx2");
#endif
}

void QueryDistance::SetQuery(uint64_t query_frame) {
  query_ = query_frame;
  const int16_t* query = features_.frame(query_frame);
  const float inverse = 1.0f / PoseFeatures::kQuantScale;
  for (uint32_t joint_idx = 0; joint_idx < joint_count_; ++joint_idx) {
    float* joint = &query_joints_[6 * joint_idx];
    float norm = 0;
    for (int component = 0; component < 4; ++component) {
      const float value = query[4 * joint_idx + component] * inverse;
      joint[component] = value;
      norm += value * value;  // the same sum, in the same order, as PoseDistance
    }
    joint[4] = norm;
    joint[5] = features_.weights()[joint_idx];
  }
  for (uint32_t group_idx = 0; group_idx < group_count_; ++group_idx) {
    float* lanes = &query_lanes_[group_idx * 24];
    for (uint32_t lane = 0; lane < 4; ++lane) {
      const uint32_t joint_idx = 4 * group_idx + lane;
      float norm = 0;
      for (int component = 0; component < 4; ++component) {
        const float value = query[4 * joint_idx + component] * inverse;
        lanes[4 * component + lane] = value;
        norm += value * value;  // the same sum, in the same order, as PoseDistance
      }
      lanes[16 + lane] = norm;
      lanes[20 + lane] = features_.weights()[joint_idx];
    }
  }
}

float QueryDistance::To(uint64_t frame, float limit) const {
  const int16_t* a = features_.frame(query_);
  const int16_t* b = features_.frame(frame);
  const float inverse = 1.0f / PoseFeatures::kQuantScale;
  float total = 0;
  uint32_t joint_idx = 0;
#if defined(__SSE2__)
  const __m128 scale = _mm_set1_ps(inverse);
  for (uint32_t group_idx = 0; group_idx < group_count_; ++group_idx, joint_idx += 4) {
    // 16 int16: joints j..j+3, each (w, x, y, z). Sign-extend to int32, convert, scale.
    const __m128i low = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + 4 * joint_idx));
    const __m128i high = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + 4 * joint_idx + 8));
    __m128 joint0 =
        _mm_mul_ps(_mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(low, low), 16)), scale);
    __m128 joint1 =
        _mm_mul_ps(_mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpackhi_epi16(low, low), 16)), scale);
    __m128 joint2 =
        _mm_mul_ps(_mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(high, high), 16)), scale);
    __m128 joint3 =
        _mm_mul_ps(_mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpackhi_epi16(high, high), 16)), scale);
    _MM_TRANSPOSE4_PS(joint0, joint1, joint2, joint3);  // now component-major: w, x, y, z lanes
    const float* lanes = &query_lanes_[group_idx * 24];
    const __m128 qw = _mm_loadu_ps(lanes);
    const __m128 qx = _mm_loadu_ps(lanes + 4);
    const __m128 qy = _mm_loadu_ps(lanes + 8);
    const __m128 qz = _mm_loadu_ps(lanes + 12);
    // dot and |b|^2 accumulated w, x, y, z in order, as the scalar loop does
    __m128 dot = _mm_mul_ps(qw, joint0);
    dot = _mm_add_ps(dot, _mm_mul_ps(qx, joint1));
    dot = _mm_add_ps(dot, _mm_mul_ps(qy, joint2));
    dot = _mm_add_ps(dot, _mm_mul_ps(qz, joint3));
    __m128 norm = _mm_mul_ps(joint0, joint0);
    norm = _mm_add_ps(norm, _mm_mul_ps(joint1, joint1));
    norm = _mm_add_ps(norm, _mm_mul_ps(joint2, joint2));
    norm = _mm_add_ps(norm, _mm_mul_ps(joint3, joint3));
    const __m128 root = JointTermFromSums<SseLanes>(_mm_loadu_ps(lanes + 16), norm, dot);
    const __m128 weighted = _mm_mul_ps(_mm_loadu_ps(lanes + 20), root);
    alignas(16) float joint_terms[4];
    _mm_store_ps(joint_terms, weighted);
    total += joint_terms[0];
    total += joint_terms[1];
    total += joint_terms[2];
    total += joint_terms[3];
    if (total > limit) return total;
  }
#endif
  for (; joint_idx < joint_count_; ++joint_idx) {
    total += features_.weights()[joint_idx] * JointTerm(a, b, joint_idx);
  }
  return total;
}

void QueryDistance::ToBatch(const uint32_t* frames, uint32_t count, float limit, float* out) const {
  uint32_t done = 0;
#if defined(MOTIF_LSH_AVX2)
  if (batch_avx2_) {
    const int16_t* candidates[8];
    lsh_internal::BatchArgs args;
    args.candidates = candidates;
    args.joint_count = joint_count_;
    args.query = query_joints_.data();
    args.limit = limit;
    for (; done + 8 <= count; done += 8) {
      for (int idx = 0; idx < 8; ++idx) candidates[idx] = features_.frame(frames[done + idx]);
      args.out = out + done;
      lsh_internal::DistanceBatch8Avx2(args);
    }
  }
#endif
  for (; done < count; ++done) out[done] = To(frames[done], limit);
}

}  // namespace motif
