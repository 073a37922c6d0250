// Trellis block codec: one column block of the matching trellis, the columns
// [first_column, first_column + column_count), in memory (docs/formats/trellis_file.md,
// "Column block" and "Column encoding"):
//
//   BlockHeader 40 B | id section: one zstd frame | distance section: one zstd frame
//   | checksum u64 (XXH3-64 of every byte of the block before it)
//
// Id section, before compression, column after column (varints are LEB128):
//   run_count | first run: zigzag(start - reference), length - 1
//             | each later run: start - (previous run's last frame + 2), length - 1
//   where a run is a maximal range of consecutive frames, and `reference` is first_column for
//   the block's first column, then the previous column's first frame + 1 (or the previous
//   reference + 1 after an empty column): neighbours of t + 1 are mostly those of t, shifted.
// Distance section, before compression: per entry the quantised distance q = round(d/eps *
// 65535) minus a prediction (2 q[i-1] - q[i-2] inside a run of consecutive frames, q[i-1]
// otherwise, 0 for a column's first entry), mod 2^16, zigzagged, stored as two byte planes
// (all low bytes, then all high bytes).
//
// Knows nothing about files. The section sizes and why this encoding: the spec.
// Thread-safety: an encoder or a decoder is used by one thread at a time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/trellis_file/trellis_block.h"
#include "formats/trellis_file/trellis_column.h"
#include "formats/trellis_file/trellis_file_format.h"

struct ZSTD_CCtx_s;
struct ZSTD_DCtx_s;

namespace motif::trellis_file {

// The stored code of a distance in [0, eps]: round(distance * 65535 / eps), computed in binary64
// (half-way cases round up). DequantizeDistance(QuantizeDistance(d)) is within
// eps / 131070 + eps * 2^-24 of d, is exact for 0 and eps, and never exceeds eps.
uint16_t QuantizeDistance(float distance, float eps);
float DequantizeDistance(uint16_t code, float eps);
// The bound above: the largest |decoded - written| for a distance in [0, eps].
double QuantizationBound(float eps);

// Whether zstd accepts `level` (negative fast levels up to the maximum, typically 22).
bool IsValidZstdLevel(int level);

// Encodes columns into blocks. The caller has checked the columns (sorted, unique, frames below
// frame_count, distances in [0, eps], sizes within k_max and the block limits).
class BlockEncoder {
 public:
  explicit BlockEncoder(int zstd_level);
  ~BlockEncoder();
  BlockEncoder(const BlockEncoder&) = delete;
  BlockEncoder& operator=(const BlockEncoder&) = delete;

  // Replaces *out with the block of `columns` starting at column `first_column`, and fills
  // *handle (all but its offset). IOError if zstd fails (out of memory).
  Status Encode(uint64_t first_column, const std::vector<std::vector<Neighbour>>& columns,
                float eps, std::string* out, BlockHandle* handle);

 private:
  int zstd_level_;
  ZSTD_CCtx_s* context_;
  std::string ids_;
  std::string distances_;
  std::string compressed_;
};

// What a block must satisfy beyond its own bytes: from the file's params.
struct BlockLimits {
  uint64_t frame_count = 0;  // every frame id is below it
  uint32_t k_max = 0;        // every column holds at most this many neighbours
  float eps = 0;             // the distance scale
};

// Checks that `available` bytes at `bytes` start with a complete block whose trailer matches
// its bytes; sets *header and *checksum. Used to scan a partial file. Corruption otherwise.
Status CheckBlockFraming(const uint8_t* bytes, uint64_t available, BlockHeader* header,
                         uint64_t* checksum);

class BlockDecoder {
 public:
  BlockDecoder();
  ~BlockDecoder();
  BlockDecoder(const BlockDecoder&) = delete;
  BlockDecoder& operator=(const BlockDecoder&) = delete;

  // Checks the block (`handle.bytes` bytes at `bytes`) against its checksum and its index entry,
  // and decodes it. Without `decode_distances` the distance section is checked only by the
  // checksum and every distance is left 0. Corruption: "checksum mismatch", or what does not
  // decode (the caller prefixes "<file>: block <n> at offset <hex>").
  Status Decode(const uint8_t* bytes, const BlockHandle& handle, const BlockLimits& limits,
                TrellisBlock* block, bool decode_distances = true);

 private:
  // Decodes the id section (and with kDistances the distance section) into *block.
  template <bool kDistances>
  Status DecodeColumns(const BlockHandle& handle, const BlockLimits& limits, const float* table,
                       TrellisBlock* block);
  // Decompresses exactly one zstd frame of `size` bytes that must hold `raw_size` bytes.
  Status Decompress(const uint8_t* frame, uint64_t size, uint64_t raw_size, const char* what,
                    std::string* out);
  const float* DistanceTable(float eps);

  ZSTD_DCtx_s* context_;
  std::string ids_raw_;
  std::string distances_raw_;
  std::vector<float> table_;  // code -> distance, for table_eps_bits_
  uint32_t table_eps_bits_ = 0;
};

}  // namespace motif::trellis_file
