// Fuzz target: the paths file reader (formats/paths_file, docs/formats/paths_file.md), through
// its in-memory entry point PathsFileReader::FromBytes (Open only reads the file into a string
// first).
//
// The header and the records section carry XXH3 checksums, which random mutations never match,
// so the target first repairs them where the input's own header says they are (the records
// checksum, then the header checksum). A file the reader accepts is then written again
// (EncodePathsFile) and read back: the writer must accept what the reader accepted, and the
// round trip must give the same params and candidates.
// Promises checked: no crash, leak or undefined behaviour; errors are Corruption naming the
// file; accepted candidates follow the file's rules (CandidatesProblem); the round trip.
// Seeds: tests/data/fuzz/paths_file_reader/ (fuzz_seed_maker writes them).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "common/byte_coding.h"
#include "formats/paths_file/paths_file_format.h"
#include "formats/paths_file/paths_file_reader.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using motif::Checksum64;
using motif::LoadU32;
using motif::LoadU64;
using motif::Status;
using motif::fuzz::Fail;
using motif::fuzz::InRange;
using motif::fuzz::StoreU64;

constexpr size_t kRecordsChecksumOffset = 0x50;
constexpr size_t kRecordsBytesOffset = 0x48;

void RepairChecksums(uint8_t* data, size_t size) {
  if (size < 0x10) return;
  const uint64_t header_bytes = LoadU32(data + 0x0c);
  if (header_bytes < kRecordsChecksumOffset + 16 || header_bytes > size) {
    return;  // no room for the 1.0 header's fields: the reader rejects it before any checksum
  }
  const uint64_t records_bytes = LoadU64(data + kRecordsBytesOffset);
  if (InRange(header_bytes, records_bytes, size)) {
    StoreU64(data + kRecordsChecksumOffset, Checksum64(data + header_bytes, records_bytes));
  }
  StoreU64(data + header_bytes - 8, Checksum64(data, header_bytes - 8));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string kName = "fuzz.mpa";
  std::string bytes(reinterpret_cast<const char*>(data), size);
  RepairChecksums(reinterpret_cast<uint8_t*>(bytes.data()), bytes.size());
  motif::Result<std::unique_ptr<motif::PathsFileReader>> reader =
      motif::PathsFileReader::FromBytes(bytes, kName);
  if (!reader.ok()) {
    motif::fuzz::CheckError(reader.status(), Status::Code::kCorruption, kName, "FromBytes");
    return 0;
  }
  const motif::PathsParams& params = (*reader)->params();
  const std::vector<motif::PathCandidate>& candidates = (*reader)->candidates();
  const std::string problem = motif::paths_file::CandidatesProblem(params, candidates);
  if (!problem.empty()) Fail("FromBytes", "accepted candidates that break the rules: " + problem);

  motif::Result<std::string> encoded = motif::EncodePathsFile(params, candidates, /*zstd_level=*/1);
  if (!encoded.ok())
    Fail("EncodePathsFile", "refused what the reader accepted: " + encoded.status().ToString());
  motif::Result<std::unique_ptr<motif::PathsFileReader>> again =
      motif::PathsFileReader::FromBytes(*encoded, kName);
  if (!again.ok()) Fail("round trip", again.status().ToString());
  if (!((*again)->params() == params) || (*again)->candidates() != candidates) {
    Fail("round trip", "params or candidates differ");
  }
  return 0;
}
