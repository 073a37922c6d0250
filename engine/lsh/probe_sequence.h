// ProbeSequence: the buckets one column's query visits, nearest first (docs/design/lsh.md,
// section 3, step 1). The column's frame is embedded and projected for every table; per table
// its own bucket and the neighbouring buckets of lowest multi-probe score are listed (Lv et al.
// 2007, "Multi-probe LSH", query-directed probing), and the probes of all tables are sorted by
// score. The score is a squared lower bound: every frame of a probed bucket has
// D >= |P(e - e_q)| >= sqrt(score), because the projections are orthonormal (HashFamily).
// Owns the query's embedding, projections and probe list (scratch reused across columns); refers
// to the family and the index, which must outlive it.
// Thread-safety: one per query worker.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_index.h"

namespace motif {

// Lower bounds are computed from float projections of quantised quaternions (|q|^2 = 1 +- 1e-4)
// and int16 sort values; this slack, added to a radius before comparing, keeps them below the
// true D.
inline constexpr float kBoundSlack = 1e-3f;

// One bucket to visit: table, bucket key and lower bound (squared, embedding units).
struct BucketProbe {
  float score = 0;
  uint32_t table_idx = 0;
  uint32_t rank = 0;  // order within its table (0: the query's own bucket)
  uint32_t key = 0;
  // Coordinates whose cell is one below / one above the query's (bit i: hash coordinate i).
  uint32_t minus_mask = 0;
  uint32_t plus_mask = 0;
};

// The order of a sequence: score, then table, then rank within the table.
bool ProbeBefore(const BucketProbe& a, const BucketProbe& b);

class ProbeSequence {
 public:
  ProbeSequence(const HashFamily& family, const LshIndex& index);

  // Embeds, projects and quantises `frame` (PoseFeatures::frame) and lists the probes of rank
  // [0, probes_per_table) of every table (AddProbes(probes_per_table, 0)).
  void Prepare(const int16_t* frame, uint32_t probes_per_table);
  // Appends the probes of rank [skip, wanted) of every table, sorted among themselves (the
  // earlier ones stay in front), and prefetches their directory slots and keys. Fewer per table
  // if the table's cell has fewer valid perturbations within the search's bound on work.
  void AddProbes(uint32_t wanted, uint32_t skip);

  const std::vector<BucketProbe>& probes() const { return probes_; }
  // The query's m cell coordinates in table `table_idx`, then its sort value (m + 1 floats).
  const float* coordinates(uint32_t table_idx) const {
    return &projections_[static_cast<size_t>(table_idx) * (family_.hashes_per_table() + 1)];
  }
  // The query's quantised sort value in each table (what the tables' entries store).
  const int16_t* query_sort_values() const { return query_sort_values_.data(); }

 private:
  // Appends the probes of rank [skip, wanted) of one table to probes_.
  void ListProbes(uint32_t table_idx, uint32_t wanted, uint32_t skip);

  const HashFamily& family_;
  const LshIndex& index_;
  std::vector<float> embedding_;
  std::vector<float> projections_;
  std::vector<int16_t> query_sort_values_;  // per table
  std::vector<BucketProbe> probes_;
};

}  // namespace motif
