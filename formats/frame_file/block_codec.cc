#include "formats/frame_file/block_codec.h"

#include "common/byte_coding.h"

namespace motif::frame_file {
BlockEncoder::BlockEncoder(std::vector<ColumnSpec> columns, uint32_t joint_count, int zstd_level)
    : columns_(std::move(columns)),
      stride_(FrameLayout{joint_count}.stride()),
      encoder_(zstd_level) {}

// Block bytes:
//   header 24 B | entry[c] = compressed_bytes u32, raw_bytes u32 | chunk[0] | chunk[1] | ...
Status BlockEncoder::Encode(const float* rows, uint32_t frame_count, uint64_t first_frame,
                            std::string* out) {
  out->clear();
  BlockHeader header;
  header.column_count = static_cast<uint32_t>(columns_.size());
  header.first_frame = first_frame;
  header.frame_count = frame_count;
  header.EncodeTo(out);
  chunks_.clear();
  for (const ColumnSpec& column : columns_) {
    // Gather component-major: values[component * frame_count + frame].
    values_.resize(static_cast<size_t>(column.component_count) * frame_count);
    for (uint32_t component = 0; component < column.component_count; ++component) {
      float* run = values_.data() + static_cast<size_t>(component) * frame_count;
      const float* source = rows + column.row_offset + component;
      for (uint32_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
        run[frame_idx] = source[frame_idx * stride_];
      }
    }
    const size_t before = chunks_.size();
    MOTIF_RETURN_IF_ERROR(encoder_.Encode(column.encoding, values_.data(), column.component_count,
                                          frame_count, &chunks_));
    PutU32(out, static_cast<uint32_t>(chunks_.size() - before));
    PutU32(out, static_cast<uint32_t>(ChunkRawBytes(column.component_count, frame_count)));
  }
  out->append(chunks_);
  return Status::Ok();
}

Status DecodeBlock(const std::vector<ColumnSpec>& columns, uint32_t joint_count,
                   const BlockHandle& handle, const uint8_t* block_bytes,
                   std::vector<float>* rows) {
  if (Checksum64(block_bytes, handle.bytes) != handle.checksum) {
    return Status::Corruption("checksum mismatch");
  }
  BlockHeader header;
  MOTIF_RETURN_IF_ERROR(BlockHeader::DecodeFrom(block_bytes, handle.bytes, &header));
  if (header.column_count != columns.size() || header.first_frame != handle.first_frame ||
      header.frame_count != handle.frame_count) {
    return Status::Corruption("block header (" + std::to_string(header.column_count) +
                              " columns, frames [" + std::to_string(header.first_frame) + ", +" +
                              std::to_string(header.frame_count) +
                              ")) disagrees with the block index");
  }
  const uint64_t entries_end = kBlockHeaderBytes + kChunkEntryBytes * columns.size();
  if (entries_end > handle.bytes) return Status::Corruption("chunk table runs past the block");
  const size_t stride = FrameLayout{joint_count}.stride();
  const uint32_t frame_count = handle.frame_count;
  rows->resize(static_cast<size_t>(frame_count) * stride);
  std::vector<float> values;
  uint64_t chunk_offset = entries_end;
  for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
    const ColumnSpec& column = columns[column_idx];
    const uint8_t* entry = block_bytes + kBlockHeaderBytes + kChunkEntryBytes * column_idx;
    const uint32_t compressed_bytes = LoadU32(entry);
    const uint32_t raw_bytes = LoadU32(entry + 4);
    const std::string what = "column " + std::to_string(column_idx);
    if (raw_bytes != ChunkRawBytes(column.component_count, frame_count)) {
      return Status::Corruption(what + ": chunk of " + std::to_string(raw_bytes) +
                                " raw bytes, expected " +
                                std::to_string(ChunkRawBytes(column.component_count, frame_count)));
    }
    if (compressed_bytes > handle.bytes - chunk_offset) {
      return Status::Corruption(what + ": chunk runs past the block");
    }
    values.resize(static_cast<size_t>(column.component_count) * frame_count);
    Status decoded =
        DecodeColumnChunk(column.encoding, block_bytes + chunk_offset, compressed_bytes,
                          column.component_count, frame_count, values.data());
    if (!decoded.ok()) return decoded.WithContext(what + " at offset " + Hex(chunk_offset));
    for (uint32_t component = 0; component < column.component_count; ++component) {
      const float* run = values.data() + static_cast<size_t>(component) * frame_count;
      float* target = rows->data() + column.row_offset + component;
      for (uint32_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
        target[frame_idx * stride] = run[frame_idx];
      }
    }
    chunk_offset += compressed_bytes;
  }
  if (chunk_offset != handle.bytes) {
    return Status::Corruption("chunks end at " + std::to_string(chunk_offset) + " of " +
                              std::to_string(handle.bytes) + " block bytes");
  }
  return Status::Ok();
}

}  // namespace motif::frame_file
