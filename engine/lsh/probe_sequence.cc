#include "engine/lsh/probe_sequence.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <queue>

namespace motif {
namespace {

// A boundary of the query's cell along one coordinate, at a squared distance in cells.
struct CellBoundary {
  float squared = 0;
  uint32_t coordinate = 0;
  int32_t step = 0;  // -1 (the cell below) or +1 (the cell above)
};

// The query's cell along each of the `hashes` coordinates into `cells`, and the 2 * hashes
// boundaries of that cell into `boundaries`, nearest first (ties: lower coordinate, then below).
void SortCellBoundaries(const float* coordinates, uint32_t hashes, int32_t* cells,
                        CellBoundary* boundaries) {
  for (uint32_t idx = 0; idx < hashes; ++idx) {
    const float floor_value = std::floor(coordinates[idx]);
    cells[idx] = static_cast<int32_t>(floor_value);
    const float below = coordinates[idx] - floor_value;
    const float above = 1.0f - below;
    boundaries[2 * idx] = {below * below, idx, -1};
    boundaries[2 * idx + 1] = {above * above, idx, +1};
  }
  std::sort(boundaries, boundaries + 2 * hashes, [](const CellBoundary& a, const CellBoundary& b) {
    if (a.squared != b.squared) return a.squared < b.squared;
    return a.coordinate < b.coordinate || (a.coordinate == b.coordinate && a.step < b.step);
  });
}

// A perturbation set: a bit mask over the sorted boundaries (at most 64), its score (the sum of
// its members' squared distances) and its largest member.
struct PerturbationSet {
  float score;
  uint64_t members;
  uint32_t largest;
};

// The heap's order: the lowest score on top (ties: the lower mask).
struct LaterPerturbationSet {
  bool operator()(const PerturbationSet& a, const PerturbationSet& b) const {
    if (a.score != b.score) return a.score > b.score;
    return a.members > b.members;
  }
};

using PerturbationHeap =
    std::priority_queue<PerturbationSet, std::vector<PerturbationSet>, LaterPerturbationSet>;

// The two successors of a set: "shift" (its largest member replaced by the next boundary) and
// "expand" (the next boundary added). Every set is generated once, in increasing score.
void PushSuccessors(const PerturbationSet& set, const CellBoundary* boundaries,
                    uint32_t boundary_count, PerturbationHeap* heap) {
  if (set.largest + 1 >= boundary_count) return;
  const uint32_t next = set.largest + 1;
  const float next_squared = boundaries[next].squared;
  heap->push({set.score - boundaries[set.largest].squared + next_squared,
              (set.members & ~(uint64_t{1} << set.largest)) | (uint64_t{1} << next), next});
  heap->push({set.score + next_squared, set.members | (uint64_t{1} << next), next});
}

// The cells of the bucket a set moves to, and which coordinates move down or up. False if the
// set moves one coordinate both ways (no such bucket).
bool PerturbCells(uint64_t members, const CellBoundary* boundaries, const int32_t* cells,
                  uint32_t hashes, int32_t* perturbed, uint32_t* minus_mask, uint32_t* plus_mask) {
  uint32_t used = 0;
  std::copy(cells, cells + hashes, perturbed);
  for (; members != 0; members &= members - 1) {
    const CellBoundary& boundary = boundaries[std::countr_zero(members)];
    if (used & (1u << boundary.coordinate)) return false;
    used |= 1u << boundary.coordinate;
    perturbed[boundary.coordinate] += boundary.step;
    (boundary.step < 0 ? *minus_mask : *plus_mask) |= 1u << boundary.coordinate;
  }
  return true;
}

}  // namespace

bool ProbeBefore(const BucketProbe& a, const BucketProbe& b) {
  if (a.score != b.score) return a.score < b.score;
  if (a.table_idx != b.table_idx) return a.table_idx < b.table_idx;
  return a.rank < b.rank;
}

ProbeSequence::ProbeSequence(const HashFamily& family, const LshIndex& index)
    : family_(family),
      index_(index),
      embedding_(family.embedding_dims()),
      projections_(static_cast<size_t>(family.table_count()) * (family.hashes_per_table() + 1)),
      query_sort_values_(family.table_count()) {}

void ProbeSequence::Prepare(const int16_t* frame, uint32_t probes_per_table) {
  family_.Embed(frame, embedding_.data());
  family_.Project(embedding_.data(), projections_.data());
  for (uint32_t table_idx = 0; table_idx < family_.table_count(); ++table_idx) {
    query_sort_values_[table_idx] =
        family_.QuantiseSortValue(coordinates(table_idx)[family_.hashes_per_table()]);
  }
  probes_.clear();
  AddProbes(probes_per_table, 0);
}

void ProbeSequence::AddProbes(uint32_t wanted, uint32_t skip) {
  const size_t first = probes_.size();
  for (uint32_t table_idx = 0; table_idx < family_.table_count(); ++table_idx) {
    ListProbes(table_idx, wanted, skip);
  }
  std::sort(probes_.begin() + first, probes_.end(), ProbeBefore);
  // The buckets are looked up in this order later: start fetching their directory slots and
  // keys now, so that the lookups' cache misses overlap.
  for (size_t idx = first; idx < probes_.size(); ++idx) {
    index_.PrefetchDirectory(probes_[idx].table_idx, probes_[idx].key);
  }
  for (size_t idx = first; idx < probes_.size(); ++idx) {
    index_.PrefetchKeys(probes_[idx].table_idx, probes_[idx].key);
  }
}

// Query-directed probing (Lv et al. 2007): perturbation sets of the 2m boundaries of the query's
// cell are generated in increasing score by a heap, skipping sets that move one coordinate both
// ways.
void ProbeSequence::ListProbes(uint32_t table_idx, uint32_t wanted, uint32_t skip) {
  const uint32_t hashes = family_.hashes_per_table();
  int32_t cells[HashFamily::kMaxHashesPerTable];
  CellBoundary boundaries[2 * HashFamily::kMaxHashesPerTable];
  SortCellBoundaries(coordinates(table_idx), hashes, cells, boundaries);
  if (skip == 0) {
    probes_.push_back({0.0f, table_idx, 0, HashFamily::BucketKey(cells, hashes), 0, 0});
  }
  if (wanted <= 1) return;
  PerturbationHeap heap;
  heap.push({boundaries[0].squared, 1, 0});
  uint32_t emitted = 1;
  const float width_squared = family_.bucket_width() * family_.bucket_width();
  // Each pop pushes at most two sets; bounding pops bounds the work when most sets are invalid.
  for (uint32_t pops = 0; emitted < wanted && !heap.empty() && pops < 8 * wanted; ++pops) {
    const PerturbationSet set = heap.top();
    heap.pop();
    PushSuccessors(set, boundaries, 2 * hashes, &heap);
    int32_t perturbed[HashFamily::kMaxHashesPerTable];
    uint32_t minus_mask = 0;
    uint32_t plus_mask = 0;
    if (!PerturbCells(set.members, boundaries, cells, hashes, perturbed, &minus_mask, &plus_mask)) {
      continue;
    }
    if (emitted >= skip) {
      probes_.push_back({set.score * width_squared, table_idx, emitted,
                         HashFamily::BucketKey(perturbed, hashes), minus_mask, plus_mask});
    }
    ++emitted;
  }
}

}  // namespace motif
