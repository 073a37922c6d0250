// Fuzz target: the motion archive reader (formats/frame_file, docs/formats/frame_file.md).
//
// Every structure of an archive carries an XXH3 checksum, which random mutations never match;
// left alone, the fuzzer would only ever test the checksum comparisons. So the target first
// repairs the checksums of the input where its own offsets say they are (RepairChecksums:
// header, each written commit slot, the footer it points at, the metadata, and every block the
// BLOCKS section lists), then reads the repaired bytes twice:
//   1. in memory, on buffers of exactly the right size (AddressSanitizer catches any read past
//      a structure): LoadArchive, then DecodeBlock on a copy of each block;
//   2. through a file, as users do: FrameFileReader::Open on a scratch file, then summary(),
//      ClipOfFrame, Verify(), a FrameStream over every frame, and ReadFrames of the whole
//      archive (when small), a range across a block boundary and a range past the end.
// Promises checked: no crash, leak or undefined behaviour; Open fails exactly when LoadArchive
// does; data errors are Corruption naming the file; the stream returns every frame once, in
// order; a range past the end is InvalidArgument.
// Seeds: tests/data/fuzz/frame_file_reader/ (fuzz_seed_maker writes them).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/byte_coding.h"
#include "formats/frame_file/archive_loader.h"
#include "formats/frame_file/block_codec.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using motif::Checksum64;
using motif::LoadU32;
using motif::LoadU64;
using motif::Status;
using motif::fuzz::InRange;
using motif::fuzz::StoreU64;
namespace ff = motif::frame_file;

// Whole-archive reads above this many floats are skipped (they would only measure memset).
constexpr uint64_t kMaxReadFloats = uint64_t{1} << 22;

// Sets the checksum of every block entry of the BLOCKS sections in metadata [begin, end).
void RepairBlockChecksums(uint8_t* data, size_t size, uint64_t begin, uint64_t end) {
  constexpr uint64_t kSectionHeaderBytes = 16;
  constexpr uint64_t kBlocksPayloadHeaderBytes = 16;  // block_count, entry_bytes, reserved
  uint64_t pos = begin;
  while (end - pos >= kSectionHeaderBytes) {
    const uint32_t tag = LoadU32(data + pos);
    const uint64_t payload_bytes = LoadU64(data + pos + 8);
    if (payload_bytes > end - pos - kSectionHeaderBytes) break;
    if (tag == static_cast<uint32_t>(ff::SectionTag::kBlocks) &&
        payload_bytes >= kBlocksPayloadHeaderBytes) {
      uint8_t* payload = data + pos + kSectionHeaderBytes;
      const uint64_t block_count = LoadU64(payload);
      const uint32_t entry_bytes = LoadU32(payload + 8);
      if (entry_bytes >= ff::kBlockEntryBytes) {
        const uint64_t fitting = (payload_bytes - kBlocksPayloadHeaderBytes) / entry_bytes;
        for (uint64_t block_idx = 0; block_idx < block_count && block_idx < fitting; ++block_idx) {
          uint8_t* entry = payload + kBlocksPayloadHeaderBytes + block_idx * entry_bytes;
          const uint64_t offset = LoadU64(entry);
          const uint64_t bytes = LoadU64(entry + 8);
          if (InRange(offset, bytes, size)) {
            StoreU64(entry + 0x20, Checksum64(data + offset, bytes));
          }
        }
      }
    }
    pos += kSectionHeaderBytes + payload_bytes;
  }
}

// docs/formats/frame_file.md, section 1: block checksums (in the metadata) before the metadata
// checksum (in the footer) before the footer checksum before the slot checksum.
void RepairChecksums(uint8_t* data, size_t size) {
  if (size < ff::kHeaderFixedBytes) return;
  StoreU64(data + 0x28, Checksum64(data, 0x28));
  for (const size_t slot_offset : ff::kSlotOffsets) {
    if (!InRange(slot_offset, ff::kSlotBytes, size)) continue;
    uint8_t* slot = data + slot_offset;
    bool empty = true;
    for (size_t byte_idx = 0; byte_idx < ff::kSlotBytes; ++byte_idx) empty &= slot[byte_idx] == 0;
    if (empty) continue;  // an empty slot has no checksum
    const uint64_t footer_offset = LoadU64(slot + 0x08);
    if (InRange(footer_offset, ff::kFooterBytes, size)) {
      uint8_t* footer = data + footer_offset;
      const uint64_t metadata_offset = LoadU64(footer + 0x18);
      const uint64_t metadata_bytes = LoadU64(footer + 0x20);
      if (InRange(metadata_offset, metadata_bytes, size)) {
        RepairBlockChecksums(data, size, metadata_offset, metadata_offset + metadata_bytes);
        StoreU64(footer + 0x28, Checksum64(data + metadata_offset, metadata_bytes));
      }
      StoreU64(footer + 0x38, Checksum64(footer, 0x38));
    }
    StoreU64(slot + 0x20, Checksum64(slot, 0x20));
  }
}

// Pass 1: the loader and the block decoder on exact-size heap buffers.
bool ReadInMemory(const std::vector<uint8_t>& bytes) {
  static const std::string kName = "fuzz-memory.mfs";
  motif::Result<ff::LoadedArchive> archive = ff::LoadArchive(kName, bytes.data(), bytes.size());
  if (!archive.ok()) {
    motif::fuzz::CheckError(archive.status(), Status::Code::kCorruption, kName, "LoadArchive");
    return false;
  }
  const ff::ArchiveMetadata& metadata = archive->metadata;
  std::vector<float> rows;
  for (const ff::BlockHandle& block : metadata.blocks) {
    if (!InRange(block.offset, block.bytes, bytes.size())) {
      motif::fuzz::Fail("LoadArchive", "accepted a block outside the file");
    }
    const std::vector<uint8_t> block_bytes(bytes.begin() + block.offset,
                                           bytes.begin() + block.offset + block.bytes);
    Status status =
        ff::DecodeBlock(metadata.columns, metadata.joint_count, block, block_bytes.data(), &rows);
    motif::fuzz::CheckError(status, Status::Code::kCorruption, "", "DecodeBlock");
  }
  return true;
}

// Pass 2: FrameFileReader over a file holding the same bytes.
bool ReadThroughFile(const std::vector<uint8_t>& bytes) {
  static motif::fuzz::ScratchFile scratch("frame_file", ".mfs");
  scratch.Write(bytes.data(), bytes.size());
  const std::string& path = scratch.path();
  motif::Result<std::unique_ptr<motif::FrameFileReader>> opened =
      motif::FrameFileReader::Open(path);
  if (!opened.ok()) {
    motif::fuzz::CheckError(opened.status(), Status::Code::kCorruption, path, "Open");
    return false;
  }
  const motif::FrameFileReader& reader = **opened;
  (void)reader.summary();
  const uint64_t frame_count = reader.frame_count();
  const uint64_t stride = reader.layout().stride();
  if (frame_count > 0) {
    (void)reader.ClipOfFrame(0);
    (void)reader.ClipOfFrame(frame_count - 1);
  }
  motif::fuzz::CheckError(reader.Verify(), Status::Code::kCorruption, path, "Verify");

  std::unique_ptr<motif::FrameStream> stream = reader.Stream();
  uint64_t next_frame = 0;
  while (true) {
    motif::Result<bool> more = stream->Next();
    if (!more.ok()) {
      motif::fuzz::CheckError(more.status(), Status::Code::kCorruption, path, "FrameStream");
      break;
    }
    if (!*more) {
      if (next_frame != frame_count) {
        motif::fuzz::Fail("FrameStream", "ended at frame " + std::to_string(next_frame) + " of " +
                                             std::to_string(frame_count));
      }
      break;
    }
    if (stream->first_frame() != next_frame || stream->frame_count() == 0 ||
        stream->frame_count() > frame_count - next_frame) {
      motif::fuzz::Fail("FrameStream", "run [" + std::to_string(stream->first_frame()) + ", +" +
                                           std::to_string(stream->frame_count()) +
                                           ") where frame " + std::to_string(next_frame) +
                                           " was next");
    }
    next_frame += stream->frame_count();
  }

  std::vector<float> rows;
  if (frame_count * stride <= kMaxReadFloats) {  // stride <= 4 * 4096 + 4: no overflow
    motif::fuzz::CheckError(reader.ReadFrames(0, frame_count, &rows), Status::Code::kCorruption,
                            path, "ReadFrames(all)");
  }
  if (frame_count >= 2) {
    const uint64_t first = frame_count / 2 - 1;
    motif::fuzz::CheckError(reader.ReadFrames(first, 2, &rows), Status::Code::kCorruption, path,
                            "ReadFrames(middle)");
  }
  Status past_end = reader.ReadFrames(frame_count, 1, &rows);
  if (!past_end.IsInvalidArgument()) {
    motif::fuzz::Fail("ReadFrames(past the end)", past_end.ToString());
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  RepairChecksums(bytes.data(), bytes.size());
  const bool loaded = ReadInMemory(bytes);
  const bool opened = ReadThroughFile(bytes);
  if (loaded != opened) {
    motif::fuzz::Fail("FrameFileReader::Open", opened ? "opened what LoadArchive rejected"
                                                      : "rejected what LoadArchive accepted");
  }
  return 0;
}
