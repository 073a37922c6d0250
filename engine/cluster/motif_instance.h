// MotifInstance and InstanceLink: the units clustering works on. An instance is a global frame
// range of the archive (half-open [start, end)); it never spans two clips, because the path
// grower kills a path at a clip boundary and keeps matched segments inside one clip. A link says
// that a path joined two instances (its top-row segment and its matched segment): the strongest
// evidence that they are the same motif.
// Thread-safety: value types.
#pragma once

#include <cstdint>

namespace motif {

struct MotifInstance {
  uint64_t start = 0;  // first global frame
  uint64_t end = 0;    // one past the last

  uint64_t length() const { return end - start; }
  bool operator==(const MotifInstance& other) const = default;
};

// Frames the two ranges share.
inline uint64_t OverlapFrames(const MotifInstance& a, const MotifInstance& b) {
  const uint64_t start = a.start > b.start ? a.start : b.start;
  const uint64_t end = a.end < b.end ? a.end : b.end;
  return end > start ? end - start : 0;
}

// Two instances (ids into an instance list) joined by a path; a < b.
struct InstanceLink {
  uint32_t a = 0;
  uint32_t b = 0;

  bool operator==(const InstanceLink& other) const = default;
  bool operator<(const InstanceLink& other) const {
    return a != other.a ? a < other.a : b < other.b;
  }
};

}  // namespace motif
