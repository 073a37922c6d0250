// DistanceKernel: the pose distance D (pose_features.h) for a block of query frames against a
// block of candidate frames at once, the inner loop of the exact search, of the epsilon
// estimator's density count and of any batch verification of LSH candidates.
//
// Frames are dequantised once per block into a FrameBlock, structure-of-arrays in tiles of
// kTileFrames frames: per tile and weighted joint, five rows of kTileFrames floats: the
// quaternion components w, x, y, z and the squared norm |q|^2. Per pair and joint the kernel
// uses min(|q - p|, |q + p|)^2 = |q|^2 + |p|^2 - 2 |q.p|, so a joint costs a 4-term dot product,
// an abs, a sqrt and a weighted add, evaluated for a whole tile of candidates in SIMD registers
// (Eigen fixed-size arrays: SSE2 in the default build, AVX with -mavx; the square root is the
// exact instruction, not Eigen's fast-math approximation).
//
// On x86-64 CPUs with AVX2, the same loop runs on 8-lane registers (distance_kernel_avx2.cc,
// chosen at run time: the build stays portable).
//
// Results are the scalar PoseDistance's, bit for bit, as long as the compiler does not fuse
// multiply-adds (this library is built with -ffp-contract=off): every pair is evaluated with the
// same operations in the same order as PoseDistance, only many lanes at a time. So D(a, b) from
// the kernel equals PoseDistance(a, b) and PoseDistance(b, a), and does not depend on the block
// sizes or on which block a frame sits in.
//
// Thread-safety: a DistanceKernel is immutable, Compute is const and safe from many threads;
// a FrameBlock is a value (one per thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "engine/distance/pose_features.h"

namespace motif {

// std::allocator with 64-byte alignment (a cache line; enough for any SIMD width). FrameBlock
// keeps its buffer in a std::vector of these rather than an Eigen type, so that the header does
// not depend on the SIMD flags a translation unit is compiled with.
template <typename T>
struct CacheAlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  CacheAlignedAllocator() = default;
  template <typename U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) {}  // NOLINT: rebinding
  T* allocate(size_t count) {
    return static_cast<T*>(::operator new(count * sizeof(T), kAlignment));
  }
  void deallocate(T* pointer, size_t) { ::operator delete(pointer, kAlignment); }
  template <typename U>
  bool operator==(const CacheAlignedAllocator<U>&) const {
    return true;
  }
};

class FrameBlock {
 public:
  static constexpr uint32_t kTileFrames = 16;
  static constexpr uint32_t kRowsPerJoint = 5;  // w, x, y, z, |q|^2

  // Dequantises frames [first_frame, first_frame + frame_count) of `features` (the range must
  // lie inside the archive). The last tile is padded with zero frames.
  void LoadRange(const PoseFeatures& features, uint64_t first_frame, uint32_t frame_count);
  // Dequantises the listed frames, in that order (frame_indices[i] < frame_count()).
  void LoadFrames(const PoseFeatures& features, const uint64_t* frame_indices,
                  uint32_t frame_count);

  uint32_t frame_count() const { return frame_count_; }
  uint32_t joint_count() const { return joint_count_; }
  uint32_t tile_count() const { return (frame_count_ + kTileFrames - 1) / kTileFrames; }
  // Floats per tile: joint_count * kRowsPerJoint * kTileFrames.
  size_t tile_floats() const {
    return static_cast<size_t>(joint_count_) * kRowsPerJoint * kTileFrames;
  }
  // The tile's rows: row (joint_idx * kRowsPerJoint + row_idx) starts at
  // tile(tile_idx) + (joint_idx * kRowsPerJoint + row_idx) * kTileFrames. Aligned for SIMD.
  const float* tile(uint32_t tile_idx) const { return values_.data() + tile_idx * tile_floats(); }
  // One dequantised value: row_idx 0..3 the components w, x, y, z, 4 the squared norm.
  float value(uint32_t frame_idx, uint32_t joint_idx, uint32_t row_idx) const {
    return tile(
        frame_idx /
        kTileFrames)[(joint_idx * kRowsPerJoint + row_idx) * kTileFrames + frame_idx % kTileFrames];
  }

 private:
  void Resize(uint32_t frame_count, uint32_t joint_count);
  void StoreFrame(uint32_t slot, const int16_t* quantised);

  uint32_t frame_count_ = 0;
  uint32_t joint_count_ = 0;
  std::vector<float, CacheAlignedAllocator<float>> values_;  // tile-major
};

class DistanceKernel {
 public:
  // Which code computes the distances: the portable one (Eigen; SSE2 on any x86-64 build), or
  // on x86-64 CPUs that have it, an AVX2 one (twice as fast), chosen at run time. Both give the
  // same bits.
  enum class Simd { kPortable, kAvx2 };
  // The fastest this build and CPU support.
  static Simd BestSimd();

  // Uses the weights of `features` (which need not outlive the kernel). A `simd` the CPU does
  // not support falls back to kPortable (see simd()).
  explicit DistanceKernel(const PoseFeatures& features, Simd simd = BestSimd());
  explicit DistanceKernel(std::vector<float> weights, Simd simd = BestSimd());

  // out[query_idx * out_stride + candidate_idx] = D(query frame, candidate frame) for every
  // query_idx < queries.frame_count() and candidate_idx < candidates.frame_count().
  // Preconditions: both blocks were loaded from features with this kernel's weighted joints;
  // out_stride >= candidates.frame_count().
  void Compute(const FrameBlock& queries, const FrameBlock& candidates, float* out,
               size_t out_stride) const;

  // The same for queries [first_query, first_query + query_count) of `queries` only; row
  // query_idx of `out` holds query first_query + query_idx.
  void ComputeRows(const FrameBlock& queries, uint32_t first_query, uint32_t query_count,
                   const FrameBlock& candidates, float* out, size_t out_stride) const;

  const std::vector<float>& weights() const { return weights_; }
  Simd simd() const { return simd_; }

 private:
  std::vector<float> weights_;
  Simd simd_ = Simd::kPortable;
};

}  // namespace motif
