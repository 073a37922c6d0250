#include "engine/lsh/exclusion_filter.h"

namespace motif {

bool ExclusionFilter::ExcludedNear(uint64_t column, uint32_t clip_of_column, uint32_t frame) const {
  return rules_.Excluded(column, frame, clip_of_column, features_.ClipOf(frame));
}

}  // namespace motif
