// ColumnQuery: the forward query of one column of the LSH search (docs/design/lsh.md, section
// 3), composed of named steps:
//   0. seeds (a chained column): the predecessor's neighbours advanced by 0..chain_advance
//      frames are verified first (section 3a); only every chain_probe_every-th column of a chain
//      then probes (section 3c);
//   1. the probe sequence of the column's frame (ProbeSequence);
//   2. the probed buckets, read breadth first (BucketScanner), in one of two candidate orders
//      (LshOptions::ranking): as the scan meets them (kSortValue), or gathered and ranked by
//      their position codes first (kPositionCode, PositionCodeRanker);
//   3. every candidate verified exactly, the k_max nearest within eps kept (CandidateVerifier);
//   4. sparse columns probe farther buckets: up to extension_stages stages of 4x the probes.
// Owns one of each step's scratch, reused across columns; refers to the LshSearch's parts
// through the context.
// Thread-safety: one per query worker (SearchColumns runs one per TBB range).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/neighbour_search.h"
#include "engine/lsh/bucket_scanner.h"
#include "engine/lsh/candidate_verifier.h"
#include "engine/lsh/lsh_query_context.h"
#include "engine/lsh/lsh_query_stats.h"
#include "engine/lsh/position_code_ranker.h"
#include "engine/lsh/probe_sequence.h"

namespace motif {

class ColumnQuery {
 public:
  explicit ColumnQuery(const LshQueryContext& context);

  // Finds column `column` into *out (sorted by frame) and adds its work to *work. `previous`:
  // the neighbours of column - 1 in the same chain (seeds), or null for a chain's first column
  // (or without chaining). With `reverse_query`, *reverse receives the verified older frames
  // within eps and their thresholds (CandidateVerifier), in no particular order.
  void Run(uint64_t column, const std::vector<Neighbour>* previous, std::vector<Neighbour>* out,
           ColumnWork* work, const ReverseQuery* reverse_query = nullptr,
           std::vector<Neighbour>* reverse = nullptr);

 private:
  class SortValueRounds;   // the BucketVisitor of the kSortValue order
  class CodeGatherRounds;  // the BucketVisitor of the kPositionCode gathering

  // Verifies the seeds and sets the chained budget. True if this column probes.
  bool VerifySeeds(const std::vector<Neighbour>& previous);
  // Scans the probes [first_probe, ...) in the options' order.
  void Scan(size_t first_probe);
  void ScanBySortValue(size_t first_probe);
  void ScanByCode(size_t first_probe);
  void VerifyRanked(const std::vector<PositionCodeRanker::Ranked>& ranked);
  void ProbeFartherBuckets();
  // Adds a scan's counters to the column's statistics.
  void CountScan(const BucketScanner::Outcome& outcome);

  const LshQueryContext context_;
  ProbeSequence probes_;
  BucketScanner scanner_;
  CandidateVerifier verifier_;
  PositionCodeRanker ranker_;
  // The current column's.
  LshQueryStats stats_;
  bool budget_spent_ = false;   // stopped by its budget
  bool bound_stopped_ = false;  // stopped because nothing left could enter
};

}  // namespace motif
