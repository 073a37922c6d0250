// LshOptions: every parameter of the LSH eps-neighbour search (docs/design/lsh.md), with the
// defaults measured on the real CMU takes and the synthetic archives, and DescribeLshOptions(),
// the one-line text the trellis file keeps as its search_params.
//
// The scheme (Datar et al. 2004, "Locality-sensitive hashing scheme based on p-stable
// distributions"; multi-probe after Lv et al. 2007, "Multi-probe LSH"): each frame's weighted
// joint quaternions are embedded sign-invariantly (HashFamily), projected on `hashes_per_table`
// orthonormal random directions per table and cut into cells of `bucket_width`; a bucket is a
// cell. A query visits the buckets of all tables nearest first and verifies every candidate with
// the exact pose distance D.
// Thread-safety: a value type.
#pragma once

#include <cstdint>
#include <string>
#include "motifmine/defaults.h"

namespace motif {

// The order in which a column's candidates are verified (docs/design/lsh.md section 3).
enum class LshRanking {
  // Bucket by bucket, breadth first, outward from the query's sort value: reads few entries
  // (~5,000 a column), the fastest; recall 0.95-0.97 at 1M frames of real-density motion.
  kSortValue,
  // All entries within reach gathered (up to max_entries) and ranked by their position code
  // before verification: ~1.4-2.5x the time per column, recall up to 0.94 at 1M frames of the
  // low-contrast procedural synthetic archive where kSortValue gets 0.82. Adds 4 bytes per
  // frame per table to the index.
  kPositionCode,
};

struct LshOptions {
  // L: independent hash tables. Each costs 10 bytes per frame (frame id, bucket key, sort value).
  uint32_t tables = motifmine::defaults::kLshTables;
  // m: projections per table (the cell is m-dimensional). 0: from the archive size
  // (DefaultHashesPerTable in lsh_tuning.h: 13 at 40k frames, 16 at 1M, 18 at 10M).
  uint32_t hashes_per_table = motifmine::defaults::kLshHashes;
  // w: cell width along each projection, in embedding units (|e_i - e_j| <= D). 0: chosen from
  // the data, width_per_hash * m * the 90th percentile of the embedding distance of a column's
  // neighbours (ResolveLshOptions in lsh_tuning.h).
  float bucket_width = static_cast<float>(motifmine::defaults::kLshWidth);
  float width_per_hash = static_cast<float>(motifmine::defaults::kLshWidthPerHash);
  // Buckets visited per table, nearest first (multi-probe); 1 visits only the query's own.
  uint32_t probes_per_table = motifmine::defaults::kLshProbes;
  // Work bounds per column: exact distance evaluations, and entries examined in one bucket
  // (heavy buckets: a static pose repeated thousands of times falls into one bucket).
  uint32_t max_candidates = motifmine::defaults::kLshMaxCandidates;
  uint32_t max_bucket_scan = 2048;
  LshRanking ranking = LshRanking::kSortValue;
  // kPositionCode: bucket entries gathered and ranked per column (and per extension stage)
  // before the best max_candidates of them are verified.
  uint32_t max_entries = motifmine::defaults::kLshMaxEntries;
  // Buckets are scanned breadth first: all probed buckets to this depth, then 4x deeper, ...
  // up to max_bucket_scan.
  uint32_t first_round_scan = 64;
  // Sparse columns (not full when their probes are used up, or full with a k_max-th neighbour
  // farther than sparse_radius_factor times the archive's typical one) probe further: up to
  // this many stages of 4x more probes per table, within the same max_candidates.
  uint32_t extension_stages = 2;
  float sparse_radius_factor = 2.0f;
  // Temporal chaining. Motion is continuous: if j is a neighbour of column t, then j, j + 1 or
  // j + 2 is most likely one of column t + 1 (the trellis's paths are exactly these runs).
  // Columns are searched in chains of chain_columns consecutive columns, aligned on multiples of
  // chain_columns (so a column's result does not depend on which range or thread computed it).
  // Every column after a chain's first verifies its predecessor's neighbours advanced by
  // 0..chain_advance frames before probing, which sets a tight radius at once, and then (if it
  // is a probing column, see chain_probe_every) spends at most chained_max_candidates further
  // evaluations on the probed buckets (new paths).
  // chain_columns 0 or 1: every column is searched alone with max_candidates.
  uint32_t chain_columns = motifmine::defaults::kLshChainColumns;
  uint32_t chain_advance = 2;
  // Only every chain_probe_every-th column of a chain (those at positions 0, S, 2S, ... from
  // its start) probes the buckets, with chained_max_candidates after its seeds; the columns
  // between keep their seeds and get what the chain sweeps carry over from the probing ones.
  // Neighbouring columns probe nearly the same buckets and find nearly the same candidates, so
  // one column going deep finds more new paths than S columns going shallow, at a fraction of
  // the probing cost (docs/design/lsh.md section 3c). 1: every column probes.
  uint32_t chain_probe_every = motifmine::defaults::kLshChainProbeEvery;
  uint32_t chained_max_candidates = motifmine::defaults::kLshChainedMaxCandidates;
  uint32_t chained_probe_stride = 1;  // DEV
  uint32_t chained_off_budget = 0;    // DEV
  // Sweeps over a finished chain, alternately backward and forward, without probing: each column
  // verifies its successor's neighbours moved back by 0..chain_advance frames (backward), or its
  // predecessor's moved on (forward), so a path found anywhere in the chain reaches all of its
  // columns, not only the later ones. 0: none (a column then depends only on the columns before
  // it in its chain).
  uint32_t chain_sweeps = motifmine::defaults::kLshChainSweeps;
  // Random projections and offsets are drawn from this seed; the same seed gives the same index
  // and the same columns for any thread count.
  uint64_t seed = 0x6d6f746966ull;
  // Frames hashed per build shard (one TBB task each).
  uint32_t shard_frames = 1u << 14;
  // Worker threads of the build and of the queries (0: all cores).
  int threads = 0;
};

// "lsh embedding=qqT tables=8 hashes=16 width=0.0567 ... seed=...". On options as given (0 =
// automatic) it identifies a configuration (deterministic for an archive and seed); on
// LshSearch::options() (resolved) it names the m and w actually used (LshSearch::DescribeParams).
std::string DescribeLshOptions(const LshOptions& options);

// "sort" / "code", and back (InvalidArgument-free: false on other text).
const char* LshRankingName(LshRanking ranking);
bool ParseLshRanking(const std::string& text, LshRanking* ranking);

}  // namespace motif
