#include "engine/distance/distance_kernel.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/distance/distance_kernel_avx2.h"
#include "engine/distance/joint_term.h"

namespace motif {
namespace {

// sqrt, lane by lane, correctly rounded as std::sqrt is. Eigen's own packet sqrt is, by default
// (EIGEN_FAST_MATH), an approximate reciprocal square root and a Newton step, 1-2 bits off.
struct ExactSqrt {
  float operator()(float value) const { return std::sqrt(value); }
#if defined(EIGEN_VECTORIZE_AVX)
  Eigen::internal::Packet8f packetOp(const Eigen::internal::Packet8f& value) const {
    return _mm256_sqrt_ps(value);
  }
#endif
#if defined(EIGEN_VECTORIZE_SSE)
  Eigen::internal::Packet4f packetOp(const Eigen::internal::Packet4f& value) const {
    return _mm_sqrt_ps(value);
  }
#endif
};

}  // namespace
}  // namespace motif

template <>
struct Eigen::internal::functor_traits<motif::ExactSqrt> {
  enum {
    Cost = 8,
#if defined(EIGEN_VECTORIZE_SSE) || defined(EIGEN_VECTORIZE_AVX)
    PacketAccess = true,
#else
    PacketAccess = false,
#endif
  };
};

namespace motif {
namespace {

constexpr uint32_t kTile = FrameBlock::kTileFrames;
constexpr uint32_t kJointFloats = FrameBlock::kRowsPerJoint * kTile;

using Lanes = Eigen::Array<float, kTile, 1>;
using LanesMap = Eigen::Map<const Lanes, Eigen::AlignedMax>;

// JointTermFromSums's lane operations on a tile's lanes.
struct EigenLanes {
  using Lane = Lanes;
  static Lanes Abs(const Lanes& value) { return value.abs(); }
  static Lanes AtLeastZero(const Lanes& value) { return value.max(0.0f); }
  static Lanes Sqrt(const Lanes& value) { return value.unaryExpr(ExactSqrt()); }
};

// D of one query (lane `query_lane` of `query_tile`) against the kTile candidates of
// `candidate_tile`. Per lane the operations and their order are PoseDistance's: the dot product
// summed w, x, y, z; JointTermFromSums; times the weight; summed over the joints in order.
inline Lanes TileDistances(const float* query_tile, uint32_t query_lane,
                           const float* candidate_tile, const float* weights,
                           uint32_t joint_count) {
  Lanes total = Lanes::Zero();
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const float* query = query_tile + joint_idx * kJointFloats + query_lane;
    const float* rows = candidate_tile + joint_idx * kJointFloats;
    const float qw = query[0];
    const float qx = query[kTile];
    const float qy = query[2 * kTile];
    const float qz = query[3 * kTile];
    const float q_norm = query[4 * kTile];
    const Lanes dot = LanesMap(rows) * qw + LanesMap(rows + kTile) * qx +
                      LanesMap(rows + 2 * kTile) * qy + LanesMap(rows + 3 * kTile) * qz;
    total += weights[joint_idx] * JointTermFromSums<EigenLanes>(Lanes::Constant(q_norm),
                                                                LanesMap(rows + 4 * kTile), dot);
  }
  return total;
}

}  // namespace

void FrameBlock::Resize(uint32_t frame_count, uint32_t joint_count) {
  frame_count_ = frame_count;
  joint_count_ = joint_count;
  const size_t floats = static_cast<size_t>(tile_count()) * tile_floats();
  if (values_.size() < floats) values_.resize(floats);
  // Padding lanes of the last tile: zero frames (their distances are computed and dropped).
  if (frame_count % kTileFrames != 0) {
    std::fill(values_.begin() + (tile_count() - 1) * tile_floats(),
              values_.begin() + tile_count() * tile_floats(), 0.0f);
  }
}

void FrameBlock::StoreFrame(uint32_t slot, const int16_t* quantised) {
  const float inverse = 1.0f / PoseFeatures::kQuantScale;
  float* tile = values_.data() + (slot / kTileFrames) * tile_floats() + slot % kTileFrames;
  for (uint32_t joint_idx = 0; joint_idx < joint_count_; ++joint_idx) {
    float* rows = tile + joint_idx * kJointFloats;
    float norm = 0;
    for (uint32_t component = 0; component < 4; ++component) {
      // The same float values, and the same summation order for the norm, as PoseDistance.
      const float value = quantised[4 * joint_idx + component] * inverse;
      rows[component * kTileFrames] = value;
      norm += value * value;
    }
    rows[4 * kTileFrames] = norm;
  }
}

void FrameBlock::LoadRange(const PoseFeatures& features, uint64_t first_frame,
                           uint32_t frame_count) {
  MOTIF_CHECK(first_frame + frame_count <= features.frame_count());
  Resize(frame_count, features.weighted_joint_count());
  for (uint32_t slot = 0; slot < frame_count; ++slot) {
    StoreFrame(slot, features.frame(first_frame + slot));
  }
}

void FrameBlock::LoadFrames(const PoseFeatures& features, const uint64_t* frame_indices,
                            uint32_t frame_count) {
  Resize(frame_count, features.weighted_joint_count());
  for (uint32_t slot = 0; slot < frame_count; ++slot) {
    MOTIF_CHECK(frame_indices[slot] < features.frame_count());
    StoreFrame(slot, features.frame(frame_indices[slot]));
  }
}

DistanceKernel::Simd DistanceKernel::BestSimd() {
#if defined(MOTIF_DISTANCE_AVX2)
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  if (has_avx2) return Simd::kAvx2;
#endif
  return Simd::kPortable;
}

DistanceKernel::DistanceKernel(const PoseFeatures& features, Simd simd)
    : DistanceKernel(features.weights(), simd) {}

DistanceKernel::DistanceKernel(std::vector<float> weights, Simd simd)
    : weights_(std::move(weights)), simd_(simd == Simd::kAvx2 ? BestSimd() : Simd::kPortable) {}

void DistanceKernel::Compute(const FrameBlock& queries, const FrameBlock& candidates, float* out,
                             size_t out_stride) const {
  ComputeRows(queries, 0, queries.frame_count(), candidates, out, out_stride);
}

void DistanceKernel::ComputeRows(const FrameBlock& queries, uint32_t first_query,
                                 uint32_t query_count, const FrameBlock& candidates, float* out,
                                 size_t out_stride) const {
  const uint32_t joint_count = static_cast<uint32_t>(weights_.size());
  MOTIF_CHECK(queries.joint_count() == joint_count && candidates.joint_count() == joint_count);
  MOTIF_CHECK(first_query + query_count <= queries.frame_count());
  MOTIF_CHECK(out_stride >= candidates.frame_count());
  const float* weights = weights_.data();
  const uint32_t candidate_count = candidates.frame_count();
#if defined(MOTIF_DISTANCE_AVX2)
  if (simd_ == Simd::kAvx2) {
    distance_internal::KernelArgs args;
    args.query_tiles = queries.tile(0);
    args.first_query = first_query;
    args.query_count = query_count;
    args.candidate_tiles = candidates.tile(0);
    args.candidate_count = candidate_count;
    args.tile_floats = candidates.tile_floats();
    args.weights = weights;
    args.joint_count = joint_count;
    args.out = out;
    args.out_stride = out_stride;
    distance_internal::ComputeRowsAvx2(args);
    return;
  }
#endif
  // Candidate tile outermost: its 5 * joint_count rows stay in L1 while every query passes over
  // them; a query's values are read as scalars and broadcast.
  for (uint32_t tile_idx = 0; tile_idx < candidates.tile_count(); ++tile_idx) {
    const float* candidate_tile = candidates.tile(tile_idx);
    const uint32_t first_candidate = tile_idx * kTile;
    const uint32_t lanes = std::min(kTile, candidate_count - first_candidate);
    for (uint32_t query_idx = 0; query_idx < query_count; ++query_idx) {
      const uint32_t query = first_query + query_idx;
      const Lanes distances = TileDistances(queries.tile(query / kTile), query % kTile,
                                            candidate_tile, weights, joint_count);
      float* row = out + query_idx * out_stride + first_candidate;
      if (lanes == kTile) {
        Eigen::Map<Lanes> full_row(row);
        full_row = distances;
      } else {
        for (uint32_t lane = 0; lane < lanes; ++lane) row[lane] = distances[lane];
      }
    }
  }
}

}  // namespace motif
