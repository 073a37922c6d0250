#include "engine/lsh/chain_sweep.h"

#include <algorithm>

#include "engine/lsh/candidate_verifier.h"

namespace motif {

ChainSweep::ChainSweep(const PoseFeatures& features, const NeighbourRules& rules,
                       uint32_t chain_advance)
    : features_(features),
      rules_(rules),
      advance_(chain_advance),
      exclusion_(features, rules),
      distance_(features) {}

void ChainSweep::Sweep(uint64_t column, const std::vector<Neighbour>& from, int direction,
                       std::vector<Neighbour>* out, ColumnWork* work) {
  const uint32_t k_max = rules_.k_max;
  CollectCandidates(column, from, direction, *out);
  if (candidates_.empty()) return;
  // Nothing farther than the column's k_max-th neighbour can enter it.
  float bound = rules_.eps;
  if (out->size() >= k_max) {
    float farthest = 0;
    for (const Neighbour& neighbour : *out) farthest = std::max(farthest, neighbour.distance);
    bound = std::min(rules_.eps, farthest);
  }
  distance_.SetQuery(column);
  const uint64_t within_eps = VerifyCandidates(bound);
  const size_t count = candidates_.size();
  work->evaluations += count;
  work->lsh.sweep_evaluations += count;
  // The column's own frames and the new ones within eps are distinct frames within eps.
  work->capped = work->capped || out->size() + within_eps > k_max;
  if (accepted_.empty()) return;
  MergeAccepted(out);
}

void ChainSweep::CollectCandidates(uint64_t column, const std::vector<Neighbour>& from,
                                   int direction, const std::vector<Neighbour>& held) {
  const int64_t frame_count = static_cast<int64_t>(features_.frame_count());
  const uint32_t clip_of_column = features_.ClipOf(column);
  candidates_.clear();
  size_t held_idx = 0;
  int64_t next = 0;  // frames below this were considered already
  for (const Neighbour& neighbour : from) {
    const int64_t frame = neighbour.frame;
    const int64_t low = std::max(next, direction > 0 ? frame - advance_ : frame);
    const int64_t high = std::min(frame_count - 1, direction > 0 ? frame : frame + advance_);
    for (int64_t candidate = low; candidate <= high; ++candidate) {
      while (held_idx < held.size() && held[held_idx].frame < candidate) ++held_idx;
      if (held_idx < held.size() && held[held_idx].frame == candidate) continue;
      if (exclusion_.Excluded(column, clip_of_column, static_cast<uint32_t>(candidate))) continue;
      candidates_.push_back(static_cast<uint32_t>(candidate));
    }
    next = std::max(next, high + 1);
  }
}

uint64_t ChainSweep::VerifyCandidates(float bound) {
  const float eps = rules_.eps;
  float distances[kVerifyBatch];
  uint64_t within_eps = 0;
  accepted_.clear();
  const size_t count = candidates_.size();
  for (size_t idx = 0; idx < std::min<size_t>(kVerifyBatch, count); ++idx) {
    distance_.Prefetch(candidates_[idx]);
  }
  for (size_t first = 0; first < count; first += kVerifyBatch) {
    const uint32_t batch = static_cast<uint32_t>(std::min<size_t>(kVerifyBatch, count - first));
    for (size_t idx = first + kVerifyBatch; idx < std::min(count, first + 2 * kVerifyBatch);
         ++idx) {
      distance_.Prefetch(candidates_[idx]);  // the next batch, while this one is verified
    }
    distance_.ToBatch(&candidates_[first], batch, bound, distances);
    for (uint32_t idx = 0; idx < batch; ++idx) {
      if (distances[idx] <= eps) ++within_eps;
      if (distances[idx] <= bound) accepted_.push_back({candidates_[first + idx], distances[idx]});
    }
  }
  return within_eps;
}

// The same column as FinishColumn over both, without its sort.
void ChainSweep::MergeAccepted(std::vector<Neighbour>* out) {
  const uint32_t k_max = rules_.k_max;
  merged_.resize(out->size() + accepted_.size());
  std::merge(out->begin(), out->end(), accepted_.begin(), accepted_.end(), merged_.begin(),
             [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
  if (merged_.size() > k_max) {
    accepted_.assign(merged_.begin(), merged_.end());
    std::nth_element(accepted_.begin(), accepted_.begin() + (k_max - 1), accepted_.end(),
                     NearerNeighbour());
    const Neighbour cut = accepted_[k_max - 1];  // the k_max-th nearest: it and all nearer stay
    merged_.erase(std::remove_if(merged_.begin(), merged_.end(),
                                 [&](const Neighbour& n) { return NearerNeighbour()(cut, n); }),
                  merged_.end());
  }
  out->swap(merged_);
}

}  // namespace motif
