// PositionCodeRanker: the candidate order of LshRanking::kPositionCode (docs/design/lsh.md,
// section 3, steps 2 and 3). The entries a column's scan gathers are ranked by an estimate of
// their squared distance from the query: per coded coordinate i, the squared distance (in cells)
// from the query's exact position x_i to the centre of the entry's quarter of its cell
// (HashFamily::PositionCode), plus the sort-value gap squared. The estimate is summed from
// eight 16-entry tables per probed bucket (two coordinates a table, in units of 1/128 cell^2:
// small enough to stay in L1 for all of a column's buckets), and its value is the bin of a
// counting sort: 1/128 cell^2 resolution up to 8 cells^2. Within a bin the gathering order is
// kept, so the ranking depends only on the index and the query.
// Owns the estimate tables and the gathered and ranked entries (scratch reused across columns);
// refers to the family.
// Thread-safety: one per query worker.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/lsh/hash_family.h"
#include "engine/lsh/probe_sequence.h"

namespace motif {

class PositionCodeRanker {
 public:
  static constexpr size_t kEstimateTableSize = 8 * 16;  // per probed bucket
  static constexpr float kEstimateUnitsPerCell2 = 128.0f;
  static constexpr uint32_t kRankBins = 1024;

  struct Ranked {
    uint32_t frame;
    float lower_squared;  // lower bound on D^2 from the probe and the sort value
  };

  explicit PositionCodeRanker(const HashFamily& family);

  // Forgets the entries gathered (a new scan).
  void Clear() { gathered_.clear(); }
  // Fills the estimate tables of the bucket `probe` (the cursor_idx-th of the scan), the query's
  // cell coordinates in its table at `coordinates`.
  void FillEstimateTable(const BucketProbe& probe, const float* coordinates, size_t cursor_idx);
  // Gathers an entry of the cursor_idx-th bucket with position code `code` and sort-value gap
  // `gap` (embedding units), its lower bound on D^2 `lower_squared`; returns how many entries
  // are gathered.
  size_t Add(uint32_t frame, float lower_squared, size_t cursor_idx, uint32_t code, float gap) {
    const uint16_t* estimates = &estimate_tables_[cursor_idx * kEstimateTableSize];
    uint32_t estimate = 0;
    for (uint32_t nibble = 0; nibble < 8; ++nibble) {
      estimate += estimates[16 * nibble + ((code >> (4 * nibble)) & 15u)];
    }
    const float gap_units = gap * gap_scale_;
    estimate += static_cast<uint32_t>(std::min(gap_units * gap_units, 65535.0f));
    gathered_.push_back({frame, lower_squared, std::min(estimate, kRankBins - 1)});
    return gathered_.size();
  }
  // The gathered entries by estimate bin (stable: gathering order within a bin).
  const std::vector<Ranked>& Rank();

  // The estimate table entry of bucket `cursor_idx` (tests): nibble 0..7, value 0..15.
  uint16_t estimate(size_t cursor_idx, uint32_t nibble, uint32_t value) const {
    return estimate_tables_[cursor_idx * kEstimateTableSize + 16 * nibble + value];
  }

 private:
  struct Gathered {
    uint32_t frame;
    float lower_squared;
    uint32_t bin;  // estimate bin
  };

  const HashFamily& family_;
  // Sort-value gap to estimate units: an estimate unit is 1 / kEstimateUnitsPerCell2 of a
  // squared cell width.
  float gap_scale_ = 0;
  std::vector<uint16_t> estimate_tables_;
  std::vector<Gathered> gathered_;
  std::vector<Ranked> ranked_;
  std::vector<uint32_t> bin_starts_;
};

}  // namespace motif
