// Block codec: one column block of a motion archive, the frames [first_frame, +frame_count)
// stored column by column (docs/formats/frame_file.md, "Column block"):
//
//   BlockHeader 24 B | chunk entry x column_count (compressed_bytes u32, raw_bytes u32)
//   | chunk 0 | chunk 1 | ...                 (chunks in column-table order, no padding)
//
// Each chunk is one column encoded by the column codec, so a reader can decode any subset of
// columns. The block's checksum (in the block index) covers all of its bytes. Knows nothing
// about files: it encodes to and decodes from memory.
// Thread-safety: BlockEncoder is used by one thread at a time; DecodeBlock is thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/frame_file/archive_metadata.h"
#include "formats/frame_file/column_codec.h"
#include "formats/frame_file/frame_file_format.h"

namespace motif::frame_file {

class BlockEncoder {
 public:
  BlockEncoder(std::vector<ColumnSpec> columns, uint32_t joint_count, int zstd_level);

  // Encodes `frame_count` rows (row-major, layout stride floats each) as the block of global
  // frames [first_frame, +frame_count) into `out` (replaced). InvalidArgument if a value cannot
  // be encoded (the writer checks values before buffering them, so this is a second line).
  Status Encode(const float* rows, uint32_t frame_count, uint64_t first_frame, std::string* out);

 private:
  std::vector<ColumnSpec> columns_;
  size_t stride_;
  ColumnEncoder encoder_;
  std::vector<float> values_;
  std::string chunks_;
};

// Checks `block_bytes` (the block `handle` points at, already sliced from the file) against its
// checksum and its index entry, and decodes its frames into `rows` (resized to
// handle.frame_count * stride). Corruption: "checksum mismatch", or what does not decode.
// The caller prefixes "<file>: block <n> at offset <hex>".
Status DecodeBlock(const std::vector<ColumnSpec>& columns, uint32_t joint_count,
                   const BlockHandle& handle, const uint8_t* block_bytes, std::vector<float>* rows);

}  // namespace motif::frame_file
