// On-disk structures of the matching-trellis file (.mtr), version 1.0. The byte layout, the
// checksums, the column encoding and the reader's duties are specified in
// docs/formats/trellis_file.md; this header and that document change together (the
// TrellisFileGolden test compares a written file with the document's hexdump).
//
//   partial file ("<path>.partial", while the trellis is built):
//     [FileHeader: magic, version, block_columns, TrellisParams, checksum]
//     [block 0] [block 1] ...          each block checksums itself (trailer), so the partial
//                                      file can be scanned and resumed without an index
//   finished file (the partial file renamed once complete):
//     [FileHeader] [block 0] ... [block n-1] [block index: n x 40 B] [Footer 64 B]
//
// Every struct here is a plain value with EncodeTo (appends its exact bytes, little-endian) and
// DecodeFrom (checks sizes, magic, checksums and reserved fields; Corruption with a message that
// names the structure but not the file: callers add it). Nothing here touches files.
// Thread-safety: values and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/byte_coding.h"
#include "common/status.h"
#include "formats/trellis_file/trellis_params.h"

namespace motif::trellis_file {

// "\x89MTR\r\n\x1a\n" (motif trellis): PNG-style, see the spec. Non-ASCII first byte, CR LF and
// ^Z catch text-mode transfers.
inline constexpr std::array<uint8_t, 8> kFileMagic = {0x89, 'M', 'T', 'R', '\r', '\n', 0x1A, '\n'};
// "\x89MTREND\n": starts the footer, the last 64 bytes of a finished file.
inline constexpr std::array<uint8_t, 8> kFooterMagic = {0x89, 'M', 'T', 'R', 'E', 'N', 'D', '\n'};
// "MTBK": starts every column block.
inline constexpr std::array<uint8_t, 4> kBlockMagic = {'M', 'T', 'B', 'K'};

inline constexpr uint16_t kFormatMajor = 1;
inline constexpr uint16_t kFormatMinor = 0;

inline constexpr size_t kHeaderFixedBytes = 32;  // magic .. reserved, before the params
inline constexpr size_t kParamsFixedBytes = 60;  // the params' fixed fields + string length
inline constexpr size_t kBlockHeaderBytes = 40;
inline constexpr size_t kBlockTrailerBytes = 8;  // the block checksum
inline constexpr size_t kBlockEntryBytes = 40;   // one block index entry
inline constexpr size_t kFooterBytes = 64;
inline constexpr size_t kMinHeaderBytes = kHeaderFixedBytes + kParamsFixedBytes + 8;

// Upper bounds, enforced by the writer (InvalidArgument) and by readers before they allocate
// (Corruption): a crafted file must not exhaust memory.
inline constexpr uint64_t kMaxFrameCount = 1ull << 32;  // frame ids are u32
inline constexpr uint32_t kMaxBlockColumns = 1u << 20;
inline constexpr uint32_t kMaxBlockNeighbours = 1u << 28;  // distances: 512 MiB raw
inline constexpr uint32_t kMaxParamsBytes = 1u << 20;
inline constexpr uint32_t kMaxSearchParamsBytes = 1u << 16;  // the writer's limit

// The byte coding of common/byte_coding.h.
using ::motif::Checksum64;
using ::motif::Hex;
using ::motif::LoadU16;
using ::motif::LoadU32;
using ::motif::LoadU64;
using ::motif::PutF32;
using ::motif::PutF64;
using ::motif::PutString;
using ::motif::PutU16;
using ::motif::PutU32;
using ::motif::PutU64;
using ::motif::PutU8;

// Encodes the params as stored in the header (kParamsFixedBytes + search_params bytes).
void EncodeParams(const TrellisParams& params, std::string* out);
// Decodes `size` bytes of params. Bytes after the known fields (a later minor version's) are
// skipped. Corruption: too short, string past the end, eps not finite and > 0, frame_count
// above 2^32, k_max 0.
Status DecodeParams(const uint8_t* bytes, size_t size, TrellisParams* params);
// The checks DecodeParams makes on values, for the writer (InvalidArgument there).
std::string ParamsProblem(const TrellisParams& params);

// The header at offset 0: identical in the partial and the finished file.
struct FileHeader {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  uint32_t block_columns = 0;
  TrellisParams params;

  // header_bytes = kHeaderFixedBytes + params bytes + 8 (the checksum).
  void EncodeTo(std::string* out) const;
  // `size` bytes are available from `bytes`; sets *header_bytes. NotSupported: another major
  // version. Corruption: bad magic, checksum, header size, reserved field, block_columns out of
  // [1, 2^20], params (DecodeParams).
  static Status DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header,
                           uint64_t* header_bytes);
};

// The first 40 bytes of a block; its last 8 bytes (the trailer) are the block checksum.
struct BlockHeader {
  uint32_t column_count = 0;
  uint64_t first_column = 0;
  uint32_t neighbour_count = 0;
  uint32_t ids_raw_bytes = 0;    // the id section before compression
  uint32_t ids_bytes = 0;        // the id section's zstd frame
  uint32_t distances_bytes = 0;  // the distance section's zstd frame (raw: 2 x neighbours)

  uint64_t block_bytes() const {
    return kBlockHeaderBytes + uint64_t{ids_bytes} + distances_bytes + kBlockTrailerBytes;
  }
  void EncodeTo(std::string* out) const;  // kBlockHeaderBytes
  // `bytes` holds kBlockHeaderBytes. Corruption: bad magic, reserved field not zero.
  static Status DecodeFrom(const uint8_t* bytes, BlockHeader* header);
};

// One block index entry.
struct BlockHandle {
  uint64_t offset = 0;  // from the start of the file
  uint64_t bytes = 0;   // the whole block: header, sections, trailer
  uint64_t first_column = 0;
  uint32_t column_count = 0;
  uint32_t neighbour_count = 0;
  uint64_t checksum = 0;  // the block's trailer: Checksum64 of its bytes but the last 8

  void EncodeTo(std::string* out) const;                // kBlockEntryBytes
  static BlockHandle DecodeFrom(const uint8_t* bytes);  // kBlockEntryBytes; no checks
};

// The last 64 bytes of a finished file.
struct Footer {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  uint64_t index_offset = 0;
  uint64_t block_count = 0;
  uint64_t neighbour_count = 0;
  uint64_t index_checksum = 0;   // Checksum64 of the block_count x 40 index bytes
  uint64_t header_checksum = 0;  // a copy of the header's checksum

  void EncodeTo(std::string* out) const;  // kFooterBytes
  // `bytes` holds kFooterBytes. Corruption: magic, checksum, major version, footer size.
  static Status DecodeFrom(const uint8_t* bytes, Footer* footer);
};

}  // namespace motif::trellis_file
