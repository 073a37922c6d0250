// Time alignment of a motif's instances for the report's player: each instance is aligned to a
// reference instance (the motif's first) by dynamic time warping of their playback samples under
// the pose distance (per joint min(|q - p|, |q + p|) of the archive's rotations, the root's
// heading removed as the archive stores it, weighted by the skeleton's weights). This is the
// alignment a motif's warping path gives between two instances, recomputed at the samples the
// player shows (motifs.json does not keep the paths).
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/motion/skeleton.h"

namespace motif {

// The largest reference x instance sample grid aligned; beyond it, AlignToReference is linear.
inline constexpr uint64_t kMaxAlignmentCells = uint64_t{4} << 20;

// For each of the reference's samples, the instance's sample shown with it: non-decreasing,
// from 0 to instance_samples - 1 (of the instance samples the DTW path pairs with that
// reference sample, the nearest; the earliest of equals). `reference` and `instance` hold the
// samples' quaternion rows: 4 floats per joint of `skeleton`, `stride` floats per sample (the
// archive's row layout).
std::vector<uint32_t> AlignToReference(const Skeleton& skeleton, size_t stride,
                                       const std::vector<float>& reference,
                                       uint32_t reference_samples,
                                       const std::vector<float>& instance,
                                       uint32_t instance_samples);

}  // namespace motif
