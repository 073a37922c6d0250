// Damaged files: whatever was cut or changed, the reader reports Corruption (NotFound for a
// missing file) from Open, ReadBlock or Verify, never crashes and never hands out data that
// differs from what was written.
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_file_format.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// The outcome of opening and reading a whole file.
struct Outcome {
  Status status;  // the first failure, or OK
  TrellisColumns columns;
};

Outcome OpenAndReadAll(const std::string& path) {
  Outcome outcome;
  auto reader = TrellisFileReader::Open(path);
  if (!reader.ok()) {
    outcome.status = reader.status();
    return outcome;
  }
  outcome.status = (*reader)->Verify();
  if (!outcome.status.ok()) return outcome;
  TrellisBlock block;
  for (uint64_t block_idx = 0; block_idx < (*reader)->block_count(); ++block_idx) {
    outcome.status = (*reader)->ReadBlock(block_idx, &block);
    if (!outcome.status.ok()) return outcome;
  }
  outcome.status = (*reader)->ReadColumns(0, (*reader)->column_count(), &outcome.columns);
  return outcome;
}

class TrellisFileCorruptionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Small: 3 blocks (8 + 8 + 4 columns), a few hundred bytes.
    params_ = MakeParams(20, 6);
    params_.search_params = "exact";
    columns_ = MakeRunColumns(20, params_.eps, 0, 6, 2, 1, 4);
    path_ = dir_.File("t.mtr");
    TrellisFileWriterOptions options;
    options.block_columns = 8;
    options.file_system = NoSyncFileSystem();
    ASSERT_TRUE(WriteTrellis(path_, params_, columns_, options).ok());
    bytes_ = ReadBytes(path_);
    auto read = ReadTrellis(path_);
    ASSERT_TRUE(read.ok());
    decoded_ = *read;
  }

  // Writes `bytes` to a new file and checks the reader rejects it with Corruption.
  void ExpectCorruption(const std::string& bytes, const std::string& context) {
    const std::string path = dir_.File("damaged-" + std::to_string(counter_++) + ".mtr");
    WriteBytes(path, bytes);
    const Outcome outcome = OpenAndReadAll(path);
    // A damaged major version reads as a future one (NotSupported, exit 15).
    EXPECT_TRUE(outcome.status.IsCorruption() || outcome.status.IsNotSupported())
        << context << ": " << outcome.status.ToString();
    EXPECT_NE(outcome.status.message().find(path), std::string::npos)
        << context << ": the message does not name the file: " << outcome.status.ToString();
    std::filesystem::remove(path);
  }

  TempDir dir_;
  TrellisParams params_;
  TrellisColumns columns_;
  TrellisColumns decoded_;
  std::string path_;
  std::string bytes_;
  int counter_ = 0;
};

TEST_F(TrellisFileCorruptionTest, TheUndamagedFileReadsBack) {
  const Outcome outcome = OpenAndReadAll(path_);
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.ToString();
  ExpectSameWithinBound(columns_, outcome.columns, params_.eps);
  EXPECT_LT(bytes_.size(), 1000u);
}

TEST_F(TrellisFileCorruptionTest, RejectsTruncationAtEveryLength) {
  for (size_t size = 0; size < bytes_.size(); ++size) {
    ExpectCorruption(bytes_.substr(0, size), "truncated to " + std::to_string(size));
  }
}

TEST_F(TrellisFileCorruptionTest, RejectsEveryFlippedByte) {
  for (size_t byte_idx = 0; byte_idx < bytes_.size(); ++byte_idx) {
    for (uint8_t mask : {0x01, 0x80}) {
      std::string damaged = bytes_;
      damaged[byte_idx] = static_cast<char>(damaged[byte_idx] ^ mask);
      ExpectCorruption(damaged, "byte " + std::to_string(byte_idx) + " ^ " + std::to_string(mask));
      if (HasFailure()) return;
    }
  }
}

TEST_F(TrellisFileCorruptionTest, RejectsBytesAppendedOrInserted) {
  ExpectCorruption(bytes_ + std::string(1, '\0'), "one byte appended");
  ExpectCorruption(bytes_ + bytes_, "the file twice");
  ExpectCorruption(std::string(1, '\0') + bytes_, "one byte in front");
  std::string inserted = bytes_;
  inserted.insert(bytes_.size() / 2, "x");
  ExpectCorruption(inserted, "one byte inserted in the middle");
}

TEST_F(TrellisFileCorruptionTest, RejectsAnEmptyFile) {
  const std::string path = dir_.File("empty.mtr");
  WriteBytes(path, "");
  auto reader = TrellisFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption());
  EXPECT_NE(reader.status().message().find("empty file"), std::string::npos);
}

TEST_F(TrellisFileCorruptionTest, RejectsAWrongMagic) {
  std::string damaged = bytes_;
  damaged[1] = 'X';
  const std::string path = dir_.File("magic.mtr");
  WriteBytes(path, damaged);
  auto reader = TrellisFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption());
  EXPECT_NE(reader.status().message().find("bad magic"), std::string::npos);
  // Another format's file: the motion archive's magic.
  damaged = bytes_;
  damaged.replace(0, 4, "\x89MFS");
  ExpectCorruption(damaged, "motion archive magic");
}

TEST_F(TrellisFileCorruptionTest, RejectsAnUnfinishedPartialFile) {
  const std::string partial = dir_.File("u.mtr.partial");
  TrellisFileWriterOptions options;
  options.block_columns = 8;
  options.file_system = NoSyncFileSystem();
  {
    auto writer = TrellisFileWriter::OpenOrResume(dir_.File("u.mtr"), params_, options);
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE((*writer)->AppendBlock(Slice(columns_, 0, 8)).ok());
  }
  auto reader = TrellisFileReader::Open(partial);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsCorruption()) << reader.status().ToString();
}

TEST_F(TrellisFileCorruptionTest, RejectsRandomBytes) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    std::string random(rng() % 2000, '\0');
    for (char& byte : random) byte = static_cast<char>(rng());
    if (trial % 2 == 1 && random.size() >= 8) random.replace(0, 8, bytes_.substr(0, 8));
    ExpectCorruption(random, "random bytes, trial " + std::to_string(trial));
  }
}

TEST_F(TrellisFileCorruptionTest, RejectsAFutureMajorVersionByName) {
  std::string damaged = bytes_;
  damaged[8] = 2;  // format_major
  const std::string path = dir_.File("v2.mtr");
  WriteBytes(path, damaged);
  auto reader = TrellisFileReader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsNotSupported());
  EXPECT_NE(reader.status().message().find("major version 2"), std::string::npos)
      << reader.status().ToString();
}

TEST_F(TrellisFileCorruptionTest, ReportsAMissingFileAsNotFound) {
  auto reader = TrellisFileReader::Open(dir_.File("missing.mtr"));
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsNotFound());
  auto directory = TrellisFileReader::Open(dir_.path());
  ASSERT_FALSE(directory.ok());
  EXPECT_TRUE(directory.status().IsIOError());
}

// A damaged block is found by Open's successors, not by Open: Open checks only the footer, the
// header and the index; the block's own checksum is checked when it is read, and the message
// names the block and its offset.
TEST_F(TrellisFileCorruptionTest, ReportsADamagedBlockWhenItIsRead) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes_.data());
  const uint64_t index_offset =
      trellis_file::LoadU64(data + bytes_.size() - trellis_file::kFooterBytes + 16);
  const trellis_file::BlockHandle block1 =
      trellis_file::BlockHandle::DecodeFrom(data + index_offset + trellis_file::kBlockEntryBytes);
  std::string damaged = bytes_;
  damaged[block1.offset + block1.bytes / 2] ^= 0x10;
  const std::string path = dir_.File("block.mtr");
  WriteBytes(path, damaged);
  auto reader = TrellisFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  TrellisBlock block;
  EXPECT_TRUE((*reader)->ReadBlock(0, &block).ok());
  const Status status = (*reader)->ReadBlock(1, &block);
  EXPECT_TRUE(status.IsCorruption());
  EXPECT_NE(status.message().find("block 1 at offset " + trellis_file::Hex(block1.offset)),
            std::string::npos)
      << status.ToString();
  EXPECT_NE(status.message().find("checksum mismatch"), std::string::npos);
  EXPECT_TRUE((*reader)->ReadBlock(2, &block).ok());
  EXPECT_TRUE((*reader)->Verify().IsCorruption());
  TrellisColumns columns;
  EXPECT_TRUE((*reader)->ReadColumns(0, 8, &columns).ok());
  EXPECT_TRUE((*reader)->ReadColumns(7, 2, &columns).IsCorruption());
}

// A crafted file: every checksum recomputed after the damage, so only the structural checks
// stand between it and the caller. The index entry of block 1 is moved, resized, renumbered.
TEST_F(TrellisFileCorruptionTest, RejectsACraftedIndexWithValidChecksums) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes_.data());
  const uint64_t footer_offset = bytes_.size() - trellis_file::kFooterBytes;
  const uint64_t index_offset = trellis_file::LoadU64(data + footer_offset + 16);
  for (int field = 0; field < 6; ++field) {
    std::string crafted = bytes_;
    const uint64_t entry = index_offset + trellis_file::kBlockEntryBytes;
    trellis_file::BlockHandle handle = trellis_file::BlockHandle::DecodeFrom(data + entry);
    if (field == 0) handle.offset += 1;
    if (field == 1) handle.bytes += 1;
    if (field == 2) handle.first_column += 1;
    if (field == 3) handle.column_count -= 1;
    if (field == 4) handle.neighbour_count += 1;
    if (field == 5) handle.bytes = UINT64_MAX - 100;
    std::string encoded;
    handle.EncodeTo(&encoded);
    crafted.replace(entry, encoded.size(), encoded);
    trellis_file::Footer footer;
    ASSERT_TRUE(trellis_file::Footer::DecodeFrom(data + footer_offset, &footer).ok());
    footer.index_checksum =
        trellis_file::Checksum64(crafted.data() + index_offset, footer_offset - index_offset);
    std::string footer_bytes;
    footer.EncodeTo(&footer_bytes);
    crafted.replace(footer_offset, footer_bytes.size(), footer_bytes);
    ExpectCorruption(crafted, "crafted index field " + std::to_string(field));
  }
}

}  // namespace
}  // namespace motif::testing
