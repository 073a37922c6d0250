// VisitedSet: the frames a column's query has verified already (LshSearch), so that a frame
// found in several tables or as a seed is verified once.
// Thread-safety: none; one per query worker.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace motif {

// Frames already verified in this column: open addressing with a generation stamp, so clearing
// is O(1) and the size is bounded by the evaluation budget, not by N. Sized so that `max_entries`
// inserts fill it at most two-thirds; past three-quarters (the reverse scan's seeds are outside
// any budget) it doubles rather than fill up.
class VisitedSet {
 public:
  explicit VisitedSet(uint32_t max_entries) {
    // A table small enough to stay in L2 (128 KB for the default budgets).
    Allocate(std::bit_ceil(std::max<uint32_t>(64, max_entries + max_entries / 2 + 2)));
  }
  void Clear() {
    size_ = 0;
    if (++stamp_ == 0) {  // wrapped: really clear once every 2^32 columns
      std::fill(slots_.begin(), slots_.end(), Slot{});
      stamp_ = 1;
    }
  }
  // Slots allocated (a power of two).
  uint32_t capacity() const { return mask_ + 1; }
  // True if `frame` was not in the set (and adds it).
  bool Insert(uint32_t frame) {
    uint32_t slot = SlotOf(frame);
    while (slots_[slot].stamp == stamp_) {
      if (slots_[slot].frame == frame) return false;
      slot = (slot + 1) & mask_;
    }
    slots_[slot] = Slot{frame, stamp_};
    if (++size_ > mask_ / 4 * 3) Grow();
    return true;
  }

 private:
  struct Slot {  // frame and stamp side by side: one cache line per probe of the set
    uint32_t frame = 0;
    uint32_t stamp = 0;
  };
  uint32_t SlotOf(uint32_t frame) const {
    return (frame * 0x9e3779b1u) >> shift_;  // Fibonacci hashing: the high bits
  }
  void Allocate(uint32_t capacity) {
    slots_.assign(capacity, Slot{});
    shift_ = 32 - static_cast<uint32_t>(std::countr_zero(capacity));
    mask_ = capacity - 1;
  }
  // Twice the slots, the current column's frames inserted again.
  void Grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    Allocate(static_cast<uint32_t>(old.size() * 2));
    for (const Slot& entry : old) {
      if (entry.stamp != stamp_) continue;
      uint32_t slot = SlotOf(entry.frame);
      while (slots_[slot].stamp == stamp_) slot = (slot + 1) & mask_;
      slots_[slot] = entry;
    }
  }
  std::vector<Slot> slots_;
  uint32_t shift_ = 0;
  uint32_t mask_ = 0;
  uint32_t stamp_ = 1;
  uint32_t size_ = 0;  // frames inserted since Clear()
};

}  // namespace motif
