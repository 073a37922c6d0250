// Damaged archives: truncations, flipped bytes, wrong magic, random bytes, empty files. The
// rule everywhere: Open fails with Corruption, or Verify (and a read of the damaged block)
// fails with Corruption; never a crash, never silently different data.
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "formats/frame_file/archive_loader.h"
#include "formats/frame_file/frame_file_format.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/formats/frame_file/frame_file_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

using frame_file::kSlotBytes;
using frame_file::kSlotOffsets;

constexpr uint32_t kCorruptionJoints = 2;

FrameFileWriterOptions Options() {
  FrameFileWriterOptions options;
  options.block_frames = 16;
  return options;
}

std::string MakeSmallArchive(const TempDir& dir, const std::string& name = "a.mfs") {
  const std::string path = dir.File(name);
  WriteArchive(
      path, MakeSkeleton(kCorruptionJoints),
      {MakeClip("one", kCorruptionJoints, 20, 1), MakeClip("two", kCorruptionJoints, 21, 2)},
      Options());
  return path;
}

// The committed version's structure, decoded by the library's own loader.
frame_file::LoadedArchive Structure(const std::string& bytes) {
  auto loaded =
      frame_file::LoadArchive("x", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  EXPECT_TRUE(loaded.ok()) << loaded.status().ToString();
  return loaded.ok() ? *loaded : frame_file::LoadedArchive();
}

bool InRange(size_t offset, uint64_t begin, uint64_t size) {
  return offset >= begin && offset - begin < size;
}

int BlockHolding(const frame_file::LoadedArchive& archive, size_t offset) {
  for (size_t block_idx = 0; block_idx < archive.metadata.blocks.size(); ++block_idx) {
    const frame_file::BlockHandle& block = archive.metadata.blocks[block_idx];
    if (InRange(offset, block.offset, block.bytes)) return static_cast<int>(block_idx);
  }
  return -1;
}

enum class Outcome { kOpenFailed, kVerifyFailed, kClean };

// Opens `path` and applies the rule. `expected`: the contents that must come back if nothing is
// reported. `allowed_previous`: another version that may come back unreported.
Outcome CheckDamaged(const std::string& path, const ArchiveContents& expected, int damaged_block,
                     const frame_file::LoadedArchive& structure, const std::string& context) {
  auto reader = FrameFileReader::Open(path);
  if (!reader.ok()) {
    // A damaged major version reads as a future one (NotSupported, exit 15).
    EXPECT_TRUE(reader.status().IsCorruption() || reader.status().IsNotSupported())
        << context << ": " << reader.status().ToString();
    EXPECT_NE(reader.status().message().find(path), std::string::npos) << context;
    return Outcome::kOpenFailed;
  }
  Status verified = (*reader)->Verify();
  if (!verified.ok()) {
    EXPECT_TRUE(verified.IsCorruption()) << context << ": " << verified.ToString();
  }
  const size_t stride = (*reader)->layout().stride();
  if (damaged_block >= 0 && (*reader)->frame_count() == structure.metadata.frame_count) {
    // The damaged block fails; every other block still reads back exactly.
    for (size_t block_idx = 0; block_idx < structure.metadata.blocks.size(); ++block_idx) {
      const frame_file::BlockHandle& block = structure.metadata.blocks[block_idx];
      std::vector<float> rows;
      Status read = (*reader)->ReadFrames(block.first_frame, block.frame_count, &rows);
      if (static_cast<int>(block_idx) == damaged_block) {
        EXPECT_TRUE(read.IsCorruption()) << context << ": block " << block_idx;
        EXPECT_NE(read.message().find("block " + std::to_string(block_idx) + " at offset " +
                                      frame_file::Hex(block.offset)),
                  std::string::npos)
            << context << ": " << read.message();
      } else {
        EXPECT_TRUE(read.ok()) << context << ": " << read.ToString();
        const std::vector<float> want(
            expected.rows.begin() + block.first_frame * stride,
            expected.rows.begin() + (block.first_frame + block.frame_count) * stride);
        EXPECT_TRUE(SameBits(want, rows)) << context << ": block " << block_idx;
      }
    }
  }
  if (!verified.ok()) return Outcome::kVerifyFailed;
  return Outcome::kClean;
}

TEST(FrameFileCorruption, RejectsAnEmptyFile) {
  TempDir dir;
  WriteBytes(dir.File("e.mfs"), "");
  auto reader = FrameFileReader::Open(dir.File("e.mfs"));
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption());
  EXPECT_NE(reader.status().message().find("empty"), std::string::npos);
}

TEST(FrameFileCorruption, RejectsAWrongMagic) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  std::string bytes = ReadBytes(path);
  bytes[0] = 'P';
  WriteBytes(path, bytes);
  auto reader = FrameFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption());
  EXPECT_NE(reader.status().message().find("bad magic"), std::string::npos);
  EXPECT_NE(reader.status().message().find(path), std::string::npos);
}

TEST(FrameFileCorruption, RejectsAnUnknownMajorVersion) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  std::string bytes = ReadBytes(path);
  bytes[8] = 2;  // major 2, with a header checksum that matches
  std::string checksum;
  frame_file::PutU64(&checksum, frame_file::Checksum64(bytes.data(), 40));
  bytes.replace(40, 8, checksum);
  WriteBytes(path, bytes);
  auto reader = FrameFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsNotSupported());
  EXPECT_NE(reader.status().message().find("major version 2"), std::string::npos);
}

TEST(FrameFileCorruption, RejectsRandomBytes) {
  TempDir dir;
  std::mt19937 random(17);
  for (int trial = 0; trial < 300; ++trial) {
    const std::string path = dir.File(Numbered("r", trial));  // a new file: no O_TRUNC flush
    std::string bytes(random() % 3000, '\0');
    for (char& byte : bytes) byte = static_cast<char>(random());
    if (trial % 2 == 0 && bytes.size() >= 8) bytes.replace(0, 8, "\x89MFS\r\n\x1a\n");
    WriteBytes(path, bytes);
    auto reader = FrameFileReader::Open(path);
    ASSERT_FALSE(reader.ok()) << trial;
    EXPECT_TRUE(reader.status().IsCorruption() || reader.status().IsNotSupported())
        << reader.status().ToString();
  }
}

TEST(FrameFileCorruption, RejectsTruncatedFooter) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  const std::string bytes = ReadBytes(path);
  WriteBytes(path, bytes.substr(0, bytes.size() - 10));
  auto reader = FrameFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption());
  EXPECT_NE(reader.status().message().find("truncated"), std::string::npos)
      << reader.status().message();
}

TEST(FrameFileCorruption, RejectsEveryTruncation) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  const std::string bytes = ReadBytes(path);
  const std::string cut = dir.File("cut.mfs");
  WriteBytes(cut, bytes);
  for (size_t length = bytes.size(); length-- > 0;) {
    std::filesystem::resize_file(cut, length);  // shrinking in place: no rewrite per length
    auto reader = FrameFileReader::Open(cut);
    ASSERT_FALSE(reader.ok()) << "length " << length;
    ASSERT_TRUE(reader.status().IsCorruption()) << length << ": " << reader.status().ToString();
  }
}

TEST(FrameFileCorruption, TruncatingAnAppendedArchiveIsAlwaysReported) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  auto previous = ReadContents(path);
  ASSERT_TRUE(previous.ok());
  AppendToArchive(path, {MakeClip("three", kCorruptionJoints, 30, 3)}, Options());
  const std::string bytes = ReadBytes(path);
  const std::string cut = dir.File("cut.mfs");
  WriteBytes(cut, bytes);
  for (size_t length = bytes.size(); length-- > 0;) {
    std::filesystem::resize_file(cut, length);
    auto reader = FrameFileReader::Open(cut);
    if (!reader.ok()) {
      ASSERT_TRUE(reader.status().IsCorruption()) << length;
      continue;
    }
    // The newest commit is cut off: the previous version opens, and Verify says why.
    EXPECT_FALSE((*reader)->summary().fallback_reason.empty()) << length;
    EXPECT_TRUE((*reader)->Verify().IsCorruption()) << length;
    EXPECT_EQ((*reader)->clips().size(), previous->clips.size()) << length;
  }
}

TEST(FrameFileCorruption, DetectsEveryFlippedByte) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  const std::string bytes = ReadBytes(path);
  auto original = ReadContents(path);
  ASSERT_TRUE(original.ok());
  const frame_file::LoadedArchive structure = Structure(bytes);
  ASSERT_EQ(structure.active_slot, 0);
  const std::string damaged = dir.File("damaged.mfs");
  WriteBytes(damaged, bytes);
  int open_failed = 0, verify_failed = 0, clean = 0;
  for (size_t offset = 0; offset < bytes.size(); ++offset) {
    for (uint8_t mask : {0x01, 0x80}) {
      PatchByte(damaged, offset, static_cast<char>(bytes[offset] ^ mask));
      const std::string context = "byte " + std::to_string(offset) + " ^ " + std::to_string(mask);
      const Outcome outcome =
          CheckDamaged(damaged, *original, BlockHolding(structure, offset), structure, context);
      if (outcome == Outcome::kClean) {
        // Only the unused commit slot may change unnoticed (it is what a torn slot write
        // leaves), and then nothing else changed.
        EXPECT_TRUE(InRange(offset, kSlotOffsets[1], kSlotBytes)) << context;
        auto contents = ReadContents(damaged);
        ASSERT_TRUE(contents.ok()) << context;
        ExpectSameContents(*original, *contents);
        ++clean;
      } else if (outcome == Outcome::kVerifyFailed) {
        ++verify_failed;
      } else {
        ++open_failed;
      }
      PatchByte(damaged, offset, bytes[offset]);
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_EQ(clean, 2 * static_cast<int>(kSlotBytes));
  EXPECT_GT(verify_failed, 0);
  EXPECT_GT(open_failed, 0);
}

TEST(FrameFileCorruption, DetectsFlippedBytesInAnAppendedArchive) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  auto previous = ReadContents(path);
  ASSERT_TRUE(previous.ok());
  const uint64_t previous_length = ReadBytes(path).size();
  AppendToArchive(path, {MakeClip("three", kCorruptionJoints, 30, 3)}, Options());
  const std::string bytes = ReadBytes(path);
  auto current = ReadContents(path);
  ASSERT_TRUE(current.ok());
  const frame_file::LoadedArchive structure = Structure(bytes);
  ASSERT_EQ(structure.active_slot, 1);
  // Generation 1's metadata and footer, superseded by generation 2's.
  const uint64_t dead_begin =
      structure.metadata.blocks[2].offset + structure.metadata.blocks[2].bytes;
  const std::string damaged = dir.File("damaged.mfs");
  WriteBytes(damaged, bytes);
  for (size_t offset = 0; offset < bytes.size(); ++offset) {
    PatchByte(damaged, offset, static_cast<char>(bytes[offset] ^ 0x04));
    const std::string context = "byte " + std::to_string(offset);
    const Outcome outcome =
        CheckDamaged(damaged, *current, BlockHolding(structure, offset), structure, context);
    if (outcome == Outcome::kClean) {
      auto contents = ReadContents(damaged);
      ASSERT_TRUE(contents.ok()) << context;
      if (contents->clips.size() == previous->clips.size()) {
        // Reverting to the previous version unreported is what a torn slot write looks like,
        // so only a damaged active slot may do it.
        EXPECT_TRUE(InRange(offset, kSlotOffsets[1], kSlotBytes)) << context;
        ExpectSameContents(*previous, *contents);
      } else {
        // Unnoticed changes only where nothing of the current version lives: the older slot
        // and the superseded metadata and footer of generation 1.
        EXPECT_TRUE(InRange(offset, kSlotOffsets[0], kSlotBytes) ||
                    (offset >= dead_begin && offset < previous_length))
            << context;
        ExpectSameContents(*current, *contents);
      }
    }
    PatchByte(damaged, offset, bytes[offset]);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(FrameFileCorruption, ChecksumMismatchNamesTheFileTheBlockAndItsOffset) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  std::string bytes = ReadBytes(path);
  const frame_file::LoadedArchive structure = Structure(bytes);
  const frame_file::BlockHandle& block = structure.metadata.blocks[1];
  bytes[block.offset + block.bytes / 2] ^= 0x20;
  WriteBytes(path, bytes);
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  std::vector<float> rows;
  Status read = (*reader)->ReadFrames(block.first_frame, 1, &rows);
  EXPECT_TRUE(read.IsCorruption());
  EXPECT_EQ(read.message(),
            path + ": block 1 at offset " + frame_file::Hex(block.offset) + ": checksum mismatch");
  Status verified = (*reader)->Verify();
  EXPECT_EQ(verified.message(), read.message());
  auto stream = (*reader)->Stream();
  ASSERT_TRUE(stream->Next().ok());
  Result<bool> second = stream->Next();
  EXPECT_TRUE(second.status().IsCorruption());
}

TEST(FrameFileCorruption, FallsBackToThePreviousVersionWhenTheNewestFooterIsDamaged) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  auto previous = ReadContents(path);
  ASSERT_TRUE(previous.ok());
  AppendToArchive(path, {MakeClip("three", kCorruptionJoints, 30, 3)}, Options());
  std::string bytes = ReadBytes(path);
  bytes[bytes.size() - 20] ^= 0x01;  // inside the newest footer
  WriteBytes(path, bytes);

  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->summary().generation, 1u);
  EXPECT_NE((*reader)->summary().fallback_reason.find("footer"), std::string::npos);
  Status verified = (*reader)->Verify();
  EXPECT_TRUE(verified.IsCorruption());
  EXPECT_NE(verified.message().find("generation 1"), std::string::npos) << verified.message();
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ExpectSameContents(*previous, *contents);
  // A writer does not build on a damaged archive.
  auto writer = FrameFileWriter::OpenForAppend(path, Options());
  EXPECT_TRUE(writer.status().IsCorruption());
}

TEST(FrameFileCorruption, ATornSlotWriteKeepsTheNewestVersionAndReportsTheSlot) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  const std::string before = ReadBytes(path);
  AppendToArchive(path, {MakeClip("three", kCorruptionJoints, 30, 3)}, Options());
  auto current = ReadContents(path);
  ASSERT_TRUE(current.ok());
  std::string bytes = ReadBytes(path);
  // Only the first half of the new slot reached the disk (a power loss in that one write).
  bytes.replace(kSlotOffsets[1] + kSlotBytes / 2, kSlotBytes / 2,
                before.substr(kSlotOffsets[1] + kSlotBytes / 2, kSlotBytes / 2));
  WriteBytes(path, bytes);
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->summary().generation, 2u);
  EXPECT_EQ((*reader)->summary().uncommitted_bytes, 0u);
  EXPECT_TRUE((*reader)->summary().fallback_reason.empty());
  Status verified = (*reader)->Verify();
  EXPECT_TRUE(verified.IsCorruption());
  EXPECT_NE(verified.message().find("commit slot 1"), std::string::npos) << verified.message();
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ExpectSameContents(*current, *contents);
}

// A flipped bit in the slot that names the newest version (bytes 0x58-0x7f of a two-commit
// archive) must not hide that version, nor let an append write over it.
TEST(FrameFileCorruption, AFlippedBitInTheActiveSlotLosesNoVersion) {
  TempDir dir;
  const std::string path = MakeSmallArchive(dir);
  AppendToArchive(path, {MakeClip("three", kCorruptionJoints, 30, 3)}, Options());
  auto current = ReadContents(path);
  ASSERT_TRUE(current.ok());
  const std::string bytes = ReadBytes(path);
  ASSERT_EQ(Structure(bytes).active_slot, 1);
  for (size_t offset = kSlotOffsets[1]; offset < kSlotOffsets[1] + kSlotBytes; ++offset) {
    for (uint8_t mask : {0x01, 0x80}) {
      const std::string context = "byte " + std::to_string(offset) + " ^ " + std::to_string(mask);
      std::string damaged = bytes;
      damaged[offset] = static_cast<char>(damaged[offset] ^ mask);
      WriteBytes(path, damaged);
      auto reader = FrameFileReader::Open(path);
      ASSERT_TRUE(reader.ok()) << context << ": " << reader.status().ToString();
      EXPECT_EQ((*reader)->clips().size(), 3u) << context;
      EXPECT_TRUE((*reader)->Verify().IsCorruption()) << context;
      // The next commit goes to the other slot; every version stays.
      AppendToArchive(path, {MakeClip("four", kCorruptionJoints, 17, 4)}, Options());
      auto appended = FrameFileReader::Open(path);
      ASSERT_TRUE(appended.ok()) << context;
      EXPECT_EQ((*appended)->clips().size(), 4u) << context;
      EXPECT_TRUE((*appended)->Verify().ok()) << context;
      auto second = FrameFileReader::OpenCommit(path, 2, bytes.size());
      ASSERT_TRUE(second.ok()) << context << ": " << second.status().ToString();
      EXPECT_EQ((*second)->clips().size(), 3u) << context;
      if (::testing::Test::HasFailure()) return;
    }
  }
}

}  // namespace
}  // namespace motif::testing
