// TrellisFileWriter: argument checks, and resuming an interrupted build from its partial file
// (complete blocks kept, a torn or damaged tail dropped, stale partial files replaced), always
// ending byte-identical to an uninterrupted build.
#include "formats/trellis_file/trellis_file_writer.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_file_format.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint32_t kBlockColumns = 16;
constexpr uint64_t kFrames = 10 * kBlockColumns - 5;  // 10 blocks, the last one shorter

// Durability is the crash test's subject; here fsync is skipped (NoSyncFileSystem) except where
// a test says otherwise.
TrellisFileWriterOptions Options(FileSystem* file_system = NoSyncFileSystem()) {
  TrellisFileWriterOptions options;
  options.block_columns = kBlockColumns;
  options.file_system = file_system;
  return options;
}

class TrellisFileWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    params_ = MakeParams(kFrames, 200);
    columns_ = MakeRunColumns(kFrames, params_.eps, 20, 120, 5);
    const std::string reference = dir_.File("reference.mtr");
    ASSERT_TRUE(WriteTrellis(reference, params_, columns_, Options()).ok());
    reference_ = ReadBytes(reference);
    path_ = dir_.File("t.mtr");
    partial_ = TrellisFileWriter::PartialPath(path_);
  }

  // Writes the first `blocks` blocks, then drops the writer without Finish.
  void BuildAndStop(uint64_t blocks, const TrellisParams& params,
                    const TrellisFileWriterOptions& options) {
    auto writer = TrellisFileWriter::OpenOrResume(path_, params, options);
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    for (uint64_t block_idx = 0; block_idx < blocks; ++block_idx) {
      const uint64_t first = (*writer)->next_column();
      const uint64_t count = std::min<uint64_t>(options.block_columns, params.frame_count - first);
      ASSERT_TRUE((*writer)->AppendBlock(Slice(columns_, first, count)).ok());
    }
  }
  void BuildAndStop(uint64_t blocks) { BuildAndStop(blocks, params_, Options()); }

  // Resumes, checks where, completes, and checks the result is the uninterrupted build.
  void ResumeAndExpectReference(uint64_t expected_next_column,
                                FileSystem* file_system = NoSyncFileSystem()) {
    auto writer = TrellisFileWriter::OpenOrResume(path_, params_, Options(file_system));
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    EXPECT_EQ((*writer)->next_column(), expected_next_column);
    while ((*writer)->next_column() < kFrames) {
      const uint64_t first = (*writer)->next_column();
      const uint64_t count = std::min<uint64_t>(kBlockColumns, kFrames - first);
      ASSERT_TRUE((*writer)->AppendBlock(Slice(columns_, first, count)).ok());
    }
    ASSERT_TRUE((*writer)->Finish().ok());
    EXPECT_FALSE(FileExists(partial_));
    EXPECT_TRUE(ReadBytes(path_) == reference_) << "resumed build differs from the reference";
  }

  // Offset of block `block_idx` in the reference (the partial file shares its prefix).
  // (The reference's block index, read by hand; for block 10 its index offset.)
  uint64_t BlockOffset(uint64_t block_idx) const {
    const auto* data = reinterpret_cast<const uint8_t*>(reference_.data());
    const uint64_t footer = reference_.size() - trellis_file::kFooterBytes;
    const uint64_t index_offset = trellis_file::LoadU64(data + footer + 16);
    if (block_idx == 10) return index_offset;
    return trellis_file::BlockHandle::DecodeFrom(data + index_offset +
                                                 block_idx * trellis_file::kBlockEntryBytes)
        .offset;
  }

  TempDir dir_;
  TrellisParams params_;
  TrellisColumns columns_;
  std::string reference_;
  std::string path_;
  std::string partial_;
};

// On the real file system, fsyncs included.
TEST_F(TrellisFileWriterTest, ResumesAfterTheLastCompleteBlockAndMatchesAnUninterruptedBuild) {
  BuildAndStop(4, params_, Options(PosixFileSystem()));
  EXPECT_TRUE(FileExists(partial_));
  EXPECT_FALSE(FileExists(path_));
  ResumeAndExpectReference(4 * kBlockColumns, PosixFileSystem());
}

TEST_F(TrellisFileWriterTest, ResumesAfterEveryNumberOfBlocks) {
  for (uint64_t blocks = 0; blocks <= 10; ++blocks) {
    SCOPED_TRACE("stopped after " + std::to_string(blocks) + " blocks");
    BuildAndStop(blocks);
    ResumeAndExpectReference(std::min<uint64_t>(blocks * kBlockColumns, kFrames));
    std::filesystem::remove(path_);
  }
}

TEST_F(TrellisFileWriterTest, ResumingTwiceInARowKeepsTheBlocks) {
  BuildAndStop(3);
  BuildAndStop(0);  // opened and dropped: nothing lost
  ResumeAndExpectReference(3 * kBlockColumns);
}

// Cut points: inside each field of the block header (40 bytes), through the sections, and
// into the trailer (the last 8 bytes).
TEST_F(TrellisFileWriterTest, DropsATornLastBlockCutAnywhere) {
  BuildAndStop(4);
  const std::string partial = ReadBytes(partial_);
  const uint64_t block3 = BlockOffset(3);
  const uint64_t block_bytes = partial.size() - block3;
  ASSERT_EQ(partial.size(), BlockOffset(4));
  std::vector<uint64_t> cuts = {0,  1,  3,  4,  7,  8,  15, 16, 19, 20,
                                23, 24, 27, 28, 31, 32, 39, 40, 41, 48};
  for (uint64_t eighth = 1; eighth < 8; ++eighth) cuts.push_back(block_bytes * eighth / 8);
  for (uint64_t from_end : {9, 8, 7, 1}) cuts.push_back(block_bytes - from_end);
  for (uint64_t cut : cuts) {
    SCOPED_TRACE("last block cut after " + std::to_string(cut) + " of " +
                 std::to_string(block_bytes) + " bytes");
    WriteBytes(partial_, partial.substr(0, block3 + cut));
    ResumeAndExpectReference(3 * kBlockColumns);
    std::filesystem::remove(path_);
  }
}

TEST_F(TrellisFileWriterTest, DropsALastBlockWithAFlippedByte) {
  BuildAndStop(4);
  const uint64_t block3 = BlockOffset(3);
  const std::string partial = ReadBytes(partial_);
  for (uint64_t offset : {block3, block3 + 5, block3 + 41, (block3 + partial.size()) / 2,
                          uint64_t{partial.size()} - 1}) {
    SCOPED_TRACE("byte " + std::to_string(offset) + " flipped");
    std::string damaged = partial;
    damaged[offset] = static_cast<char>(damaged[offset] ^ 0x01);
    WriteBytes(partial_, damaged);
    ResumeAndExpectReference(3 * kBlockColumns);
    std::filesystem::remove(path_);
  }
}

TEST_F(TrellisFileWriterTest, DropsEverythingAfterADamagedMiddleBlock) {
  BuildAndStop(6);
  PatchByte(partial_, BlockOffset(2) + 60, 'x');
  ResumeAndExpectReference(2 * kBlockColumns);
}

TEST_F(TrellisFileWriterTest, DropsGarbageAfterTheLastBlock) {
  BuildAndStop(5);
  WriteBytes(partial_, ReadBytes(partial_) + std::string(1000, '\x5a'));
  ResumeAndExpectReference(5 * kBlockColumns);
}

TEST_F(TrellisFileWriterTest, ResumesAnInterruptedFinish) {
  // All blocks, the index and the footer written, the rename not done: the partial file holds
  // a whole trellis. Resume drops the index and footer and writes them again.
  const std::string finished = reference_;
  WriteBytes(partial_, finished);
  ResumeAndExpectReference(kFrames);
}

TEST_F(TrellisFileWriterTest, DifferentParamsStartOver) {
  BuildAndStop(4);
  TrellisParams other = params_;
  other.seed += 1;
  auto writer = TrellisFileWriter::OpenOrResume(path_, other, Options());
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ((*writer)->next_column(), 0u);
  writer->reset();
  // And back again: the first start-over replaced the old blocks, so nothing is resumed.
  ResumeAndExpectReference(0);
}

TEST_F(TrellisFileWriterTest, EveryParamTakesPartInTheResumeDecision) {
  for (int field = 0; field < 11; ++field) {
    SCOPED_TRACE("field " + std::to_string(field));
    BuildAndStop(2);
    TrellisParams other = params_;
    switch (field) {
      case 0:
        other.frame_count += 1;
        break;
      case 1:
        other.archive_identity += 1;
        break;
      case 2:
        other.eps = std::nextafter(other.eps, 2.0f);
        break;
      case 3:
        other.mu += 0.5f;
        break;
      case 4:
        other.sigma += 0.5f;
        break;
      case 5:
        other.k_max += 1;
        break;
      case 6:
        other.exclusion_frames += 1;
        break;
      case 7:
        other.search_mode = 0;
        break;
      case 8:
        other.seed += 1;
        break;
      case 9:
        other.weights_hash += 1;
        break;
      case 10:
        other.search_params += " ";
        break;
    }
    EXPECT_FALSE(other == params_);
    auto writer = TrellisFileWriter::OpenOrResume(path_, other, Options());
    ASSERT_TRUE(writer.ok());
    EXPECT_EQ((*writer)->next_column(), 0u);
  }
}

TEST_F(TrellisFileWriterTest, DifferentBlockColumnsStartOver) {
  BuildAndStop(4);
  TrellisFileWriterOptions options = Options();
  options.block_columns = 32;
  auto writer = TrellisFileWriter::OpenOrResume(path_, params_, options);
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ((*writer)->next_column(), 0u);
  EXPECT_EQ((*writer)->block_columns(), 32u);
}

TEST_F(TrellisFileWriterTest, GarbagePartialFileStartsOver) {
  for (const std::string& garbage :
       {std::string(), std::string("x"), std::string(5000, '\x89'), reference_.substr(0, 30)}) {
    WriteBytes(partial_, garbage);
    ResumeAndExpectReference(0);
    std::filesystem::remove(path_);
  }
}

TEST_F(TrellisFileWriterTest, AFinishedFileDoesNotStopANewBuildAndIsReplacedAtFinish) {
  TrellisParams other = params_;
  other.seed = 7;
  ASSERT_TRUE(WriteTrellis(path_, other, columns_, Options()).ok());
  auto writer = TrellisFileWriter::OpenOrResume(path_, params_, Options());
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ((*writer)->next_column(), 0u);
  writer->reset();
  {
    // Until the new build finishes, the old file is still there and readable.
    auto reader = TrellisFileReader::Open(path_);
    ASSERT_TRUE(reader.ok());
    EXPECT_EQ((*reader)->params().seed, 7u);
  }
  ResumeAndExpectReference(0);
}

TEST_F(TrellisFileWriterTest, ASecondWriterOnTheSamePathIsRefused) {
  auto first = TrellisFileWriter::OpenOrResume(path_, params_, Options());
  ASSERT_TRUE(first.ok());
  auto second = TrellisFileWriter::OpenOrResume(path_, params_, Options());
  ASSERT_FALSE(second.ok());
  EXPECT_TRUE(second.status().IsBusy());
  EXPECT_NE(second.status().message().find("locked"), std::string::npos);
  first->reset();
  EXPECT_TRUE(TrellisFileWriter::OpenOrResume(path_, params_, Options()).ok());
}

TEST_F(TrellisFileWriterTest, WritesAnEmptyTrellis) {
  const TrellisParams params = MakeParams(0);
  ASSERT_TRUE(WriteTrellis(path_, params, {}, Options()).ok());
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->column_count(), 0u);
  EXPECT_EQ((*reader)->block_count(), 0u);
  EXPECT_TRUE((*reader)->Verify().ok());
}

TEST_F(TrellisFileWriterTest, RejectsInvalidParamsAndOptions) {
  const auto expect_invalid = [&](const TrellisParams& params,
                                  const TrellisFileWriterOptions& options) {
    auto writer = TrellisFileWriter::OpenOrResume(path_, params, options);
    ASSERT_FALSE(writer.ok());
    EXPECT_TRUE(writer.status().IsInvalidArgument()) << writer.status().ToString();
  };
  for (float eps : {0.0f, -1.0f, std::numeric_limits<float>::infinity(),
                    std::numeric_limits<float>::quiet_NaN()}) {
    TrellisParams params = params_;
    params.eps = eps;
    expect_invalid(params, Options());
  }
  TrellisParams params = params_;
  params.frame_count = (1ull << 32) + 1;
  expect_invalid(params, Options());
  params = params_;
  params.k_max = 0;
  expect_invalid(params, Options());
  params = params_;
  params.search_params.assign(70000, 'x');
  expect_invalid(params, Options());
  TrellisFileWriterOptions options = Options();
  options.block_columns = 0;
  expect_invalid(params_, options);
  options.block_columns = (1u << 20) + 1;
  expect_invalid(params_, options);
  options = Options();
  options.zstd_level = 1000;
  expect_invalid(params_, options);
  options = Options();
  options.file_system = nullptr;
  expect_invalid(params_, options);
  EXPECT_FALSE(FileExists(partial_));
}

TEST_F(TrellisFileWriterTest, RejectsInvalidBlocksAndStaysUsable) {
  auto writer = TrellisFileWriter::OpenOrResume(path_, params_, Options());
  ASSERT_TRUE(writer.ok());
  const TrellisColumns good = Slice(columns_, 0, kBlockColumns);
  const auto expect_invalid = [&](const TrellisColumns& columns, const std::string& what) {
    const Status status = (*writer)->AppendBlock(columns);
    EXPECT_TRUE(status.IsInvalidArgument()) << what << ": " << status.ToString();
  };
  expect_invalid(Slice(columns_, 0, kBlockColumns - 1), "too few columns");
  expect_invalid(Slice(columns_, 0, kBlockColumns + 1), "too many columns");
  TrellisColumns bad = good;
  bad[3] = {{5, 0.1f}, {4, 0.1f}};
  expect_invalid(bad, "unsorted");
  bad[3] = {{5, 0.1f}, {5, 0.2f}};
  expect_invalid(bad, "duplicate frame");
  bad[3] = {{static_cast<uint32_t>(kFrames), 0.1f}};
  expect_invalid(bad, "frame outside the archive");
  for (float distance :
       {-0.001f, std::nextafter(1.0f, 2.0f), std::numeric_limits<float>::quiet_NaN(),
        std::numeric_limits<float>::infinity()}) {
    bad[3] = {{5, distance}};
    expect_invalid(bad, "distance " + std::to_string(distance));
  }
  bad[3].clear();
  for (uint32_t frame = 0; frame < 201; ++frame) bad[3].push_back({frame, 0.5f});
  expect_invalid(bad, "more than k_max");
  EXPECT_TRUE((*writer)->Finish().IsInvalidArgument());
  EXPECT_EQ((*writer)->next_column(), 0u);
  // Still usable: the good blocks go through and the result is the reference.
  writer->reset();
  ResumeAndExpectReference(0);
}

TEST_F(TrellisFileWriterTest, IsClosedAfterFinish) {
  auto writer = TrellisFileWriter::OpenOrResume(path_, params_, Options());
  ASSERT_TRUE(writer.ok());
  while ((*writer)->next_column() < kFrames) {
    const uint64_t first = (*writer)->next_column();
    ASSERT_TRUE((*writer)
                    ->AppendBlock(
                        Slice(columns_, first, std::min<uint64_t>(kBlockColumns, kFrames - first)))
                    .ok());
  }
  EXPECT_TRUE((*writer)->AppendBlock({}).IsInvalidArgument());
  ASSERT_TRUE((*writer)->Finish().ok());
  EXPECT_TRUE((*writer)->Finish().IsInvalidArgument());
  EXPECT_EQ(ReadBytes(path_), reference_);
}

}  // namespace
}  // namespace motif::testing
