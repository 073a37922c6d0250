// The one definition of a joint's term in the pose distance D, shared by every kernel that
// evaluates D: the scalar JointTerm (PoseDistance), the LSH verification (SSE and AVX2), the
// trellis block kernel (Eigen and AVX2) and the motion-word DTW. Each kernel gathers the three
// sums of a joint its own way (lanes of candidates, of frames, of columns), always summing the
// components w, x, y, z in that order; the term itself is this function, so the kernels agree
// with PoseDistance bit for bit (the kernels' BitIdentical tests check it).
//
//   term = sqrt(max(0, (|q|^2 + |p|^2) - 2|q.p|))   which equals min(|q - p|, |q + p|)
//
// `Lanes` names a lane type and its three lane-wise operations: Abs, AtLeastZero (0 when the
// value is not above 0, NaN included, as std::max(0.0f, v) does) and Sqrt (correctly rounded,
// as std::sqrt is). The lane type must have + and -. Lane types of SIMD registers are named by
// a struct, never passed as template arguments themselves (that drops their attributes).
#pragma once

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace motif {

template <class Lanes>
inline typename Lanes::Lane JointTermFromSums(typename Lanes::Lane norm_q,
                                              typename Lanes::Lane norm_p,
                                              typename Lanes::Lane dot) {
  const typename Lanes::Lane abs_dot = Lanes::Abs(dot);
  // abs_dot + abs_dot is 2|q.p| exactly (doubling never rounds), with no multiply to fuse.
  return Lanes::Sqrt(Lanes::AtLeastZero((norm_q + norm_p) - (abs_dot + abs_dot)));
}

struct ScalarLanes {
  using Lane = float;
  static float Abs(float value) { return std::abs(value); }
  static float AtLeastZero(float value) { return std::max(0.0f, value); }
  static float Sqrt(float value) { return std::sqrt(value); }
};

#if defined(__SSE2__)
struct SseLanes {
  using Lane = __m128;
  static __m128 Abs(__m128 value) {
    return _mm_and_ps(value, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)));
  }
  // maxps returns its second operand when the two compare equal or unordered: 0 for NaN.
  static __m128 AtLeastZero(__m128 value) { return _mm_max_ps(value, _mm_setzero_ps()); }
  static __m128 Sqrt(__m128 value) { return _mm_sqrt_ps(value); }
};
#endif

#if defined(__AVX__)
struct AvxLanes {
  using Lane = __m256;
  static __m256 Abs(__m256 value) {
    return _mm256_and_ps(value, _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff)));
  }
  static __m256 AtLeastZero(__m256 value) { return _mm256_max_ps(value, _mm256_setzero_ps()); }
  static __m256 Sqrt(__m256 value) { return _mm256_sqrt_ps(value); }
};
#endif

}  // namespace motif
