// AuditTrellis: how good an LSH trellis is. Samples columns (seeded), computes each one exactly
// (blocked brute force against all N frames, with the same rules: eps, exclusion, k_max cap),
// and compares with the trellis file: recall is the share of the exact columns' entries that
// the trellis has (over all sampled columns). Also reruns the LSH search on the chains of some of
// those columns to count exact distance evaluations per column, against N for the brute force.
// Thread-safety: one call at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "common/status.h"
#include "engine/lsh/lsh_options.h"

namespace motif {

struct AuditOptions {
  uint64_t sample_columns = 1000;
  uint64_t seed = 1;
  int threads = 0;
  std::string weights_path;  // must be the weights the trellis was built with
  LshOptions lsh;            // the LSH options the trellis was built with (seed: from the file)
  std::function<void(uint64_t, uint64_t)> progress;  // sampled columns done / total
};

struct AuditReport {
  uint64_t sampled_columns = 0;
  uint64_t exact_entries = 0;     // entries of the exact sampled columns (after the k_max cap)
  uint64_t found_entries = 0;     // of those, present in the trellis
  uint64_t trellis_entries = 0;   // entries of the sampled trellis columns
  double recall = 0;              // found / exact (1 when there is nothing to find)
  double mean_column_recall = 0;  // mean over sampled columns with a non-empty exact column
  double min_column_recall = 1;
  uint64_t capped_exact_columns = 0;  // exact columns that had more than k_max within eps
  // The same split by kind of column. An uncapped exact column holds every frame within eps; a
  // capped one only the k_max nearest of more, so a trellis column that misses some of those
  // may still hold k_max frames within eps (every trellis entry is verified), only not the
  // nearest: `capped_columns_full` counts the capped columns whose trellis column is full.
  uint64_t uncapped_exact_entries = 0;
  uint64_t uncapped_found_entries = 0;
  uint64_t capped_exact_entries = 0;
  uint64_t capped_found_entries = 0;
  uint64_t capped_columns_full = 0;
  // The LSH figures are per column of the whole chains holding up to 16 of the sampled columns
  // (lsh_timed_columns columns): a chained column is computed with the rest of its chain.
  uint64_t lsh_timed_columns = 0;
  double lsh_evaluations_per_query = 0;  // 0 if the trellis is exact
  double exact_evaluations_per_query = 0;
  double lsh_seconds_per_query = 0;
  double exact_seconds_per_query = 0;
  std::string search_params;  // as recorded in the trellis file
};

Result<AuditReport> AuditTrellis(const std::string& archive_path, const std::string& trellis_path,
                                 const AuditOptions& options);

}  // namespace motif
