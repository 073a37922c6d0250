// LshQueryStats and ColumnWork: the work counters of the LSH queries (LshSearch), per column
// (ColumnWork, filled by the steps of a column's search) and summed over columns (LshQueryStats,
// which SearchColumns reports).
// Thread-safety: plain values; each worker fills its own.
#pragma once

#include <cstdint>

namespace motif {

// LSH-specific work counters, summed over columns.
struct LshQueryStats {
  uint64_t probes = 0;                 // buckets looked up
  uint64_t entries_examined = 0;       // bucket entries read (including repeats and excluded)
  uint64_t bucket_scans_capped = 0;    // buckets left early by max_bucket_scan
  uint64_t columns_budget_capped = 0;  // columns stopped by max_candidates
  uint64_t columns_bound_stopped = 0;  // columns stopped because nothing left could enter
  uint64_t extensions = 0;             // extra probing stages of sparse columns
  uint64_t seed_evaluations = 0;       // evaluations of chained columns' seeds (in the total)
  uint64_t sweep_evaluations = 0;      // evaluations of the chain sweeps (in the total)

  void Add(const LshQueryStats& other) {
    probes += other.probes;
    entries_examined += other.entries_examined;
    bucket_scans_capped += other.bucket_scans_capped;
    columns_budget_capped += other.columns_budget_capped;
    columns_bound_stopped += other.columns_bound_stopped;
    extensions += other.extensions;
    seed_evaluations += other.seed_evaluations;
    sweep_evaluations += other.sweep_evaluations;
  }
};

// The work of one column: its forward query's and its chain sweeps'. Added to a range's
// statistics only if the range asked for the column.
struct ColumnWork {
  uint64_t evaluations = 0;  // exact distance evaluations
  bool capped = false;       // more than k_max frames within eps were seen
  LshQueryStats lsh;
};

}  // namespace motif
