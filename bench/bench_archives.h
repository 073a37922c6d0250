// In-memory archives shared by the search benchmarks (bench_engine_lsh, bench_faiss_range): the
// PoseFeatures of N frames made by the motion synthesiser, and their neighbour rules. Nothing
// is written to disk; the archive is made on first use and cached.
//   "synth"        MotionSynthesizer::Create, procedural motion, seed 7.
//   "resequenced"  the real CMU BVH takes (bench::MocapDir()/bvh, resampled to 120 fps)
//                  re-sequenced by MotionSynthesizer::CreateFromTakes, seed 7; an error (skip)
//                  when the takes are absent.
//   "heavy"        "synth" of N - N/16 frames plus a last clip of N/16 frames of one static
//                  T-pose (identity rotations): a heavy bucket for the LSH tables.
// Motifs: clamp(N / 10000, 1, 8), at most 2 s long below 20,000 frames and 5 s above.
// Rules: k_max 256, a 30-frame exclusion radius, eps = mu - 2 sigma of 20,000 random allowed
// pairs (a fixed LCG, seed 3) among the moving frames (the T-pose clip left out).
// Thread-safety: none; call from the benchmark thread only. One archive is kept at a time (the
// largest, 2^20 frames, is 100 MB of features): asking for another one frees the previous one,
// so a reference returned earlier is valid only until the next call with other arguments.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"

namespace motif::bench {

struct Archive {
  std::unique_ptr<PoseFeatures> features;
  NeighbourRules rules;
  std::string error;  // non-empty: the archive could not be made; the benchmark skips
};

// The archive of kind `data` ("synth", "resequenced", "heavy") with `frames` frames.
const Archive& ArchiveOf(const std::string& data, uint64_t frames);

}  // namespace motif::bench
