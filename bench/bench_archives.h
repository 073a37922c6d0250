// Archives shared by the benchmarks, of two kinds of motion:
//   "synth"        MotionSynthesizer::Create, procedural motion, seed 7.
//   "resequenced"  the real CMU BVH takes (bench::MocapDir()/bvh, resampled to 120 fps)
//                  re-sequenced by MotionSynthesizer::CreateFromTakes, seed 7 (the real takes'
//                  neighbour density); an error (skip) when the takes are absent.
//   "heavy"        (in memory only) "synth" of N - N/16 frames plus a last clip of N/16 frames
//                  of one static T-pose (identity rotations): a heavy bucket for the LSH tables.
// Motifs: clamp(N / 10000, 1, 8), at most 2 s long below 20,000 frames and 5 s above; no
// background variation (the library default).
//
// ArchiveFileOf writes the archive once, streaming, to $MOTIF_BENCH_DIR/archives/<data>-<N>.mfs
// and reuses it in later runs and by the other benchmark programs (2^24 frames: ~400 MB, ~1 min).
// ArchiveOf holds its PoseFeatures in memory (read from that file, as the trellis builder reads
// an archive: 96 bytes a frame) with the neighbour rules:
//   k_max 256, a 30-frame exclusion radius, eps = mu - 2 sigma of 20,000 random allowed pairs (a
//   fixed LCG, seed 3) among the moving frames (the T-pose clip left out).
// Thread-safety: none; call from the benchmark thread only. One in-memory archive is kept at a
// time: asking for another one frees the previous one first, so a reference returned earlier is
// valid only until the next call with other arguments.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"

namespace motif::bench {

struct Archive {
  std::unique_ptr<PoseFeatures> features;
  NeighbourRules rules;
  std::string error;  // non-empty: the archive could not be made; the benchmark skips
};

// The path of the archive file of kind `data` ("synth" or "resequenced") with `frames` frames,
// written first if it is not there yet.
Result<std::string> ArchiveFileOf(const std::string& data, uint64_t frames);

// The archive of kind `data` ("synth", "resequenced", "heavy") with `frames` frames, in memory.
const Archive& ArchiveOf(const std::string& data, uint64_t frames);

// Frees the archive ArchiveOf holds (before a measurement that must not count it).
void ReleaseArchive();

}  // namespace motif::bench
