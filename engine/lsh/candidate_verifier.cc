#include "engine/lsh/candidate_verifier.h"

#include <algorithm>

namespace motif {

float KeepNearest(uint32_t k_max, float eps, std::vector<Neighbour>* best) {
  if (best->size() < k_max) return eps;
  std::nth_element(best->begin(), best->begin() + (k_max - 1), best->end(), NearerNeighbour());
  best->resize(k_max);
  return std::min(eps, (*best)[k_max - 1].distance);
}

CandidateVerifier::CandidateVerifier(const PoseFeatures& features, const NeighbourRules& rules,
                                     uint32_t visited_capacity)
    : features_(features),
      rules_(rules),
      exclusion_(features, rules),
      distance_(features),
      visited_(visited_capacity) {}

void CandidateVerifier::BeginColumn(uint64_t column, uint64_t max_evaluations,
                                    const ReverseQuery* reverse_query,
                                    std::vector<Neighbour>* reverse) {
  visited_.Clear();
  best_.clear();
  distance_.SetQuery(column);
  column_ = column;
  clip_ = features_.ClipOf(column);
  bound_ = rules_.eps;
  evaluations_ = 0;
  within_eps_ = 0;
  max_evaluations_ = max_evaluations;
  reverse_query_ = reverse_query;
  reverse_ = reverse;
  batch_size_ = 0;
  pending_size_ = 0;
  if (reverse != nullptr) reverse->clear();
}

uint32_t CandidateVerifier::BatchLimit() const {
  const uint64_t room = max_evaluations_ - evaluations_ - pending_size_;
  return static_cast<uint32_t>(std::min<uint64_t>(kVerifyBatch, room));
}

// Done when twice k_max have been accepted (amortised O(1) per candidate, where a heap would
// pay O(log k_max) on every improvement), and when a decision needs the exact radius.
void CandidateVerifier::Prune() { bound_ = KeepNearest(rules_.k_max, rules_.eps, &best_); }

void CandidateVerifier::Verify(const uint32_t* candidates, uint32_t count) {
  const float eps = rules_.eps;
  const size_t prune_at = 2 * static_cast<size_t>(rules_.k_max);
  // For the reverse neighbours every distance up to eps is needed exactly; a distance within the
  // bound is the same either way (the joints are summed in the same order).
  float distances[kVerifyBatch];
  distance_.ToBatch(candidates, count, reverse_ != nullptr ? eps : bound_, distances);
  // Counted in locals (registers) and stored once: best_.push_back may allocate.
  float bound = bound_;
  uint64_t within_eps = 0;
  for (uint32_t idx = 0; idx < count; ++idx) {
    const float distance = distances[idx];
    if (reverse_ != nullptr && candidates[idx] < reverse_query_->frame_limit && distance <= eps &&
        (reverse_query_->thresholds == nullptr ||
         distance <= reverse_query_->thresholds[candidates[idx]])) {
      reverse_->push_back({candidates[idx], distance});
    }
    // A value above the bound may be a partial sum: it only says D > bound. capped_columns
    // counts a column when more than k_max candidates came out at or below eps this way.
    if (distance <= eps) ++within_eps;
    if (distance > bound) continue;  // cannot enter the column (bound <= eps)
    best_.push_back({candidates[idx], distance});
    if (best_.size() >= prune_at) {
      Prune();
      bound = bound_;
    }
  }
  evaluations_ += count;
  within_eps_ += within_eps;
}

void CandidateVerifier::Flush() {
  Verify(pending_, pending_size_);
  std::copy(batch_, batch_ + batch_size_, pending_);
  pending_size_ = batch_size_;
  batch_size_ = 0;
}

void CandidateVerifier::VerifyGathered() {
  Drain();
  Prune();
}

}  // namespace motif
