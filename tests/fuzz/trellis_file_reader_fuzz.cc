// Fuzz target: the matching-trellis reader (formats/trellis_file, docs/formats/trellis_file.md).
//
// Every structure of a trellis file carries an XXH3 checksum, which random mutations never
// match. So the target first repairs the checksums of the input where its own offsets say they
// are (RepairChecksums: every block the index lists, with the index's copy, the header, the
// index and the footer), then opens the repaired bytes through a scratch file
// (TrellisFileReader::Open) and reads everything: params and counts, Verify(), every block with
// and without distances, the columns of the whole trellis (when small) and of a range across a
// block boundary, and requests past the end. Each block the reader accepted is also decoded
// again from an exact-size heap copy (BlockDecoder), so that AddressSanitizer catches any read
// past a block, which the file mapping would hide.
// Promises checked: no crash, leak or undefined behaviour; data errors are Corruption naming
// the file; requests past the end are InvalidArgument; Verify() passes exactly when every
// block reads; a decoded block satisfies the format (offsets tile the neighbours, frames
// strictly increasing and below frame_count, at most k_max per column, distances in
// [0, eps]); the heap decode equals the reader's.
// Seeds: tests/data/fuzz/trellis_file_reader/ (fuzz_seed_maker writes them).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/byte_coding.h"
#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_format.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using motif::Checksum64;
using motif::LoadU32;
using motif::LoadU64;
using motif::Status;
using motif::TrellisBlock;
using motif::fuzz::Fail;
using motif::fuzz::InRange;
using motif::fuzz::StoreU64;
namespace tf = motif::trellis_file;

// Whole-trellis column reads above this many columns or neighbours are skipped.
constexpr uint64_t kMaxReadColumns = uint64_t{1} << 16;
constexpr uint64_t kMaxReadNeighbours = uint64_t{1} << 20;

// docs/formats/trellis_file.md, section 1: block trailers (copied into the index) before the
// index checksum; the header checksum (copied into the footer); the footer checksum last.
void RepairChecksums(uint8_t* data, size_t size) {
  if (size < tf::kFooterBytes) return;
  uint8_t* footer = data + size - tf::kFooterBytes;
  const uint64_t index_offset = LoadU64(footer + 0x10);
  const uint64_t block_count = LoadU64(footer + 0x18);
  if (index_offset <= size - tf::kFooterBytes &&
      block_count <= (size - tf::kFooterBytes - index_offset) / tf::kBlockEntryBytes) {
    uint8_t* index = data + index_offset;
    for (uint64_t block_idx = 0; block_idx < block_count; ++block_idx) {
      uint8_t* entry = index + block_idx * tf::kBlockEntryBytes;
      const uint64_t offset = LoadU64(entry);
      const uint64_t bytes = LoadU64(entry + 8);
      if (bytes < tf::kBlockTrailerBytes || !InRange(offset, bytes, size)) continue;
      const uint64_t trailer = Checksum64(data + offset, bytes - tf::kBlockTrailerBytes);
      StoreU64(data + offset + bytes - tf::kBlockTrailerBytes, trailer);
      StoreU64(entry + 0x20, trailer);
    }
    StoreU64(footer + 0x28, Checksum64(index, block_count * tf::kBlockEntryBytes));
  }
  if (size >= 0x10) {
    const uint64_t header_bytes = LoadU32(data + 0x0c);
    if (header_bytes >= 8 && header_bytes <= size) {
      const uint64_t checksum = Checksum64(data, header_bytes - 8);
      StoreU64(data + header_bytes - 8, checksum);
      StoreU64(footer + 0x30, checksum);
    }
  }
  StoreU64(footer + 0x38, Checksum64(footer, 0x38));
}

// The format's promises about a decoded block (docs/formats/trellis_file.md, 4.4 and 4.5).
void CheckBlock(const TrellisBlock& block, const motif::TrellisParams& params, uint64_t block_idx,
                bool with_distances) {
  const std::string where = "block " + std::to_string(block_idx);
  if (block.offsets.size() != uint64_t{block.column_count} + 1 || block.offsets.front() != 0 ||
      block.offsets.back() != block.neighbours.size()) {
    Fail(where, "offsets do not tile the neighbours");
  }
  for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
    const uint32_t begin = block.offsets[column_idx];
    const uint32_t end = block.offsets[column_idx + 1];
    if (begin > end || end - begin > params.k_max) Fail(where, "a column holds too many entries");
    for (uint32_t entry_idx = begin; entry_idx < end; ++entry_idx) {
      const motif::Neighbour& neighbour = block.neighbours[entry_idx];
      if (neighbour.frame >= params.frame_count ||
          (entry_idx > begin && neighbour.frame <= block.neighbours[entry_idx - 1].frame)) {
        Fail(where, "frames out of order or out of range");
      }
      if (with_distances ? !(neighbour.distance >= 0 && neighbour.distance <= params.eps)
                         : neighbour.distance != 0) {
        Fail(where, "distance " + std::to_string(neighbour.distance) + " outside [0, eps]");
      }
    }
  }
}

bool SameBlock(const TrellisBlock& a, const TrellisBlock& b) {
  return a.first_column == b.first_column && a.column_count == b.column_count &&
         a.offsets == b.offsets && a.neighbours == b.neighbours;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  RepairChecksums(bytes.data(), bytes.size());
  static motif::fuzz::ScratchFile scratch("trellis_file", ".mtr");
  scratch.Write(bytes.data(), bytes.size());
  const std::string& path = scratch.path();

  motif::Result<std::unique_ptr<motif::TrellisFileReader>> opened =
      motif::TrellisFileReader::Open(path);
  if (!opened.ok()) {
    motif::fuzz::CheckError(opened.status(), Status::Code::kCorruption, path, "Open");
    return 0;
  }
  const motif::TrellisFileReader& reader = **opened;
  const motif::TrellisParams& params = reader.params();
  (void)reader.identity();
  (void)reader.format_minor();
  const uint64_t block_count = reader.block_count();
  const uint64_t column_count = reader.column_count();

  const Status verified = reader.Verify();
  motif::fuzz::CheckError(verified, Status::Code::kCorruption, path, "Verify");

  // The index as Open validated it, for the heap decodes.
  const uint8_t* footer = bytes.data() + bytes.size() - tf::kFooterBytes;
  const uint8_t* index = bytes.data() + LoadU64(footer + 0x10);
  tf::BlockLimits limits;
  limits.frame_count = params.frame_count;
  limits.k_max = params.k_max;
  limits.eps = params.eps;
  static tf::BlockDecoder heap_decoder;

  bool every_block_read = true;
  TrellisBlock block;
  TrellisBlock heap_block;
  for (uint64_t block_idx = 0; block_idx < block_count; ++block_idx) {
    for (const bool with_distances : {false, true}) {
      const Status status = reader.ReadBlock(block_idx, &block, with_distances);
      motif::fuzz::CheckError(status, Status::Code::kCorruption, path, "ReadBlock");
      if (!status.ok()) {
        every_block_read = false;
        continue;
      }
      CheckBlock(block, params, block_idx, with_distances);
      const tf::BlockHandle handle =
          tf::BlockHandle::DecodeFrom(index + block_idx * tf::kBlockEntryBytes);
      const std::vector<uint8_t> block_bytes(bytes.begin() + handle.offset,
                                             bytes.begin() + handle.offset + handle.bytes);
      const Status heap_status =
          heap_decoder.Decode(block_bytes.data(), handle, limits, &heap_block, with_distances);
      if (!heap_status.ok() || !SameBlock(block, heap_block)) {
        Fail("BlockDecoder", "a heap copy of block " + std::to_string(block_idx) +
                                 " decodes differently: " + heap_status.ToString());
      }
    }
  }
  if (verified.ok() != every_block_read) {
    Fail("Verify", verified.ok() ? "passed, but a block does not read" : verified.ToString());
  }

  std::vector<std::vector<motif::Neighbour>> columns;
  if (column_count <= kMaxReadColumns && reader.neighbour_count() <= kMaxReadNeighbours) {
    motif::fuzz::CheckError(reader.ReadColumns(0, column_count, &columns),
                            Status::Code::kCorruption, path, "ReadColumns(all)");
  }
  if (column_count >= 2) {
    motif::fuzz::CheckError(reader.ReadColumns(column_count / 2 - 1, 2, &columns),
                            Status::Code::kCorruption, path, "ReadColumns(middle)");
  }
  if (!reader.ReadColumns(column_count, 1, &columns).IsInvalidArgument() ||
      !reader.ReadBlock(block_count, &block).IsInvalidArgument()) {
    Fail("a request past the end", "not InvalidArgument");
  }
  return 0;
}
