// Internal to DistanceKernel (distance_kernel.cc): the AVX2 path of the block kernel, built only
// on x86-64 (MOTIF_DISTANCE_AVX2) and called only on CPUs that have AVX2. Plain data in, so the
// AVX2 translation unit needs no C++ library code (see distance_kernel_avx2.cc).
#pragma once

#include <cstddef>
#include <cstdint>

namespace motif::distance_internal {

// The arguments of DistanceKernel::ComputeRows, unpacked: tile-major FrameBlock buffers
// (kTileFrames = 16 frames a tile, 5 rows per joint), `tile_floats` floats per tile.
struct KernelArgs {
  const float* query_tiles = nullptr;
  uint32_t first_query = 0;
  uint32_t query_count = 0;
  const float* candidate_tiles = nullptr;
  uint32_t candidate_count = 0;
  size_t tile_floats = 0;
  const float* weights = nullptr;
  uint32_t joint_count = 0;
  float* out = nullptr;
  size_t out_stride = 0;
};

void ComputeRowsAvx2(const KernelArgs& args);

}  // namespace motif::distance_internal
