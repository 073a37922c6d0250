// ExclusionFilter: whether a frame may never be a candidate of a column: the column itself, and
// the frames of its own clip within the exclusion radius (NeighbourRules::Excluded, the trellis's
// trivial matches). Every bucket entry a query reads is tested, so the common case, a frame
// farther from the column than the radius, costs one comparison, inlined; the near case looks up
// clips out of line.
// Thread-safety: immutable; const methods are safe from many threads. Refers to the features and
// rules, which must outlive it.
#pragma once

#include <algorithm>
#include <cstdint>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"

namespace motif {

class ExclusionFilter {
 public:
  ExclusionFilter(const PoseFeatures& features, const NeighbourRules& rules)
      : features_(features), rules_(rules), floor_(std::max(rules.exclusion_frames, 1u)) {}

  // NeighbourRules::Excluded(column, frame, clip_of_column, ClipOf(frame)); `clip_of_column` is
  // features.ClipOf(column).
  [[gnu::always_inline]] bool Excluded(uint64_t column, uint32_t clip_of_column,
                                       uint32_t frame) const {
    const uint64_t frame_gap = frame > column ? frame - column : column - frame;
    return frame_gap < floor_ && ExcludedNear(column, clip_of_column, frame);
  }

 private:
  bool ExcludedNear(uint64_t column, uint32_t clip_of_column, uint32_t frame) const;

  const PoseFeatures& features_;
  const NeighbourRules& rules_;
  uint32_t floor_ = 1;  // frames nearer the column than this may be excluded
};

}  // namespace motif
