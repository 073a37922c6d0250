#include "engine/report/frame_chunk_cache.h"

#include <algorithm>

namespace motif {

Result<const float*> FrameChunkCache::Rows(uint64_t global_start, uint64_t global_end) {
  if (global_start < first_ || global_end > first_ + count_) {
    const uint64_t count = std::min(std::max(global_end - global_start, kChunkFrames),
                                    reader_.frame_count() - global_start);
    MOTIF_RETURN_IF_ERROR(reader_.ReadFrames(global_start, count, &rows_));
    first_ = global_start;
    count_ = count;
  }
  return rows_.data() + (global_start - first_) * stride();
}

}  // namespace motif
