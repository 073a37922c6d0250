// On-disk structures of the tensor file, version 1.0 (docs/formats/tensor_file.md; the
// TensorFileGolden test compares a written file with the document's hexdump, so the two change
// together):
//
//   [Header, 64 bytes: magic, version, kind, tensor count, data size, table checksum, checksum]
//   [Table: 80 bytes per tensor: name, type, rank, shape, offset, size, data checksum]
//   [Data: each tensor's elements at its offset (a multiple of 8), zero padding between]
//
// Nothing here touches files. Decoders return Corruption naming the structure but not the file:
// callers add it.
// Thread-safety: values and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/byte_coding.h"
#include "common/status.h"
#include "formats/tensor_file/tensor_type.h"

namespace motif::tensor_file {

// "\x89MWT\r\n\x1a\n" (motif word tensors): PNG-style like the archive's, trellis's and paths
// file's magic.
inline constexpr std::array<uint8_t, 8> kFileMagic = {0x89, 'M', 'W', 'T', '\r', '\n', 0x1A, '\n'};

inline constexpr uint16_t kFormatMajor = 1;
inline constexpr uint16_t kFormatMinor = 0;

inline constexpr size_t kHeaderBytes = 64;       // version 1.0's header, checksum included
inline constexpr size_t kMaxHeaderBytes = 4096;  // later minor versions may append fields
inline constexpr size_t kKindBytes = 16;         // kind: 1 to 15 characters, NUL-padded
inline constexpr size_t kNameBytes = 32;         // tensor name: 1 to 31 characters, NUL-padded
inline constexpr size_t kEntryBytes = 80;        // one table entry
inline constexpr uint32_t kMaxTensors = 65536;
inline constexpr uint64_t kDataAlignment = 8;

struct FileHeader {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  uint32_t header_bytes = kHeaderBytes;
  std::string kind;
  uint32_t tensor_count = 0;
  uint64_t data_bytes = 0;      // from the end of the table to the end of the file
  uint64_t table_checksum = 0;  // Checksum64 of the table

  // Appends kHeaderBytes, the checksum last; returns the checksum (the file's identity).
  uint64_t EncodeTo(std::string* out) const;
  // `size` bytes from `bytes` (the whole file). Corruption: empty or short file, bad magic,
  // another major version, header size, checksum, flags, kind, sizes that do not add up.
  static Status DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header,
                           uint64_t* header_checksum);
};

// One table entry.
struct TableEntry {
  std::string name;
  TensorType type = TensorType::kU8;
  uint8_t rank = 1;
  uint64_t rows = 0;
  uint64_t cols = 1;
  uint64_t offset = 0;  // absolute, a multiple of 8
  uint64_t bytes = 0;   // rows * cols * element size
  uint64_t checksum = 0;

  void EncodeTo(std::string* out) const;
  // Decodes kEntryBytes at `bytes`; Corruption (without position: the caller adds it) for a bad
  // name, type, rank, reserved field or a size that is not the shape's.
  static Status DecodeFrom(const uint8_t* bytes, TableEntry* entry);
};

// "" if `kind` (1 to 15 characters of [a-z0-9_.-]) or `name` (1 to 31 of [a-z0-9_.]) is
// acceptable, else why not.
std::string KindProblem(const std::string& kind);
std::string NameProblem(const std::string& name);

// Rounds `offset` up to a multiple of kDataAlignment.
inline uint64_t AlignUp(uint64_t offset) {
  return (offset + kDataAlignment - 1) / kDataAlignment * kDataAlignment;
}

}  // namespace motif::tensor_file
