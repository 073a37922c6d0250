// LshSearch: approximate eps-neighbour columns of the matching trellis from an LshIndex, every
// candidate verified with the exact pose distance D (docs/design/algorithm.md, step 2).
//
// Per column t, nearest first, with a bounded amount of work (docs/design/lsh.md):
//   1. hash f_t in every table; list, per table, its own bucket and the probes_per_table - 1
//      neighbouring buckets of lowest multi-probe score (Lv et al. 2007). The score is a lower
//      bound: every frame of a probed bucket has D >= sqrt(score) (orthonormal projections).
//   2. visit the probed buckets of all tables breadth first: each is read outward from f_t's
//      sort value, first_round_scan entries deep in every bucket, then 4x deeper, ..., so the
//      budget goes to the entries nearest f_t in all tables first. The lower bound of an entry,
//      sqrt(score + ds^2), ends a bucket's scan, and a probe's, once it exceeds the radius
//      min(eps, distance of the k_max-th neighbour found): nothing beyond can enter the column.
//      Each new candidate (not f_t, not in f_t's exclusion radius, not seen in another table) is
//      verified with the exact D (QueryDistance, bit-identical to PoseDistance); the k_max
//      nearest within eps are kept (ties: lower frame first).
//   3. sparse columns, not full when the probes are used up or full but with a k_max-th
//      neighbour beyond sparse_radius_factor x the archive's typical one, probe further: up to
//      extension_stages stages of 4x more probes per table.
// Hard caps bound everything: max_bucket_scan entries per bucket, max_candidates evaluations per
// column, probes_per_table x 4^extension_stages buckets per table. The work per column is thus
// bounded by the caps, not by how many eps-neighbours exist. Heavy buckets (a static pose
// repeated thousands of times) cost at most max_bucket_scan entries each.
//   0. chaining: columns go in chains of chain_columns, aligned on multiples of it; a column
//      after its chain's first verifies its predecessor's neighbours advanced by 0..chain_advance
//      frames first (seeds); every chain_probe_every-th one then spends at most
//      chained_max_candidates on the probed buckets, the others do not probe (steps 1-3).
//   4. chain sweeps: once a chain's columns are found, chain_sweeps passes over it, backward then
//      forward, verify each column's successor's (predecessor's) neighbours moved by
//      0..chain_advance frames, so a path found at any column of the chain reaches all of them.
// Each column depends only on the index, f_t and the other columns of its aligned chain (the
// whole chain is computed whenever a range asks for one of its columns), so columns are the same
// for any thread count and any split of the archive into ranges.
// The steps have their own files, each testable alone: ProbeSequence (1), BucketScanner (the
// breadth-first reading of 2), CandidateVerifier (the verification and the k_max nearest of 2),
// PositionCodeRanker (LshRanking::kPositionCode's order), ColumnQuery (0-3 for one column),
// ChainSweep (4) and ReversePass (SearchColumnsAndReverse's reverse scan); this class validates
// the options, owns the index and runs one task per aligned chain.
// Thread-safety: SearchColumns is const and may run from many threads at once.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_index.h"
#include "engine/lsh/lsh_options.h"
#include "engine/lsh/lsh_query_context.h"
#include "engine/lsh/lsh_query_stats.h"

namespace motif {

class LshSearch final : public NeighbourSearch {
 public:
  // Chooses the bucket width from the data when options.bucket_width is 0 (ChooseBucketWidth),
  // draws the hash family from options.seed and builds the index. `features` must outlive the
  // search. rules.clip_first_frames may be empty (the features' layout is used) or must equal
  // features.clip_first_frames(). InvalidArgument: eps <= 0, k_max == 0, another clip layout,
  // tables or hashes_per_table out of range (1..64; 0 for automatic or 1..32 and below the
  // embedding's dimension), a zero probe count, budget, scan depth or shard size, a negative
  // width, 2^32 frames or more. Errors of the index build pass through. With `ranks` (a
  // distributed run) the ranks hash a share of the frames each and exchange them
  // (LshIndex::Build): every rank gets the same index.
  static Result<std::unique_ptr<LshSearch>> Create(const PoseFeatures& features,
                                                   NeighbourRules rules, const LshOptions& options,
                                                   RankGroup* ranks = nullptr);
  // The same with the index given: built earlier over all of `features` with the family these
  // options draw (HashFamily::Draw(features.weights(), tables, hashes_per_table, bucket_width,
  // seed), both sizes given, not 0), e.g. a saved index extended with new frames
  // (LshIndex::Extend). The search is then the one Create makes. InvalidArgument, besides
  // Create's, if the index covers another frame count or table count.
  static Result<std::unique_ptr<LshSearch>> CreateWithIndex(const PoseFeatures& features,
                                                            NeighbourRules rules,
                                                            const LshOptions& options,
                                                            LshIndex index);

  Status SearchColumns(uint64_t first_column, uint64_t count,
                       std::vector<std::vector<Neighbour>>* columns,
                       SearchStats* stats) const override;
  // The same, also adding LSH work counters to *lsh_stats (may be null).
  Status SearchColumns(uint64_t first_column, uint64_t count,
                       std::vector<std::vector<Neighbour>>* columns, SearchStats* stats,
                       LshQueryStats* lsh_stats) const;
  // The same columns, and the older frames each new column may enter (NeighbourSearch): those
  // among the forward query's verified candidates (verified up to eps rather than abandoned at
  // the column's shrinking radius, so which candidates are verified, and so the columns, do not
  // change), and those of a second, reverse scan of the column's probed buckets out to eps with
  // max_candidates evaluations, which skips an older frame whose lower bound exceeds its own
  // threshold. An older frame outside the probed buckets or beyond the budget is missed.
  Status SearchColumnsAndReverse(uint64_t first_column, uint64_t count, const ReverseQuery& query,
                                 std::vector<std::vector<Neighbour>>* columns,
                                 std::vector<std::vector<Neighbour>>* reverse,
                                 SearchStats* stats) const override;

  // The buckets column `column` visits, in order, as (table, bucket key, lower bound on D), before
  // any early stop (diagnostics and tests).
  struct ProbeInfo {
    uint32_t table_idx;
    uint32_t key;
    float lower_bound;
  };
  std::vector<ProbeInfo> ProbeSequence(uint64_t column) const;

  // The options as used (bucket_width filled in).
  const LshOptions& options() const { return options_; }
  const NeighbourRules& rules() const { return rules_; }
  const HashFamily& family() const { return family_; }
  const LshIndex& index() const { return index_; }
  // DescribeLshOptions(options()): the trellis file's search_params.
  std::string DescribeParams() const { return DescribeLshOptions(options_); }
  // What the steps of a query read (ColumnQuery, ReversePass, ...): valid while the search is.
  LshQueryContext context() const {
    return {features_, rules_, options_, family_, index_, extension_radius_};
  }

 private:
  LshSearch(const PoseFeatures& features, NeighbourRules rules, LshOptions options,
            HashFamily family, LshIndex index, float extension_radius);
  // Create's work; with `index` null the index is built (shared among `ranks` when given).
  static Result<std::unique_ptr<LshSearch>> Make(const PoseFeatures& features, NeighbourRules rules,
                                                 const LshOptions& options, LshIndex* index,
                                                 RankGroup* ranks);
  // Every search; `reverse_query` and `reverse` null for the columns alone.
  Status Search(uint64_t first_column, uint64_t count, const ReverseQuery* reverse_query,
                std::vector<std::vector<Neighbour>>* columns,
                std::vector<std::vector<Neighbour>>* reverse, SearchStats* stats,
                LshQueryStats* lsh_stats) const;

  const PoseFeatures& features_;
  NeighbourRules rules_;
  LshOptions options_;
  HashFamily family_;
  LshIndex index_;
  // A full column whose k_max-th neighbour is farther than this is probed further (sparse).
  float extension_radius_ = 0;
};

}  // namespace motif
