#include "engine/lsh/position_code_ranker.h"

#include <cmath>

namespace motif {

PositionCodeRanker::PositionCodeRanker(const HashFamily& family)
    : family_(family), gap_scale_(std::sqrt(kEstimateUnitsPerCell2) / family.bucket_width()) {}

// The estimate of an entry with code c in `probe`'s bucket: per coded coordinate i, the squared
// distance (in cells) from the query's position x_i to the centre of the entry's quarter of its
// cell (the probe's cell is the query's, one below or one above along i); coordinates beyond
// the coded ones add the squared distance to the crossed boundary, if any (in the first table).
void PositionCodeRanker::FillEstimateTable(const BucketProbe& probe, const float* coordinates,
                                           size_t cursor_idx) {
  const uint32_t hashes = family_.hashes_per_table();
  const uint32_t coded = std::min(hashes, HashFamily::kCodedHashes);
  float terms[HashFamily::kCodedHashes][4] = {};
  for (uint32_t idx = 0; idx < coded; ++idx) {
    const float fraction = coordinates[idx] - std::floor(coordinates[idx]);
    const float offset = (probe.minus_mask >> idx & 1u)  ? -1.0f
                         : (probe.plus_mask >> idx & 1u) ? 1.0f
                                                         : 0.0f;
    for (uint32_t quarter = 0; quarter < 4; ++quarter) {
      const float delta = offset + (static_cast<float>(quarter) + 0.5f) * 0.25f - fraction;
      terms[idx][quarter] = delta * delta * kEstimateUnitsPerCell2;
    }
  }
  float base = 0;
  for (uint32_t idx = coded; idx < hashes; ++idx) {
    const float fraction = coordinates[idx] - std::floor(coordinates[idx]);
    if (probe.minus_mask >> idx & 1u) base += fraction * fraction;
    if (probe.plus_mask >> idx & 1u) base += (1.0f - fraction) * (1.0f - fraction);
  }
  base *= kEstimateUnitsPerCell2;
  if (estimate_tables_.size() < (cursor_idx + 1) * kEstimateTableSize) {
    estimate_tables_.resize((cursor_idx + 1) * kEstimateTableSize);
  }
  uint16_t* table = &estimate_tables_[cursor_idx * kEstimateTableSize];
  for (uint32_t nibble = 0; nibble < 8; ++nibble) {
    const float add = nibble == 0 ? base : 0.0f;
    for (uint32_t value = 0; value < 16; ++value) {
      const float sum = terms[2 * nibble][value & 3] + terms[2 * nibble + 1][value >> 2] + add;
      table[16 * nibble + value] = static_cast<uint16_t>(std::min(std::round(sum), 8000.0f));
    }
  }
}

// A counting sort on the bins.
const std::vector<PositionCodeRanker::Ranked>& PositionCodeRanker::Rank() {
  bin_starts_.assign(kRankBins + 1, 0);
  for (const Gathered& entry : gathered_) ++bin_starts_[entry.bin + 1];
  for (uint32_t bin = 0; bin < kRankBins; ++bin) bin_starts_[bin + 1] += bin_starts_[bin];
  ranked_.resize(gathered_.size());
  for (const Gathered& entry : gathered_) {
    ranked_[bin_starts_[entry.bin]++] = {entry.frame, entry.lower_squared};
  }
  return ranked_;
}

}  // namespace motif
