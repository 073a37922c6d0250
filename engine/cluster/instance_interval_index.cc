#include "engine/cluster/instance_interval_index.h"

#include <algorithm>
#include <limits>

namespace motif {

InstanceIntervalIndex::InstanceIntervalIndex(const std::vector<MotifInstance>& instances) {
  for (const MotifInstance& instance : instances) {
    if (instance.end <= instance.start) continue;
    boundaries_.push_back(instance.start);
    boundaries_.push_back(instance.end);
  }
  std::sort(boundaries_.begin(), boundaries_.end());
  boundaries_.erase(std::unique(boundaries_.begin(), boundaries_.end()), boundaries_.end());
  const size_t segment_count = boundaries_.empty() ? 0 : boundaries_.size() - 1;

  // Sweep: an instance covers the segments from the one starting at its start up to the one
  // ending at its end. Count first, then fill, so ids_ is allocated once.
  std::vector<uint64_t> coverage(segment_count + 1, 0);
  auto segment_at = [&](uint64_t boundary) {
    return static_cast<size_t>(std::lower_bound(boundaries_.begin(), boundaries_.end(), boundary) -
                               boundaries_.begin());
  };
  for (const MotifInstance& instance : instances) {
    if (instance.end <= instance.start) continue;
    for (size_t seg = segment_at(instance.start), last = segment_at(instance.end); seg < last;
         ++seg) {
      ++coverage[seg];
    }
  }
  offsets_.assign(segment_count + 1, 0);
  for (size_t seg = 0; seg < segment_count; ++seg)
    offsets_[seg + 1] = offsets_[seg] + coverage[seg];
  ids_.resize(offsets_.empty() ? 0 : offsets_.back());
  std::vector<uint64_t> fill(offsets_.begin(), offsets_.end());
  for (size_t id = 0; id < instances.size(); ++id) {  // ascending ids within each segment
    const MotifInstance& instance = instances[id];
    if (instance.end <= instance.start) continue;
    for (size_t seg = segment_at(instance.start), last = segment_at(instance.end); seg < last;
         ++seg) {
      ids_[fill[seg]++] = static_cast<uint32_t>(id);
    }
  }
}

std::span<const uint32_t> InstanceIntervalIndex::SegmentIds(size_t segment) const {
  return {ids_.data() + offsets_[segment], ids_.data() + offsets_[segment + 1]};
}

size_t InstanceIntervalIndex::SegmentOf(uint64_t frame, size_t from) const {
  if (boundaries_.size() < 2 || frame < boundaries_.front() || frame >= boundaries_.back()) {
    return std::numeric_limits<size_t>::max();
  }
  auto it = std::upper_bound(boundaries_.begin() + static_cast<ptrdiff_t>(from), boundaries_.end(),
                             frame);
  return static_cast<size_t>(it - boundaries_.begin()) - 1;
}

std::span<const uint32_t> InstanceIntervalIndex::Containing(uint64_t frame) const {
  const size_t segment = SegmentOf(frame, 0);
  if (segment == std::numeric_limits<size_t>::max()) return {};
  return SegmentIds(segment);
}

std::span<const uint32_t> InstanceIntervalIndex::Cursor::Containing(uint64_t frame) {
  const std::vector<uint64_t>& bounds = index_->boundaries_;
  if (bounds.size() < 2 || frame < bounds.front() || frame >= bounds.back()) return {};
  // Still in the current segment (the common case inside a run), else search onwards from it.
  if (!(bounds[segment_] <= frame && frame < bounds[segment_ + 1])) {
    segment_ = index_->SegmentOf(frame, frame >= bounds[segment_] ? segment_ : 0);
  }
  return index_->SegmentIds(segment_);
}

}  // namespace motif
