// InstanceIntervalIndex: which instances contain a given frame (a stabbing query), for reading
// instance similarities back from the trellis: a column's neighbours are frames, and each frame
// counts for the instances whose range holds it.
// The instance boundaries cut the frame axis into elementary segments; each segment stores the
// ids of the instances covering it (built by one sweep). A query is a binary search for the
// segment; the cursor form answers ascending queries (a column's neighbours are sorted by frame
// and come in runs) in O(1) while they stay in the same segment.
// Memory: O(boundaries + Σ coverage), O(instances) when merged instances overlap little.
// Thread-safety: immutable after construction; a Cursor belongs to one thread.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/cluster/motif_instance.h"

namespace motif {

class InstanceIntervalIndex {
 public:
  explicit InstanceIntervalIndex(const std::vector<MotifInstance>& instances);

  // Ids of the instances whose range contains `frame`, ascending.
  std::span<const uint32_t> Containing(uint64_t frame) const;

  // For queries in ascending frame order (restart with Reset() for a new ascending sequence).
  class Cursor {
   public:
    explicit Cursor(const InstanceIntervalIndex& index) : index_(&index) {}
    void Reset() { segment_ = 0; }
    std::span<const uint32_t> Containing(uint64_t frame);

   private:
    const InstanceIntervalIndex* index_;
    size_t segment_ = 0;
  };

 private:
  // Segment s is [boundaries_[s], boundaries_[s + 1]); its ids are
  // ids_[offsets_[s], offsets_[s + 1]).
  std::span<const uint32_t> SegmentIds(size_t segment) const;
  size_t SegmentOf(uint64_t frame, size_t from) const;  // SIZE_MAX outside every segment

  std::vector<uint64_t> boundaries_;
  std::vector<uint64_t> offsets_;
  std::vector<uint32_t> ids_;
};

}  // namespace motif
