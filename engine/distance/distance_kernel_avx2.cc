// The block kernel's AVX2 path (x86-64 only): this file alone is compiled with -mavx2 and its
// code runs only after DistanceKernel has checked that the CPU has AVX2 (runtime dispatch, so
// the library stays portable). It deliberately uses nothing but plain pointers and the
// always-inline intrinsics (and JointTermFromSums<AvxLanes>, which no portable file
// instantiates): an inline function of a template library (Eigen, the standard
// library) instantiated here would be an AVX2 copy that the linker could pick for the
// portable callers too.
//
// Per lane it performs PoseDistance's operations in PoseDistance's order (see
// distance_kernel.h), two 8-lane registers per 16-frame tile.
#include "engine/distance/distance_kernel_avx2.h"

#include <immintrin.h>

#include "engine/distance/joint_term.h"

namespace motif::distance_internal {
namespace {

constexpr uint32_t kTile = 16;
constexpr uint32_t kJointFloats = 5 * kTile;

}  // namespace

void ComputeRowsAvx2(const KernelArgs& args) {
  const __m256 zero = _mm256_setzero_ps();
  const uint32_t candidate_tiles = (args.candidate_count + kTile - 1) / kTile;
  for (uint32_t tile_idx = 0; tile_idx < candidate_tiles; ++tile_idx) {
    const float* candidate_tile = args.candidate_tiles + tile_idx * args.tile_floats;
    const uint32_t first_candidate = tile_idx * kTile;
    const uint32_t remaining = args.candidate_count - first_candidate;
    const uint32_t lanes = remaining < kTile ? remaining : kTile;
    for (uint32_t query_idx = 0; query_idx < args.query_count; ++query_idx) {
      const uint32_t query = args.first_query + query_idx;
      const float* query_tile =
          args.query_tiles + (query / kTile) * args.tile_floats + query % kTile;
      __m256 total_low = zero;
      __m256 total_high = zero;
      for (uint32_t joint_idx = 0; joint_idx < args.joint_count; ++joint_idx) {
        const float* q = query_tile + joint_idx * kJointFloats;
        const float* rows = candidate_tile + joint_idx * kJointFloats;
        const __m256 qw = _mm256_set1_ps(q[0]);
        const __m256 qx = _mm256_set1_ps(q[kTile]);
        const __m256 qy = _mm256_set1_ps(q[2 * kTile]);
        const __m256 qz = _mm256_set1_ps(q[3 * kTile]);
        const __m256 q_norm = _mm256_set1_ps(q[4 * kTile]);
        const __m256 weight = _mm256_set1_ps(args.weights[joint_idx]);
        for (int half = 0; half < 2; ++half) {
          const float* lane_rows = rows + 8 * half;
          __m256 dot = _mm256_mul_ps(_mm256_load_ps(lane_rows), qw);
          dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_load_ps(lane_rows + kTile), qx));
          dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_load_ps(lane_rows + 2 * kTile), qy));
          dot = _mm256_add_ps(dot, _mm256_mul_ps(_mm256_load_ps(lane_rows + 3 * kTile), qz));
          const __m256 root =
              JointTermFromSums<AvxLanes>(q_norm, _mm256_load_ps(lane_rows + 4 * kTile), dot);
          const __m256 term = _mm256_mul_ps(weight, root);
          if (half == 0) {
            total_low = _mm256_add_ps(total_low, term);
          } else {
            total_high = _mm256_add_ps(total_high, term);
          }
        }
      }
      float* row = args.out + static_cast<size_t>(query_idx) * args.out_stride + first_candidate;
      if (lanes == kTile) {
        _mm256_storeu_ps(row, total_low);
        _mm256_storeu_ps(row + 8, total_high);
      } else {
        alignas(32) float distances[kTile];
        _mm256_store_ps(distances, total_low);
        _mm256_store_ps(distances + 8, total_high);
        for (uint32_t lane = 0; lane < lanes; ++lane) row[lane] = distances[lane];
      }
    }
  }
}

}  // namespace motif::distance_internal
