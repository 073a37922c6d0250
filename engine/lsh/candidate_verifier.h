// CandidateVerifier: the exact verification of one column's candidates, and the column it
// builds (docs/design/lsh.md, section 3, steps 4 and 5). Candidates are gathered in batches of
// kVerifyBatch whose features are prefetched one batch ahead (a candidate's features are a random
// access into the archive, and overlapping those misses is most of the speed of the
// verification), then verified with QueryDistance, the exact D bit for bit. The accepted ones,
// within the column's radius, are cut back to the k_max nearest whenever 2 k_max have
// accumulated; the radius is then min(eps, the k_max-th distance): "search the nearest first,
// shrink the radius, stop". A budget bounds the evaluations of a column.
// With a ReverseQuery the verifier also reports the older frames whose own columns a candidate
// may enter: every candidate is then verified up to eps, not only up to the shrinking radius
// (a distance within the radius is the same either way: the joints are summed in the same order).
// Owns the column's state, its visited set (so a frame found in several tables or as a seed is
// verified once) and its QueryDistance; refers to the features and the rules.
// Thread-safety: one per query worker.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/exclusion_filter.h"
#include "engine/lsh/query_distance.h"
#include "engine/lsh/visited_set.h"

namespace motif {

// Candidates verified at once (a batch; the next one is prefetched meanwhile).
inline constexpr uint32_t kVerifyBatch = 16;

// Keeps the k_max nearest of *best (unordered: distance, then lower frame) once it holds k_max or
// more; returns the radius nothing farther can enter: min(eps, the k_max-th distance), or eps
// while *best is not full.
float KeepNearest(uint32_t k_max, float eps, std::vector<Neighbour>* best);

// The order of a column's neighbours when it is cut to k_max: nearer first, then lower frame.
struct NearerNeighbour {
  bool operator()(const Neighbour& a, const Neighbour& b) const {
    return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
  }
};

class CandidateVerifier {
 public:
  // `visited_capacity`: the frames a column may insert before its visited set grows.
  CandidateVerifier(const PoseFeatures& features, const NeighbourRules& rules,
                    uint32_t visited_capacity);

  // Starts column `column` with a budget of `max_evaluations`: nothing accepted, radius eps. With
  // `reverse_query`, *reverse is cleared and receives the verified frames below its frame limit
  // within eps and their thresholds.
  void BeginColumn(uint64_t column, uint64_t max_evaluations,
                   const ReverseQuery* reverse_query = nullptr,
                   std::vector<Neighbour>* reverse = nullptr);
  // Changes the column's budget (a chained column's after its seeds).
  void SetBudget(uint64_t max_evaluations) { max_evaluations_ = max_evaluations; }

  // The column itself and its own clip's temporal neighbourhood are never candidates.
  bool Excluded(uint32_t frame) const { return exclusion_.Excluded(column_, clip_, frame); }
  // True the first time `frame` is offered in this column (and marks it).
  bool FirstVisit(uint32_t frame) { return visited_.Insert(frame); }

  // Adds a candidate to the batch, prefetching its features; the caller keeps the batch within
  // BatchLimit() and flushes it.
  void AddToBatch(uint32_t frame) {
    distance_.Prefetch(frame);
    batch_[batch_size_++] = frame;
  }
  // Adds a candidate to the batch, flushing a full batch.
  void Gather(uint32_t frame) {
    AddToBatch(frame);
    if (batch_size_ == kVerifyBatch) Flush();
  }
  // The size the batch may reach without going past the budget: min(kVerifyBatch, budget left
  // after the evaluations done and the pending batch). Stays fixed until the next Flush.
  uint32_t BatchLimit() const;
  uint32_t batch_size() const { return batch_size_; }
  // Verifies the pending batch and makes the gathered one pending.
  void Flush();
  // Verifies everything gathered and pending (without cutting to k_max).
  void Drain() {
    Flush();
    Flush();
  }
  // Verifies everything gathered and brings the radius up to date (k_max nearest kept).
  void VerifyGathered();
  // True once the evaluations done, pending and gathered reach the budget.
  bool BudgetReached() const {
    return evaluations_ + pending_size_ + batch_size_ >= max_evaluations_;
  }

  uint64_t column() const { return column_; }
  // Nothing farther than this can enter the column: min(eps, the k_max-th distance accepted).
  float bound() const { return bound_; }
  uint64_t evaluations() const { return evaluations_; }
  // Candidates verified at a distance <= eps (a column with more than k_max of them is capped).
  uint64_t within_eps() const { return within_eps_; }
  // The accepted candidates, unordered: at most 2 k_max, the k_max nearest among them (after
  // VerifyGathered, at most k_max).
  const std::vector<Neighbour>& accepted() const { return best_; }

 private:
  // Keeps the k_max nearest accepted so far and sets the radius to the k_max-th distance.
  void Prune();
  // Verifies `count` candidates: the accepted ones go to best_, the reverse ones to the reverse.
  void Verify(const uint32_t* candidates, uint32_t count);

  const PoseFeatures& features_;
  const NeighbourRules& rules_;
  ExclusionFilter exclusion_;
  QueryDistance distance_;
  VisitedSet visited_;
  std::vector<Neighbour> best_;  // accepted candidates: the k_max nearest of them are kept

  uint64_t column_ = 0;
  uint32_t clip_ = 0;
  float bound_ = 0;
  uint64_t evaluations_ = 0;
  uint64_t within_eps_ = 0;
  uint64_t max_evaluations_ = 0;
  const ReverseQuery* reverse_query_ = nullptr;
  std::vector<Neighbour>* reverse_ = nullptr;  // the column's reverse frames, or null
  uint32_t batch_[kVerifyBatch];               // being gathered
  uint32_t pending_[kVerifyBatch];  // gathered and prefetched: verified at the next Flush
  uint32_t batch_size_ = 0;
  uint32_t pending_size_ = 0;
};

}  // namespace motif
