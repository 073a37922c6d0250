#include "formats/trellis_file/trellis_block_codec.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include <zstd.h>

namespace motif::trellis_file {
namespace {

// LEB128: 7 bits a byte, least significant group first, high bit set on all bytes but the last.
inline void PutVarint(std::string* out, uint64_t value) {
  char buffer[10];
  size_t size = 0;
  while (value >= 0x80) {
    buffer[size++] = static_cast<char>(value | 0x80);
    value >>= 7;
  }
  buffer[size++] = static_cast<char>(value);
  out->append(buffer, size);
}

// Reads one varint of at most 10 bytes that fits in 64 bits; false at the end of the input or on
// an overlong encoding.
inline bool GetVarint(const uint8_t** cursor, const uint8_t* end, uint64_t* value) {
  const uint8_t* p = *cursor;
  if (p < end && *p < 0x80) {  // the common case: one byte
    *value = *p;
    *cursor = p + 1;
    return true;
  }
  uint64_t result = 0;
  for (int shift = 0; shift < 64 && p < end; shift += 7) {
    const uint8_t byte = *p++;
    if (shift == 63 && byte > 1) return false;  // bits beyond 64
    result |= static_cast<uint64_t>(byte & 0x7F) << shift;
    if (byte < 0x80) {
      *value = result;
      *cursor = p;
      return true;
    }
  }
  return false;
}

inline uint64_t ZigZag64(int64_t value) {
  return (static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63);
}
inline int64_t UnZigZag64(uint64_t code) {
  return static_cast<int64_t>(code >> 1) ^ -static_cast<int64_t>(code & 1);
}
inline uint16_t ZigZag16(uint16_t residual) {
  return static_cast<uint16_t>((residual << 1) ^ (0u - (residual >> 15)));
}
inline uint16_t UnZigZag16(uint16_t code) {
  return static_cast<uint16_t>((code >> 1) ^ (0u - (code & 1u)));
}

// Prediction of entry i of a column from the codes before it (mod 2^16): the linear extrapolation
// 2 q[i-1] - q[i-2] when frames i-2, i-1, i are consecutive, q[i-1] after any earlier entry, 0
// for the first. `run` is how many consecutive frames end at entry i (1 at a run's start).
inline uint16_t Predict(uint32_t run, size_t index_in_column, uint16_t previous,
                        uint16_t before_previous) {
  if (run >= 3) return static_cast<uint16_t>(2u * previous - before_previous);
  return index_in_column == 0 ? 0 : previous;
}

Status ZstdError(const char* what, size_t code) {
  return Status::IOError(std::string("zstd ") + what + ": " + ZSTD_getErrorName(code));
}

// The id section: per column its run count, then per run the start (the first run's zigzagged
// against `reference`, the column's expected first frame; a later run's as the gap after the
// previous run) and length - 1.
void EncodeIdSection(uint64_t first_column, const std::vector<std::vector<Neighbour>>& columns,
                     std::string* ids) {
  ids->clear();
  uint64_t reference = first_column;
  for (const std::vector<Neighbour>& column : columns) {
    uint64_t run_count = 0;
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
      if (entry_idx == 0 || column[entry_idx].frame != column[entry_idx - 1].frame + 1) {
        ++run_count;
      }
    }
    PutVarint(ids, run_count);
    uint64_t previous_last = 0;
    for (size_t run_begin = 0; run_begin < column.size();) {
      size_t run_end = run_begin + 1;
      while (run_end < column.size() && column[run_end].frame == column[run_end - 1].frame + 1) {
        ++run_end;
      }
      const uint64_t start = column[run_begin].frame;
      if (run_begin == 0) {
        PutVarint(ids, ZigZag64(static_cast<int64_t>(start) - static_cast<int64_t>(reference)));
      } else {
        PutVarint(ids, start - (previous_last + 2));
      }
      PutVarint(ids, run_end - run_begin - 1);
      previous_last = column[run_end - 1].frame;
      run_begin = run_end;
    }
    reference = (column.empty() ? reference : column[0].frame) + 1;
  }
}

// The distance section: zigzagged prediction residuals as a low-byte plane and a high-byte plane.
void EncodeDistanceSection(const std::vector<std::vector<Neighbour>>& columns, float eps,
                           uint64_t neighbour_count, std::string* distances) {
  distances->assign(2 * neighbour_count, '\0');
  char* low = distances->data();
  char* high = low + neighbour_count;
  size_t out_idx = 0;
  for (const std::vector<Neighbour>& column : columns) {
    uint16_t previous = 0, before_previous = 0;
    uint32_t run = 0;
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx, ++out_idx) {
      run = (entry_idx > 0 && column[entry_idx].frame == column[entry_idx - 1].frame + 1) ? run + 1
                                                                                          : 1;
      const uint16_t code = QuantizeDistance(column[entry_idx].distance, eps);
      const uint16_t residual =
          static_cast<uint16_t>(code - Predict(run, entry_idx, previous, before_previous));
      const uint16_t zigzag = ZigZag16(residual);
      low[out_idx] = static_cast<char>(zigzag & 0xFF);
      high[out_idx] = static_cast<char>(zigzag >> 8);
      before_previous = previous;
      previous = code;
    }
  }
}

// What can be wrong with a run of the id section.
enum class RunProblem { kNone, kTruncated, kFirstFrameOutside, kFrameOutside, kRunTooLong };

// Reads run `run_idx`'s start and length - 1 and checks them against the archive's frames and
// the block's neighbours left. Inline: it is the decoder's inner loop.
inline RunProblem ReadIdRun(const uint8_t** cursor, const uint8_t* end, uint64_t run_idx,
                            uint64_t reference, uint64_t previous_last, uint64_t frame_count,
                            uint64_t neighbours_left, uint64_t* start, uint64_t* length_code) {
  uint64_t start_code = 0;
  if (!GetVarint(cursor, end, &start_code) || !GetVarint(cursor, end, length_code)) {
    return RunProblem::kTruncated;
  }
  if (run_idx == 0) {
    const int64_t delta = UnZigZag64(start_code);
    // reference < 2^33: the sum cannot overflow for any delta that leads to a valid frame.
    if (delta < -static_cast<int64_t>(reference) || delta >= static_cast<int64_t>(frame_count)) {
      return RunProblem::kFirstFrameOutside;
    }
    *start = reference + static_cast<uint64_t>(delta);
  } else {
    if (start_code >= frame_count) return RunProblem::kFrameOutside;
    *start = previous_last + 2 + start_code;
  }
  if (*length_code >= neighbours_left || *start >= frame_count ||
      *length_code >= frame_count - *start) {
    return RunProblem::kRunTooLong;
  }
  return RunProblem::kNone;
}

Status RunCorruption(RunProblem problem, const std::string& where, uint64_t start,
                     uint64_t length_code) {
  switch (problem) {
    case RunProblem::kTruncated:
      return Status::Corruption(where + "truncated");
    case RunProblem::kFirstFrameOutside:
      return Status::Corruption(where + "first frame outside the archive");
    case RunProblem::kFrameOutside:
      return Status::Corruption(where + "frame outside the archive");
    default:
      return Status::Corruption(where + "run [" + std::to_string(start) + ", +" +
                                std::to_string(length_code + 1) +
                                ") runs past the archive or the block's neighbours");
  }
}

// A run's neighbours with their distances from the planes: inside a run the first two entries
// are predicted by the entry before them, the others linearly. *previous, *before_previous: the
// column's last two codes.
inline void DecodeRunWithDistances(const uint8_t* run_low, const uint8_t* run_high,
                                   uint32_t first_frame, uint32_t length, const float* table,
                                   uint16_t* previous_code, uint16_t* before_previous_code,
                                   Neighbour* run_out) {
  uint16_t previous = *previous_code;
  uint16_t before_previous = *before_previous_code;
  uint32_t offset = 0;
  for (; offset < length && offset < 2; ++offset) {
    const uint16_t code = static_cast<uint16_t>(
        previous + UnZigZag16(static_cast<uint16_t>(run_low[offset] | run_high[offset] << 8)));
    run_out[offset] = Neighbour{first_frame + offset, table[code]};
    before_previous = previous;
    previous = code;
  }
  for (; offset < length; ++offset) {
    const uint16_t code = static_cast<uint16_t>(
        2u * previous - before_previous +
        UnZigZag16(static_cast<uint16_t>(run_low[offset] | run_high[offset] << 8)));
    run_out[offset] = Neighbour{first_frame + offset, table[code]};
    before_previous = previous;
    previous = code;
  }
  *previous_code = previous;
  *before_previous_code = before_previous;
}

}  // namespace

uint16_t QuantizeDistance(float distance, float eps) {
  const double scaled = static_cast<double>(distance) * 65535.0 / static_cast<double>(eps);
  // floor(scaled + 0.5); truncation is floor here since the value is positive.
  if (!(scaled > 0)) return 0;  // also NaN: the writer rejects those before
  if (scaled >= 65534.5) return 65535;
  return static_cast<uint16_t>(static_cast<int32_t>(scaled + 0.5));
}

float DequantizeDistance(uint16_t code, float eps) {
  return static_cast<float>(static_cast<double>(code) * static_cast<double>(eps) / 65535.0);
}

double QuantizationBound(float eps) {
  return static_cast<double>(eps) / 131070.0 + static_cast<double>(eps) * 0x1p-24;
}

bool IsValidZstdLevel(int level) { return level >= ZSTD_minCLevel() && level <= ZSTD_maxCLevel(); }

BlockEncoder::BlockEncoder(int zstd_level) : zstd_level_(zstd_level), context_(ZSTD_createCCtx()) {
  MOTIF_CHECK(context_ != nullptr);
}

BlockEncoder::~BlockEncoder() { ZSTD_freeCCtx(context_); }

// Block bytes:
//   header 40 B | zstd(id section) | zstd(distance section) | checksum u64 of all before it
Status BlockEncoder::Encode(uint64_t first_column,
                            const std::vector<std::vector<Neighbour>>& columns, float eps,
                            std::string* out, BlockHandle* handle) {
  uint64_t neighbour_count = 0;
  for (const std::vector<Neighbour>& column : columns) neighbour_count += column.size();
  MOTIF_CHECK(neighbour_count <= kMaxBlockNeighbours && columns.size() <= kMaxBlockColumns);

  EncodeIdSection(first_column, columns, &ids_);
  EncodeDistanceSection(columns, eps, neighbour_count, &distances_);

  BlockHeader header;
  header.column_count = static_cast<uint32_t>(columns.size());
  header.first_column = first_column;
  header.neighbour_count = static_cast<uint32_t>(neighbour_count);
  header.ids_raw_bytes = static_cast<uint32_t>(ids_.size());
  out->clear();
  out->resize(kBlockHeaderBytes);  // the header is filled in once the sizes are known
  for (const std::string* section : {&ids_, &distances_}) {
    compressed_.resize(ZSTD_compressBound(section->size()));
    const size_t size = ZSTD_compressCCtx(context_, compressed_.data(), compressed_.size(),
                                          section->data(), section->size(), zstd_level_);
    if (ZSTD_isError(size)) return ZstdError("compression failed", size);
    out->append(compressed_.data(), size);
    (section == &ids_ ? header.ids_bytes : header.distances_bytes) = static_cast<uint32_t>(size);
  }
  std::string header_bytes;
  header.EncodeTo(&header_bytes);
  std::memcpy(out->data(), header_bytes.data(), kBlockHeaderBytes);
  const uint64_t checksum = Checksum64(out->data(), out->size());
  PutU64(out, checksum);

  handle->bytes = out->size();
  handle->first_column = first_column;
  handle->column_count = header.column_count;
  handle->neighbour_count = header.neighbour_count;
  handle->checksum = checksum;
  return Status::Ok();
}

Status CheckBlockFraming(const uint8_t* bytes, uint64_t available, BlockHeader* header,
                         uint64_t* checksum) {
  if (available < kBlockHeaderBytes + kBlockTrailerBytes) {
    return Status::Corruption("only " + std::to_string(available) + " bytes left for a block");
  }
  MOTIF_RETURN_IF_ERROR(BlockHeader::DecodeFrom(bytes, header));
  const uint64_t size = header->block_bytes();
  if (size > available) {
    return Status::Corruption("block of " + std::to_string(size) + " bytes runs past the end (" +
                              std::to_string(available) + " bytes left)");
  }
  *checksum = LoadU64(bytes + size - kBlockTrailerBytes);
  if (Checksum64(bytes, size - kBlockTrailerBytes) != *checksum) {
    return Status::Corruption("checksum mismatch");
  }
  return Status::Ok();
}

BlockDecoder::BlockDecoder() : context_(ZSTD_createDCtx()) { MOTIF_CHECK(context_ != nullptr); }

BlockDecoder::~BlockDecoder() { ZSTD_freeDCtx(context_); }

const float* BlockDecoder::DistanceTable(float eps) {
  const uint32_t eps_bits = std::bit_cast<uint32_t>(eps);
  if (table_.empty() || eps_bits != table_eps_bits_) {
    table_.resize(65536);
    for (uint32_t code = 0; code < 65536; ++code) {
      table_[code] = DequantizeDistance(static_cast<uint16_t>(code), eps);
    }
    table_eps_bits_ = eps_bits;
  }
  return table_.data();
}

Status BlockDecoder::Decompress(const uint8_t* frame, uint64_t size, uint64_t raw_size,
                                const char* what, std::string* out) {
  const unsigned long long content_size = ZSTD_getFrameContentSize(frame, size);
  if (content_size != raw_size) {
    return Status::Corruption(std::string(what) + ": zstd frame does not declare " +
                              std::to_string(raw_size) + " bytes of content");
  }
  if (ZSTD_findFrameCompressedSize(frame, size) != size) {
    return Status::Corruption(std::string(what) + ": not exactly one zstd frame of " +
                              std::to_string(size) + " bytes");
  }
  out->resize(raw_size);
  char dummy = 0;
  const size_t decoded =
      ZSTD_decompressDCtx(context_, raw_size ? out->data() : &dummy, raw_size, frame, size);
  if (ZSTD_isError(decoded) || decoded != raw_size) {
    return Status::Corruption(std::string(what) + ": zstd frame does not decode" +
                              (ZSTD_isError(decoded)
                                   ? std::string(": ") + ZSTD_getErrorName(decoded)
                                   : std::string(" to its content size")));
  }
  return Status::Ok();
}

Status BlockDecoder::Decode(const uint8_t* bytes, const BlockHandle& handle,
                            const BlockLimits& limits, TrellisBlock* block, bool decode_distances) {
  if (handle.bytes < kBlockHeaderBytes + kBlockTrailerBytes) {
    return Status::Corruption("block of " + std::to_string(handle.bytes) + " bytes is too short");
  }
  const uint64_t checksum = LoadU64(bytes + handle.bytes - kBlockTrailerBytes);
  if (checksum != handle.checksum ||
      Checksum64(bytes, handle.bytes - kBlockTrailerBytes) != checksum) {
    return Status::Corruption("checksum mismatch");
  }
  BlockHeader header;
  MOTIF_RETURN_IF_ERROR(BlockHeader::DecodeFrom(bytes, &header));
  if (header.column_count != handle.column_count || header.first_column != handle.first_column ||
      header.neighbour_count != handle.neighbour_count || header.block_bytes() != handle.bytes) {
    return Status::Corruption("block header (columns [" + std::to_string(header.first_column) +
                              ", +" + std::to_string(header.column_count) + "), " +
                              std::to_string(header.neighbour_count) + " neighbours, " +
                              std::to_string(header.block_bytes()) +
                              " bytes) disagrees with the block index");
  }
  const uint64_t neighbour_count = header.neighbour_count;
  if (header.column_count == 0 || header.column_count > kMaxBlockColumns ||
      neighbour_count > kMaxBlockNeighbours ||
      neighbour_count > uint64_t{header.column_count} * limits.k_max) {
    return Status::Corruption(std::to_string(neighbour_count) + " neighbours in " +
                              std::to_string(header.column_count) + " columns exceed the limits");
  }
  // Each column's run count takes at most 5 bytes, each run at most 15 (start 5, gap 5,
  // length 5): a bound checked before allocating.
  if (header.ids_raw_bytes > 5 * uint64_t{header.column_count} + 15 * neighbour_count) {
    return Status::Corruption("id section of " + std::to_string(header.ids_raw_bytes) +
                              " raw bytes is larger than its columns can need");
  }
  const uint8_t* ids_frame = bytes + kBlockHeaderBytes;
  MOTIF_RETURN_IF_ERROR(
      Decompress(ids_frame, header.ids_bytes, header.ids_raw_bytes, "id section", &ids_raw_));
  block->first_column = header.first_column;
  block->column_count = header.column_count;
  if (!decode_distances) return DecodeColumns<false>(handle, limits, nullptr, block);
  MOTIF_RETURN_IF_ERROR(Decompress(ids_frame + header.ids_bytes, header.distances_bytes,
                                   2 * neighbour_count, "distance section", &distances_raw_));
  return DecodeColumns<true>(handle, limits, DistanceTable(limits.eps), block);
}

// One pass over the id section (per column: run_count, then start code and length - 1 per run;
// see the header) that writes each neighbour whole: its frame from the run, and with
// kDistances its distance from the distance section's planes (inside a run, the first two
// entries are predicted by the entry before them, the others linearly), else 0.
template <bool kDistances>
Status BlockDecoder::DecodeColumns(const BlockHandle& handle, const BlockLimits& limits,
                                   const float* table, TrellisBlock* block) {
  const uint8_t* cursor = reinterpret_cast<const uint8_t*>(ids_raw_.data());
  const uint8_t* const end = cursor + ids_raw_.size();
  const uint64_t neighbour_count = handle.neighbour_count;
  block->offsets.resize(uint64_t{handle.column_count} + 1);
  block->neighbours.resize(neighbour_count);
  Neighbour* out = block->neighbours.data();
  const uint8_t* low = reinterpret_cast<const uint8_t*>(distances_raw_.data());
  const uint8_t* high = low + neighbour_count;
  uint64_t filled = 0;
  uint64_t reference = handle.first_column;
  for (uint32_t column_idx = 0; column_idx < handle.column_count; ++column_idx) {
    block->offsets[column_idx] = static_cast<uint32_t>(filled);
    const auto where = [&] {
      return "id section: column " + std::to_string(handle.first_column + column_idx) + ": ";
    };
    uint64_t run_count = 0;
    if (!GetVarint(&cursor, end, &run_count)) return Status::Corruption(where() + "truncated");
    if (run_count > neighbour_count - filled) {
      return Status::Corruption(where() + std::to_string(run_count) +
                                " runs, more than the block's neighbours left");
    }
    const uint64_t column_begin = filled;
    uint64_t previous_last = 0;
    uint16_t previous = 0, before_previous = 0;  // codes; the column's first prediction is 0
    for (uint64_t run_idx = 0; run_idx < run_count; ++run_idx) {
      uint64_t start = 0, length_code = 0;
      const RunProblem problem =
          ReadIdRun(&cursor, end, run_idx, reference, previous_last, limits.frame_count,
                    neighbour_count - filled, &start, &length_code);
      if (problem != RunProblem::kNone) {
        return RunCorruption(problem, where(), start, length_code);
      }
      const uint32_t first_frame = static_cast<uint32_t>(start);
      const uint32_t length = static_cast<uint32_t>(length_code + 1);
      Neighbour* run_out = out + filled;
      if constexpr (kDistances) {
        DecodeRunWithDistances(low + filled, high + filled, first_frame, length, table, &previous,
                               &before_previous, run_out);
      } else {
        for (uint32_t offset = 0; offset < length; ++offset) {
          run_out[offset] = Neighbour{first_frame + offset, 0.0f};
        }
      }
      filled += length;
      previous_last = start + length_code;
    }
    if (filled - column_begin > limits.k_max) {
      return Status::Corruption(where() + std::to_string(filled - column_begin) +
                                " neighbours, more than k_max " + std::to_string(limits.k_max));
    }
    reference = (filled > column_begin ? out[column_begin].frame : reference) + 1;
  }
  block->offsets[handle.column_count] = static_cast<uint32_t>(filled);
  if (filled != neighbour_count || cursor != end) {
    return Status::Corruption(
        "id section holds " + std::to_string(filled) + " neighbours in " +
        std::to_string(cursor - reinterpret_cast<const uint8_t*>(ids_raw_.data())) + " of " +
        std::to_string(ids_raw_.size()) + " bytes; the header says " +
        std::to_string(neighbour_count));
  }
  return Status::Ok();
}

}  // namespace motif::trellis_file
