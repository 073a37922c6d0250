// On-disk structures of the paths file (.mpa), version 1.0. The byte layout, the record coding
// and the reader's duties are specified in docs/formats/paths_file.md; this header and that
// document change together (the PathsFileGolden test compares a written file with the
// document's hexdump).
//
//   [FileHeader: magic, version, params, counts, section sizes, records checksum, checksum]
//   [records section: one zstd frame holding candidate_count delta-coded records]
//
// Nothing here touches files. Decoders return Corruption with a message naming the structure
// (and the record) but not the file: callers add it.
// Thread-safety: values and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/byte_coding.h"
#include "common/status.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/paths_file/paths_params.h"

namespace motif::paths_file {

// "\x89MPA\r\n\x1a\n" (motif paths): PNG-style like the archive's and the trellis's magic.
inline constexpr std::array<uint8_t, 8> kFileMagic = {0x89, 'M', 'P', 'A', '\r', '\n', 0x1A, '\n'};

inline constexpr uint16_t kFormatMajor = 1;
inline constexpr uint16_t kFormatMinor = 0;

inline constexpr uint32_t kFlagAllBranches = 1;  // header flags, bit 0
inline constexpr size_t kHeaderBytes = 96;       // version 1.0's header, checksum included
inline constexpr size_t kMaxHeaderBytes = 4096;  // later minor versions may append fields
inline constexpr uint64_t kMaxFrameCount = uint64_t{1} << 32;
inline constexpr size_t kMinRecordBytes = 6;   // six varints of one byte
inline constexpr size_t kMaxRecordBytes = 60;  // six varints of ten bytes
// A zstd block holds at most 128 KiB and costs at least 3 bytes: a bound on how much a frame
// of a given size can expand to, checked before allocating.
inline constexpr uint64_t kZstdMaxBlockBytes = 128 * 1024;

using ::motif::Checksum64;  // common/byte_coding.h: XXH3-64 with seed 0

// The file header at offset 0.
struct FileHeader {
  uint16_t format_major = kFormatMajor;
  uint16_t format_minor = kFormatMinor;
  uint32_t header_bytes = kHeaderBytes;
  PathsParams params;
  uint64_t candidate_count = 0;
  uint64_t records_raw_bytes = 0;  // the records before compression
  uint64_t records_bytes = 0;      // the zstd frame
  uint64_t records_checksum = 0;   // Checksum64 of the zstd frame

  // Appends kHeaderBytes, the checksum last.
  void EncodeTo(std::string* out) const;
  // `size` bytes are available from `bytes` (the whole file). Corruption: bad magic, another
  // major version, header size, checksum, unknown flags, params out of range, counts and
  // section sizes that do not add up to the file's size.
  static Status DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header);
};

// The params' checks (the writer's InvalidArgument, the reader's Corruption): "" if fine.
std::string ParamsProblem(const PathsParams& params);
// The rules a candidate list must follow (see WritePathsFile): "" if fine, else what is wrong
// with which candidate.
std::string CandidatesProblem(const PathsParams& params,
                              const std::vector<PathCandidate>& candidates);

// The records section before compression: per candidate, six LEB128 varints (the spec).
void EncodeRecords(const PathsParams& params, const std::vector<PathCandidate>& candidates,
                   std::string* out);
// Decodes exactly `count` records from exactly `size` bytes and checks them
// (CandidatesProblem). Corruption naming the record and its byte in the section.
Status DecodeRecords(const uint8_t* bytes, size_t size, uint64_t count, const PathsParams& params,
                     std::vector<PathCandidate>* candidates);

}  // namespace motif::paths_file
