#include "bench/bench_trellises.h"

#include <algorithm>

namespace motif::bench {
RandomWalkTrellis::RandomWalkTrellis(uint64_t frame_count, uint32_t k)
    : frame_count_(frame_count),
      k_(k),
      rng_(frame_count * 1000 + k),
      walkers_(std::max<uint32_t>(1, k / 2 / kRun)) {
  for (Walker& walker : walkers_) Respawn(&walker);
}

void RandomWalkTrellis::NextBlock(uint64_t first_column, uint64_t count,
                                  std::vector<std::vector<Neighbour>>* block) {
  block->resize(count);
  for (uint64_t column_idx = first_column; column_idx < first_column + count; ++column_idx) {
    frames_.clear();
    for (Walker& walker : walkers_) {
      for (uint32_t offset = 0; offset < kRun && walker.frame + offset < frame_count_; ++offset) {
        frames_.push_back(static_cast<uint32_t>(walker.frame + offset));
      }
      walker.frame += rng_() % 3;
      if (--walker.columns_left == 0 || walker.frame >= frame_count_) Respawn(&walker);
    }
    // The walkers' runs and the noise are sorted apart and merged: the same column as one
    // sort of both, in about half the time (the runs are nearly sorted already).
    const size_t walker_frames = frames_.size();
    while (frames_.size() < k_) frames_.push_back(static_cast<uint32_t>(rng_() % frame_count_));
    std::sort(frames_.begin(), frames_.begin() + walker_frames);
    std::sort(frames_.begin() + walker_frames, frames_.end());
    merged_.resize(frames_.size());
    std::merge(frames_.begin(), frames_.begin() + walker_frames, frames_.begin() + walker_frames,
               frames_.end(), merged_.begin());
    merged_.erase(std::unique(merged_.begin(), merged_.end()), merged_.end());
    std::vector<Neighbour>& column = (*block)[column_idx - first_column];
    column.resize(merged_.size());
    for (size_t node_idx = 0; node_idx < merged_.size(); ++node_idx) {
      column[node_idx] = {merged_[node_idx], 0.5f};
    }
  }
}

void RandomWalkTrellis::Respawn(Walker* walker) {
  walker->frame = rng_() % frame_count_;
  walker->columns_left = 100 + rng_() % 401;
}

}  // namespace motif::bench
