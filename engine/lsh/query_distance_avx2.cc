#include "engine/lsh/query_distance_avx2.h"

#include <immintrin.h>

#include "engine/distance/joint_term.h"

namespace motif::lsh_internal {

// Lanes hold candidates in the order [0 2 4 6 | 1 3 5 7] (a 4x4 transpose inside each 128-bit
// half); every lane runs the operations of PoseDistance for its candidate, in the same order:
// per joint the dot product and |b|^2 summed w, x, y, z, then JointTermFromSums, times the weight,
// added to the lane's total joint by joint. No operation mixes lanes, so each lane's result is
// PoseDistance's, bit for bit.
void DistanceBatch8Avx2(const BatchArgs& args) {
  constexpr float kInverse = 1.0f / 32767.0f;  // PoseFeatures::kQuantScale
  const __m256 scale = _mm256_set1_ps(kInverse);
  const __m256 limit = _mm256_set1_ps(args.limit);
  const int16_t* const* c = args.candidates;
  __m256 total = _mm256_setzero_ps();
  for (uint32_t joint_idx = 0; joint_idx < args.joint_count; ++joint_idx) {
    const uint32_t offset = 4 * joint_idx;
    auto pair = [&](int first, int second) {
      const __m128i both =
          _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(c[first] + offset)),
                             _mm_loadl_epi64(reinterpret_cast<const __m128i*>(c[second] + offset)));
      return _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_cvtepi16_epi32(both)), scale);
    };
    // [c0 w x y z | c1 w x y z], [c2 | c3], [c4 | c5], [c6 | c7]
    const __m256 r0 = pair(0, 1);
    const __m256 r1 = pair(2, 3);
    const __m256 r2 = pair(4, 5);
    const __m256 r3 = pair(6, 7);
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1);  // c0w c2w c0x c2x | c1w c3w c1x c3x
    const __m256 t1 = _mm256_unpackhi_ps(r0, r1);  // c0y c2y c0z c2z | c1y c3y c1z c3z
    const __m256 t2 = _mm256_unpacklo_ps(r2, r3);
    const __m256 t3 = _mm256_unpackhi_ps(r2, r3);
    const __m256 w = _mm256_shuffle_ps(t0, t2, 0x44);  // c0 c2 c4 c6 | c1 c3 c5 c7
    const __m256 x = _mm256_shuffle_ps(t0, t2, 0xEE);
    const __m256 y = _mm256_shuffle_ps(t1, t3, 0x44);
    const __m256 z = _mm256_shuffle_ps(t1, t3, 0xEE);
    const float* q = args.query + 6 * joint_idx;
    __m256 dot = _mm256_mul_ps(_mm256_set1_ps(q[0]), w);
    dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_set1_ps(q[1]), x));
    dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_set1_ps(q[2]), y));
    dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_set1_ps(q[3]), z));
    __m256 norm = _mm256_mul_ps(w, w);
    norm = _mm256_add_ps(norm, _mm256_mul_ps(x, x));
    norm = _mm256_add_ps(norm, _mm256_mul_ps(y, y));
    norm = _mm256_add_ps(norm, _mm256_mul_ps(z, z));
    const __m256 root = JointTermFromSums<AvxLanes>(_mm256_set1_ps(q[4]), norm, dot);
    total = _mm256_add_ps(total, _mm256_mul_ps(_mm256_set1_ps(q[5]), root));
    // Every lane already beyond the limit: none can enter; their partial sums say so.
    if ((joint_idx & 3) == 3 &&
        _mm256_movemask_ps(_mm256_cmp_ps(total, limit, _CMP_GT_OQ)) == 0xFF) {
      break;
    }
  }
  alignas(32) float lanes[8];
  _mm256_store_ps(lanes, total);
  static constexpr int kCandidateOfLane[8] = {0, 2, 4, 6, 1, 3, 5, 7};
  for (int lane = 0; lane < 8; ++lane) args.out[kCandidateOfLane[lane]] = lanes[lane];
}

}  // namespace motif::lsh_internal
