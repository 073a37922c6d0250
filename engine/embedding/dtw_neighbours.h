// The k nearest words of every word of a pool under the DTW word distance (word_distance.h):
// the paper's second kind of positive (Aristidou et al. 2018, section 4.2: "the k = 5 nearest
// neighbours ... w.r.t. the time-warped distance"), found without comparing all pairs.
//
// An inverted-file index (Jegou et al. 2011; FAISS's IndexIVF) over a cheap descriptor, then the
// exact DTW on the best candidates:
//  * descriptor: the word's frames in the sign-free embedding of the LSH (hash_family.h: the 10
//    entries of q q^T per weighted joint, times its weight, whose L2 distance bounds the pose
//    distance from below), averaged over 4 equal runs of frames (so a phase shift of a frame or
//    two, which the DTW's band absorbs, moves it little): 480 numbers at J_w = 12;
//  * lists: k-means (k_means.h) of the descriptors into L = round(sqrt(n)) lists (by default),
//    fitted on a seeded sample of at most 64 L words, every word then in its nearest list;
//  * query: the `probes` lists nearest the word's descriptor; their words, minus the word's
//    trivial matches (itself and the words of its clip that overlap it, WordPool::overlap_words),
//    ranked by descriptor distance; the `max_verified` best are compared with the exact DTW
//    (early abandoning at the current k-th best), and the k nearest kept.
// Work per word: L + n probes / L descriptor distances and max_verified DTWs instead of n DTWs.
// With probes = L and max_verified = 0 (all) the search is exhaustive: the exact k nearest.
// Determinism: queries are independent, written to their own slots; the lists come from seeded
// k-means; so the result does not depend on the thread count. Ties: the lower word index first.
// Thread-safety: a pure function; it runs its parallel loops in its own task_arena.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/status.h"
#include "engine/embedding/word_pool.h"

namespace motif {

struct DtwNeighbourOptions {
  uint32_t k = 5;
  uint32_t band_frames = 2;     // the Sakoe-Chiba radius (word_distance.h)
  uint32_t lists = 0;           // L; 0: round(sqrt(n)), at most 4096
  uint32_t probes = 8;          // lists searched per word
  uint32_t max_verified = 128;  // candidates compared with the DTW per word; 0: all
  uint64_t seed = 1;
  int threads = 0;
  std::function<void(uint64_t, uint64_t)> progress;  // (words done, words)
};

struct WordNeighbour {
  uint32_t word = 0;   // pool index
  float distance = 0;  // DTW
  bool operator==(const WordNeighbour&) const = default;
};

// For each word of `pool` (version 0, the words themselves), its up to k nearest words, nearest
// first. InvalidArgument: k = 0, probes = 0, an empty pool.
Result<std::vector<std::vector<WordNeighbour>>> FindDtwNeighbours(
    const WordPool& pool, const DtwNeighbourOptions& options);

}  // namespace motif
