// On-disk structures of the motion archive (.mfs), version 1.0. The byte layout, the checksums
// and the reader's duties are specified in docs/formats/frame_file.md; this header and that
// document change together (the GoldenBytes test compares a written file with the document's
// hexdump).
//
//   [FileHeader 128 B: magic, version, header checksum, commit slot 0, commit slot 1]
//   [block] [block] ...            column blocks, never rewritten
//   [metadata] [Footer 64 B]       one pair per commit; the newest valid slot points at a footer
//   ... later commits append more blocks, metadata and a footer ...
//
// Every struct here is a plain value with EncodeTo (appends its exact bytes, little-endian) and
// DecodeFrom (checks sizes, magic, checksums and reserved fields; Corruption with a message that
// names the structure, without the file name: callers add it). Nothing here touches files.
// Thread-safety: values and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/byte_coding.h"
#include "common/status.h"

namespace motif::frame_file {

// "\x89MFS\r\n\x1a\n": PNG-style (see the spec): non-ASCII first byte, CR LF and ^Z catch
// text-mode transfers.
inline constexpr std::array<uint8_t, 8> kFileMagic = {0x89, 'M', 'F', 'S', '\r', '\n', 0x1A, '\n'};
// "\x89MFSEND\n": marks a footer.
inline constexpr std::array<uint8_t, 8> kFooterMagic = {0x89, 'M', 'F', 'S', 'E', 'N', 'D', '\n'};
// "MFBK": starts every column block.
inline constexpr std::array<uint8_t, 4> kBlockMagic = {'M', 'F', 'B', 'K'};

inline constexpr uint16_t kFormatMajor = 1;
inline constexpr uint16_t kFormatMinor = 0;

inline constexpr size_t kHeaderBytes = 128;
inline constexpr size_t kHeaderFixedBytes = 48;  // magic .. header checksum
inline constexpr size_t kSlotBytes = 40;
inline constexpr std::array<size_t, 2> kSlotOffsets = {48, 88};
inline constexpr size_t kFooterBytes = 64;
inline constexpr size_t kBlockHeaderBytes = 24;
inline constexpr size_t kChunkEntryBytes = 8;
inline constexpr size_t kColumnEntryBytes = 24;
inline constexpr size_t kBlockEntryBytes = 40;

// Upper bounds a reader enforces before allocating (a crafted file must not exhaust memory).
inline constexpr uint64_t kMaxBlockFrames = 1u << 22;
inline constexpr uint64_t kMaxJoints = 4096;
inline constexpr uint64_t kMaxBlockRawBytes = 1ull << 30;

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

// Bounds-checked little-endian reads over a byte range. Each Get returns false (and reads
// nothing) once the range is exhausted; position() says where a problem was found.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool GetU8(uint8_t* value);
  bool GetU16(uint16_t* value);
  bool GetU32(uint32_t* value);
  bool GetI32(int32_t* value);
  bool GetU64(uint64_t* value);
  bool GetF32(float* value);
  bool GetF64(double* value);
  bool GetString(std::string* value);
  bool GetBytes(size_t size, const uint8_t** bytes);
  bool Skip(size_t size);
  size_t position() const { return pos_; }
  size_t remaining() const { return size_ - pos_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// One of the header's two commit slots. All 40 bytes zero: empty (never written).
struct CommitSlot {
  uint64_t generation = 0;
  uint64_t footer_offset = 0;
  uint64_t committed_length = 0;

  bool empty() const { return generation == 0 && footer_offset == 0 && committed_length == 0; }
  void EncodeTo(std::string* out) const;  // 40 bytes, checksum included
  // `bytes` holds kSlotBytes. Sets *is_empty for an all-zero slot (then *slot is zero and the
  // status OK). Corruption: checksum mismatch, non-zero reserved field, generation 0.
  static Status DecodeFrom(const uint8_t* bytes, CommitSlot* slot, bool* is_empty);
};

// The 128 bytes at offset 0.
struct FileHeader {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  std::array<CommitSlot, 2> slots;

  void EncodeTo(std::string* out) const;  // 128 bytes
  // Checks the fixed part (bytes [0, 48)): magic, major version, header size, checksum, reserved
  // fields. Slots are decoded separately (CommitSlot::DecodeFrom): a damaged slot is not fatal.
  // `size` >= kHeaderBytes. NotSupported for another major version, Corruption on any other
  // failed check.
  static Status DecodeFixedFrom(const uint8_t* bytes, size_t size, FileHeader* header);
};

// The 64 bytes at a commit's end: where its metadata is and its checksum.
struct Footer {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  uint64_t generation = 0;
  uint64_t metadata_offset = 0;
  uint64_t metadata_bytes = 0;
  uint64_t metadata_checksum = 0;

  void EncodeTo(std::string* out) const;  // 64 bytes
  // `bytes` holds kFooterBytes. Corruption: magic, checksum, major version, size, reserved.
  static Status DecodeFrom(const uint8_t* bytes, Footer* footer);
};

// A block index entry (metadata, BLOCKS section).
struct BlockHandle {
  uint64_t offset = 0;       // from the start of the file
  uint64_t bytes = 0;        // the whole block: header, chunk entries, chunks
  uint64_t first_frame = 0;  // global frame index
  uint32_t frame_count = 0;
  uint64_t checksum = 0;  // Checksum64 of the block's `bytes` bytes

  void EncodeTo(std::string* out) const;  // kBlockEntryBytes
  // Reads kBlockEntryBytes known bytes; Corruption on a non-zero reserved field.
  static Status DecodeFrom(ByteReader* reader, BlockHandle* handle);
};

// The first 24 bytes of a block.
struct BlockHeader {
  uint32_t column_count = 0;
  uint64_t first_frame = 0;
  uint32_t frame_count = 0;

  void EncodeTo(std::string* out) const;
  static Status DecodeFrom(const uint8_t* bytes, size_t size, BlockHeader* header);
};

}  // namespace motif::frame_file
