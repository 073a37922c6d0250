// Rows of an archive read in chunks of at least 4,096 frames and kept until a range outside the
// chunk is asked for: the report's figures and player visit instances in archive order, so each
// column block is decoded about once.
// Thread-safety: one cache per thread.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

class FrameChunkCache {
 public:
  // `reader` must outlive the cache.
  explicit FrameChunkCache(const FrameFileReader& reader) : reader_(reader) {}

  // The rows of global frames [global_start, global_end) (global_start < global_end <= the
  // archive's frames), stride() floats a frame; valid until the next call. Errors of the reader.
  Result<const float*> Rows(uint64_t global_start, uint64_t global_end);
  size_t stride() const { return reader_.layout().stride(); }

 private:
  static constexpr uint64_t kChunkFrames = 4096;
  const FrameFileReader& reader_;
  std::vector<float> rows_;
  uint64_t first_ = 0;
  uint64_t count_ = 0;
};

}  // namespace motif
