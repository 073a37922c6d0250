// Column chunk codec: turns one column of a block (a run of frames of one joint's quaternion, the
// root height, the root velocity or the heading) into the bytes of one chunk, and back. It
// knows nothing about files: the block codec places the chunks. The transform, in encoding
// order (docs/formats/frame_file.md, "Column chunk encoding"):
//
//   float32 values, component-major (all frames of component 0, then component 1, ...)
//     -> quantise: q = round_half_away(value / step) as int32    (or keep the float32 bits)
//     -> delta along time per component: order 1 x[i] - x[i-1], order 2 the second difference
//        x[i] - 2 x[i-1] + x[i-2] (the first values keep lower orders)  (uint32 wrap-around)
//     -> zigzag: (d << 1) ^ (d >> 31)                           (small magnitudes -> small codes)
//     -> byte shuffle: byte plane 0 (least significant bytes of every word), plane 1, 2, 3
//     -> zstd frame                                             (or stored as is)
//
// Error bound of uniform quantisation: |decoded - value| <= step / 2, plus the float32 rounding
// of decoded = (float)((double)q * step), which is exact when step is a power of two and
// |q| < 2^24. With `normalize` the decoder rescales each 4-component group (a quaternion) to unit
// length; for unit input quaternions the rotation angle error is then <= 2 * asin(step) < 4 * step.
// Thread-safety: ColumnEncoder is used by one thread at a time; DecodeColumnChunk may be called
// from many threads at once (it keeps one zstd context per thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "common/status.h"

namespace motif::frame_file {

// Pinned values: they are stored in the column table.
enum class Quantization : uint8_t {
  kNone = 0,     // the float32 bit patterns, as uint32 (lossless)
  kUniform = 1,  // round(value / step) as int32
};

enum class Compression : uint8_t {
  kNone = 0,
  kZstd = 1,
};

inline constexpr uint8_t kMaxDeltaOrder = 2;

struct ColumnEncoding {
  Quantization quantization = Quantization::kUniform;
  uint8_t delta_order = 1;  // 0 (none), 1 (previous frame) or 2 (linear extrapolation)
  bool zigzag = true;
  bool shuffle = true;
  Compression compression = Compression::kZstd;
  bool normalize = false;  // decoder rescales each quaternion (4 components) to unit length
  double step = 0;         // quantisation step (> 0) for kUniform; 0 for kNone

  bool operator==(const ColumnEncoding&) const = default;
};

// InvalidArgument unless the encoding is usable for a column of `component_count` components:
// known enum values, delta_order <= 2, a finite step > 0 exactly when quantising, normalize only
// with 4 components and quantisation.
Status ValidateEncoding(const ColumnEncoding& encoding, uint32_t component_count);

// True if `value` can be stored with `encoding`: finite, and when quantised, its quantised value
// fits in int32.
bool IsEncodable(const ColumnEncoding& encoding, float value);

// The decoded value of `value` (what a reader gets back, before any normalisation).
float QuantizeRoundTrip(const ColumnEncoding& encoding, float value);

// True if zstd accepts `level` (ZSTD_minCLevel() .. ZSTD_maxCLevel()).
bool IsValidZstdLevel(int level);

class ColumnEncoder {
 public:
  explicit ColumnEncoder(int zstd_level);
  ~ColumnEncoder();
  ColumnEncoder(const ColumnEncoder&) = delete;
  ColumnEncoder& operator=(const ColumnEncoder&) = delete;

  // Appends the chunk for `values` (component-major: values[component * frame_count + frame])
  // to `out`. InvalidArgument if a value is not encodable (IsEncodable); ResourceExhausted if
  // zstd fails (out of memory).
  Status Encode(const ColumnEncoding& encoding, const float* values, uint32_t component_count,
                uint32_t frame_count, std::string* out);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// The raw (uncompressed) size of a chunk: component_count * frame_count * 4 bytes.
inline uint64_t ChunkRawBytes(uint32_t component_count, uint32_t frame_count) {
  return 4ull * component_count * frame_count;
}

// Decodes a chunk into `values` (component-major, component_count * frame_count floats).
// Corruption if the bytes are not a chunk of exactly that size (bad zstd frame, wrong size,
// trailing bytes). The encoding must have passed ValidateEncoding.
Status DecodeColumnChunk(const ColumnEncoding& encoding, const uint8_t* chunk, size_t chunk_bytes,
                         uint32_t component_count, uint32_t frame_count, float* values);

}  // namespace motif::frame_file
