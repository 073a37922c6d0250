#include "formats/paths_file/paths_file_format.h"

#include <cstring>
#include <tuple>

#include "formats/format_checks/format_checks.h"

namespace motif::paths_file {

namespace {

void PutVarint(std::string* out, uint64_t value) {
  while (value >= 0x80) {
    out->push_back(static_cast<char>(value | 0x80));
    value >>= 7;
  }
  out->push_back(static_cast<char>(value));
}

// At most 10 bytes, and the value fits in 64 bits; false at the end of the input or if not.
bool GetVarint(const uint8_t** cursor, const uint8_t* end, uint64_t* value) {
  uint64_t result = 0;
  const uint8_t* p = *cursor;
  for (int shift = 0; shift < 64 && p < end; shift += 7) {
    const uint8_t byte = *p++;
    if (shift == 63 && byte > 1) return false;
    result |= static_cast<uint64_t>(byte & 0x7F) << shift;
    if (byte < 0x80) {
      *value = result;
      *cursor = p;
      return true;
    }
  }
  return false;
}

uint64_t ZigZag(uint64_t from, uint64_t to) {  // zigzag(to - from), as a signed 64-bit value
  const int64_t delta = static_cast<int64_t>(to - from);
  return (static_cast<uint64_t>(delta) << 1) ^ static_cast<uint64_t>(delta >> 63);
}

uint64_t UnZigZag(uint64_t from, uint64_t code) {  // from + unzigzag(code), mod 2^64
  const int64_t delta = static_cast<int64_t>(code >> 1) ^ -static_cast<int64_t>(code & 1);
  return from + static_cast<uint64_t>(delta);
}

auto SortKey(const PathCandidate& candidate) {
  return std::tie(candidate.top_start, candidate.match_start, candidate.top_end,
                  candidate.match_end, candidate.root_column, candidate.root_frame);
}

// "" if the candidate is within the params, else why not.
std::string CandidateProblem(const PathsParams& params, const PathCandidate& candidate) {
  const uint64_t n = params.frame_count;
  if (candidate.top_end > n || candidate.top_start > candidate.top_end || candidate.match_end > n ||
      candidate.match_start > candidate.match_end) {
    return "top row [" + std::to_string(candidate.top_start) + ", " +
           std::to_string(candidate.top_end) + ") or match [" +
           std::to_string(candidate.match_start) + ", " + std::to_string(candidate.match_end) +
           ") is not a range within the " + std::to_string(n) + " frames";
  }
  if (candidate.top_length() < params.min_length || candidate.match_length() < params.min_length) {
    return "lengths " + std::to_string(candidate.top_length()) + " and " +
           std::to_string(candidate.match_length()) + " are not both at least min_length " +
           std::to_string(params.min_length);
  }
  if (candidate.root_column > candidate.top_start || candidate.root_frame >= n) {
    return "root (column " + std::to_string(candidate.root_column) + ", frame " +
           std::to_string(candidate.root_frame) + ") is after the path's start or outside " +
           "the frames";
  }
  return "";
}

// "" if `candidate` may follow `previous`: strictly after it in the sort order and, unless the
// file holds all branches, of another tree.
std::string OrderProblem(const PathsParams& params, const PathCandidate& previous,
                         const PathCandidate& candidate) {
  if (!(SortKey(previous) < SortKey(candidate))) {
    return "not after the previous one in the sort order (or equal to it)";
  }
  if (!params.all_branches && previous.root_column == candidate.root_column &&
      previous.root_frame == candidate.root_frame) {
    return "a second path of the tree rooted at column " + std::to_string(candidate.root_column) +
           ", frame " + std::to_string(candidate.root_frame) + " (all_branches is not set)";
  }
  return "";
}

}  // namespace

std::string ParamsProblem(const PathsParams& params) {
  if (params.frame_count > kMaxFrameCount) {
    return "frame_count " + std::to_string(params.frame_count) + " exceeds 2^32";
  }
  if (params.branch == 0) return "branch is 0";
  if (params.min_length == 0 || params.min_length > kMaxFrameCount) {
    return "min_length " + std::to_string(params.min_length) + " is not in [1, 2^32]";
  }
  return "";
}

std::string CandidatesProblem(const PathsParams& params,
                              const std::vector<PathCandidate>& candidates) {
  for (size_t idx = 0; idx < candidates.size(); ++idx) {
    std::string problem = CandidateProblem(params, candidates[idx]);
    if (problem.empty() && idx > 0)
      problem = OrderProblem(params, candidates[idx - 1], candidates[idx]);
    if (!problem.empty()) return "candidate " + std::to_string(idx) + ": " + problem;
  }
  return "";
}

// Header, 96 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 header_bytes u32
//   16 trellis_identity u64 | 24 archive_identity u64 | 32 frame_count u64 | 40 branch u32
//   44 flags u32 (bit 0: all_branches; the others 0) | 48 min_length u64 | 56 candidate_count u64 |
//   64 records_raw_bytes u64 72 records_bytes u64 | 80 records_checksum u64 | 88 header_checksum
//   u64 of [0, 88)
void FileHeader::EncodeTo(std::string* out) const {
  std::string header(kFileMagic.begin(), kFileMagic.end());
  PutU16(&header, format_major);
  PutU16(&header, format_minor);
  PutU32(&header, static_cast<uint32_t>(kHeaderBytes));
  PutU64(&header, params.trellis_identity);
  PutU64(&header, params.archive_identity);
  PutU64(&header, params.frame_count);
  PutU32(&header, params.branch);
  PutU32(&header, params.all_branches ? kFlagAllBranches : 0);
  PutU64(&header, params.min_length);
  PutU64(&header, candidate_count);
  PutU64(&header, records_raw_bytes);
  PutU64(&header, records_bytes);
  PutU64(&header, records_checksum);
  PutU64(&header, Checksum64(header.data(), header.size()));
  out->append(header);
}

Status FileHeader::DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header) {
  MOTIF_RETURN_IF_ERROR(
      CheckMagicAndMajor(bytes, size, kFileMagic.data(), "paths file", kFormatMajor));
  header->format_major = LoadU16(bytes + 8);
  MOTIF_RETURN_IF_ERROR(CheckFileHoldsHeader(size, kHeaderBytes));
  header->format_minor = LoadU16(bytes + 10);
  header->header_bytes = LoadU32(bytes + 12);
  if (header->header_bytes < kHeaderBytes || header->header_bytes > kMaxHeaderBytes ||
      header->header_bytes > size) {
    return Status::Corruption(
        "header at offset 0x0: header_bytes " + std::to_string(header->header_bytes) +
        " is not in [" + std::to_string(kHeaderBytes) + ", min(" + std::to_string(kMaxHeaderBytes) +
        ", file size " + std::to_string(size) + ")]");
  }
  MOTIF_RETURN_IF_ERROR(CheckHeaderChecksum(bytes, header->header_bytes));
  header->params.trellis_identity = LoadU64(bytes + 16);
  header->params.archive_identity = LoadU64(bytes + 24);
  header->params.frame_count = LoadU64(bytes + 32);
  header->params.branch = LoadU32(bytes + 40);
  const uint32_t flags = LoadU32(bytes + 44);
  if ((flags & ~kFlagAllBranches) != 0) {
    return Status::Corruption("header: unknown flags " + Hex(flags) + " at 0x2c");
  }
  header->params.all_branches = (flags & kFlagAllBranches) != 0;
  header->params.min_length = LoadU64(bytes + 48);
  header->candidate_count = LoadU64(bytes + 56);
  header->records_raw_bytes = LoadU64(bytes + 64);
  header->records_bytes = LoadU64(bytes + 72);
  header->records_checksum = LoadU64(bytes + 80);
  const std::string problem = ParamsProblem(header->params);
  if (!problem.empty()) return Status::Corruption("header: " + problem);
  if (!SectionEndsAt(header->header_bytes, header->records_bytes, 1, header->header_bytes, size)) {
    return Status::Corruption("header: a records section of " +
                              std::to_string(header->records_bytes) + " bytes at " +
                              Hex(header->header_bytes) + " does not end the file of " +
                              std::to_string(size) + " bytes (truncated or extended?)");
  }
  // Each record takes 6 to 60 bytes; a zstd frame expands at most ~43,690-fold.
  const uint64_t count = header->candidate_count;
  if (count > header->records_raw_bytes / kMinRecordBytes ||
      header->records_raw_bytes > count * kMaxRecordBytes ||
      header->records_raw_bytes > (header->records_bytes / 3 + 1) * kZstdMaxBlockBytes) {
    return Status::Corruption("header: " + std::to_string(count) + " candidates in " +
                              std::to_string(header->records_raw_bytes) +
                              " raw bytes compressed to " + std::to_string(header->records_bytes) +
                              " is impossible");
  }
  return Status::Ok();
}

// Per candidate c, after the previous one p (p = all zeros before the first):
//   top_start - p.top_start | zigzag(match_start - p.match_start) | top_length - min_length
//   | match_length - min_length | top_start - root_column | zigzag(root_frame - match_start)
void EncodeRecords(const PathsParams& params, const std::vector<PathCandidate>& candidates,
                   std::string* out) {
  PathCandidate previous;
  for (const PathCandidate& candidate : candidates) {
    PutVarint(out, candidate.top_start - previous.top_start);
    PutVarint(out, ZigZag(previous.match_start, candidate.match_start));
    PutVarint(out, candidate.top_length() - params.min_length);
    PutVarint(out, candidate.match_length() - params.min_length);
    PutVarint(out, candidate.top_start - candidate.root_column);
    PutVarint(out, ZigZag(candidate.match_start, candidate.root_frame));
    previous = candidate;
  }
}

Status DecodeRecords(const uint8_t* bytes, size_t size, uint64_t count, const PathsParams& params,
                     std::vector<PathCandidate>* candidates) {
  candidates->clear();
  candidates->reserve(count);
  const uint8_t* cursor = bytes;
  const uint8_t* end = bytes + size;
  const uint64_t n = params.frame_count;
  PathCandidate previous;
  for (uint64_t idx = 0; idx < count; ++idx) {
    const size_t record_offset = static_cast<size_t>(cursor - bytes);
    auto corrupt = [&](const std::string& what) {
      return Status::Corruption("records: record " + std::to_string(idx) + " at raw byte " +
                                std::to_string(record_offset) + ": " + what);
    };
    uint64_t fields[6];
    for (uint64_t& field : fields) {
      if (!GetVarint(&cursor, end, &field)) return corrupt("truncated or overlong varint");
    }
    // Bound every field by N before adding, so no sum wraps.
    if (fields[0] > n || fields[2] > n || fields[3] > n || fields[4] > n) {
      return corrupt("a field exceeds the frame count " + std::to_string(n));
    }
    PathCandidate candidate;
    candidate.top_start = previous.top_start + fields[0];
    candidate.match_start = UnZigZag(previous.match_start, fields[1]);
    if (candidate.top_start > n || candidate.match_start > n) {
      return corrupt("starts outside the " + std::to_string(n) + " frames");
    }
    candidate.top_end = candidate.top_start + params.min_length + fields[2];
    candidate.match_end = candidate.match_start + params.min_length + fields[3];
    if (fields[4] > candidate.top_start) return corrupt("root column before frame 0");
    candidate.root_column = candidate.top_start - fields[4];
    candidate.root_frame = UnZigZag(candidate.match_start, fields[5]);
    const std::string problem = CandidateProblem(params, candidate);
    if (!problem.empty()) return corrupt(problem);
    if (idx > 0) {
      const std::string order = OrderProblem(params, previous, candidate);
      if (!order.empty()) return corrupt(order);
    }
    candidates->push_back(candidate);
    previous = candidate;
  }
  if (cursor != end) {
    return Status::Corruption("records: " + std::to_string(end - cursor) +
                              " bytes left after the " + std::to_string(count) + " records");
  }
  return Status::Ok();
}

}  // namespace motif::paths_file
