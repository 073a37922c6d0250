// TrellisFileReader on well-formed files: the params and counts come back, blocks and any column
// range decode to what was written (within the quantisation bound), from many threads at once.
#include "formats/trellis_file/trellis_file_reader.h"

#include <filesystem>
#include <thread>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_block_codec.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

TrellisFileWriterOptions Options(uint32_t block_columns) {
  TrellisFileWriterOptions options;
  options.block_columns = block_columns;
  options.file_system = NoSyncFileSystem();
  return options;
}

class TrellisFileReaderTest : public ::testing::Test {
 protected:
  void Write(const TrellisParams& params, const TrellisColumns& columns, uint32_t block_columns) {
    params_ = params;
    columns_ = columns;
    path_ = dir_.File("t.mtr");
    std::filesystem::remove(path_);
    const Status status = WriteTrellis(path_, params, columns, Options(block_columns));
    ASSERT_TRUE(status.ok()) << status.ToString();
  }

  TempDir dir_;
  std::string path_;
  TrellisParams params_;
  TrellisColumns columns_;
};

TEST_F(TrellisFileReaderTest, ReturnsTheParamsAndCounts) {
  TrellisParams params = MakeParams(1000, 300);
  params.eps = 1.02f;
  params.mu = 3.11f;
  params.sigma = 1.04f;
  const TrellisColumns columns = MakeRunColumns(1000, params.eps, 10, 300, 3);
  Write(params, columns, 64);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_TRUE((*reader)->params() == params);
  EXPECT_EQ((*reader)->params().search_params, params.search_params);
  EXPECT_EQ((*reader)->column_count(), 1000u);
  EXPECT_EQ((*reader)->block_columns(), 64u);
  EXPECT_EQ((*reader)->block_count(), 16u);  // 15 x 64 + 40
  uint64_t entries = 0;
  for (const auto& column : columns) entries += column.size();
  EXPECT_EQ((*reader)->neighbour_count(), entries);
  EXPECT_EQ((*reader)->file_bytes(), std::filesystem::file_size(path_));
  EXPECT_EQ((*reader)->format_minor(), 0);
  EXPECT_TRUE((*reader)->Verify().ok());
}

TEST_F(TrellisFileReaderTest, ReadsEveryBlockInOrder) {
  Write(MakeParams(700), MakeRunColumns(700, 1.0f, 0, 80, 4), 128);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  TrellisBlock block;
  TrellisColumns read;
  for (uint64_t block_idx = 0; block_idx < (*reader)->block_count(); ++block_idx) {
    ASSERT_TRUE((*reader)->ReadBlock(block_idx, &block).ok());
    EXPECT_EQ(block.first_column, block_idx * 128);
    EXPECT_EQ(block.column_count, block_idx + 1 < (*reader)->block_count() ? 128u : 700u - 5 * 128);
    ASSERT_EQ(block.offsets.size(), block.column_count + 1u);
    EXPECT_EQ(block.offsets.back(), block.neighbours.size());
    for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
      read.emplace_back(block.neighbours.begin() + block.offsets[column_idx],
                        block.neighbours.begin() + block.offsets[column_idx + 1]);
    }
  }
  ExpectSameWithinBound(columns_, read, 1.0f);
  EXPECT_TRUE((*reader)->ReadBlock((*reader)->block_count(), &block).IsInvalidArgument());
}

TEST_F(TrellisFileReaderTest, ReadsAnyColumnRange) {
  Write(MakeParams(300), MakeRunColumns(300, 1.0f, 0, 40, 8), 32);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  for (uint64_t first : {0, 1, 31, 32, 33, 100, 290, 299, 300}) {
    for (uint64_t count : {0, 1, 2, 31, 32, 33, 64, 200}) {
      if (first + count > 300) continue;
      TrellisColumns read;
      ASSERT_TRUE((*reader)->ReadColumns(first, count, &read).ok());
      ExpectSameWithinBound(Slice(columns_, first, count), read, 1.0f);
    }
  }
  TrellisColumns read;
  EXPECT_TRUE((*reader)->ReadColumns(299, 2, &read).IsInvalidArgument());
  EXPECT_TRUE((*reader)->ReadColumns(301, 0, &read).IsInvalidArgument());
  EXPECT_TRUE((*reader)->ReadColumns(1, UINT64_MAX, &read).IsInvalidArgument());
}

TEST_F(TrellisFileReaderTest, RoundTripsEmptyAndSingleNeighbourColumns) {
  TrellisColumns columns(100);
  for (uint32_t column_idx = 0; column_idx < 100; column_idx += 3) {
    columns[column_idx] = {{(column_idx * 37) % 100, 0.001f * column_idx}};
  }
  Write(MakeParams(100, 1), columns, 8);
  auto read = ReadTrellis(path_);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectSameWithinBound(columns, *read, 1.0f);
}

TEST_F(TrellisFileReaderTest, RoundTripsAnAllEmptyTrellis) {
  Write(MakeParams(50), TrellisColumns(50), 16);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ((*reader)->neighbour_count(), 0u);
  auto read = ReadTrellis(path_);
  ASSERT_TRUE(read.ok());
  ExpectSameWithinBound(TrellisColumns(50), *read, 1.0f);
}

TEST_F(TrellisFileReaderTest, RoundTripsColumnsOfAThousandNeighbours) {
  TrellisParams params = MakeParams(3000, 1000);
  params.eps = 1.3f;
  TrellisColumns columns = MakeRunColumns(3000, params.eps, 1000, 1000, 12);
  Write(params, columns, 512);
  auto read = ReadTrellis(path_);
  ASSERT_TRUE(read.ok());
  for (const auto& column : *read) ASSERT_EQ(column.size(), 1000u);
  ExpectSameWithinBound(columns, *read, params.eps);
}

TEST_F(TrellisFileReaderTest, ReturnsDistancesZeroAndEpsExactly) {
  TrellisParams params = MakeParams(10, 10);
  params.eps = 1.0412f;
  TrellisColumns columns(10);
  for (uint32_t column_idx = 0; column_idx < 10; ++column_idx) {
    columns[column_idx] = {{0, 0.0f}, {1, params.eps}, {5, 0.0f}, {6, params.eps}, {7, 0.0f}};
  }
  Write(params, columns, 4);
  auto read = ReadTrellis(path_);
  ASSERT_TRUE(read.ok());
  for (const auto& column : *read) {
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
      EXPECT_EQ(column[entry_idx], columns[0][entry_idx]);
    }
  }
}

TEST_F(TrellisFileReaderTest, ReadsFramesWithoutDistancesOnRequest) {
  Write(MakeParams(64), MakeRunColumns(64, 1.0f, 1, 30, 6), 64);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  TrellisBlock block;
  ASSERT_TRUE((*reader)->ReadBlock(0, &block, /*decode_distances=*/false).ok());
  size_t entry_idx = 0;
  for (const auto& column : columns_) {
    for (const Neighbour& neighbour : column) {
      EXPECT_EQ(block.neighbours[entry_idx].frame, neighbour.frame);
      EXPECT_EQ(block.neighbours[entry_idx].distance, 0.0f);
      ++entry_idx;
    }
  }
}

// A sequential consumer releases each block after reading it: the columns are the same, a
// released block reads back the same, and the mapping's resident pages go.
TEST_F(TrellisFileReaderTest, ReleasedBlocksReadTheSameAndLeaveTheResidentSet) {
  Write(MakeParams(20000, 200), MakeRunColumns(20000, 1.0f, 50, 200, 12), 256);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  const uint64_t block_count = (*reader)->block_count();
  ASSERT_GT((*reader)->file_bytes(), 1u << 20);  // enough pages to see them go
  TrellisBlock block;
  TrellisColumns read;
  for (uint64_t block_idx = 0; block_idx < block_count; ++block_idx) {
    ASSERT_TRUE((*reader)->ReadBlock(block_idx, &block).ok());
    for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
      read.emplace_back(block.neighbours.begin() + block.offsets[column_idx],
                        block.neighbours.begin() + block.offsets[column_idx + 1]);
    }
    ASSERT_TRUE((*reader)->ReleaseBlocks(block_idx, block_idx + 1).ok());
  }
  ExpectSameWithinBound(columns_, read, 1.0f);
  // Released pages come back from the file when read again.
  TrellisColumns again;
  ASSERT_TRUE((*reader)->ReadColumns(0, 20000, &again).ok());
  EXPECT_EQ(again, read);

  // Every block read (resident), then all released: what stays is the tail (index, footer and
  // the last block's partial page) the reader validated at Open.
  const int64_t resident_read = MappedResidentBytes(path_);
  if (resident_read < 0) GTEST_SKIP() << "no /proc/self/smaps";
  EXPECT_GT(resident_read, static_cast<int64_t>((*reader)->file_bytes() / 2));
  ASSERT_TRUE((*reader)->ReleaseBlocks(0, block_count).ok());
  const int64_t resident_released = MappedResidentBytes(path_);
  EXPECT_LT(resident_released, static_cast<int64_t>((*reader)->file_bytes() / 10))
      << "resident after reading " << resident_read;
  EXPECT_TRUE((*reader)->Verify().ok());

  EXPECT_TRUE((*reader)->ReleaseBlocks(0, 0).ok());
  EXPECT_TRUE((*reader)->ReleaseBlocks(block_count, block_count).ok());
  EXPECT_TRUE((*reader)->ReleaseBlocks(2, 1).IsInvalidArgument());
  EXPECT_TRUE((*reader)->ReleaseBlocks(0, block_count + 1).IsInvalidArgument());
}

TEST_F(TrellisFileReaderTest, ConstMethodsAreSafeFromManyThreads) {
  Write(MakeParams(2000), MakeRunColumns(2000, 1.0f, 5, 100, 10), 100);
  auto reader = TrellisFileReader::Open(path_);
  ASSERT_TRUE(reader.ok());
  const TrellisFileReader& shared = **reader;
  std::vector<Status> results(4);
  std::vector<std::thread> threads;
  for (size_t thread_idx = 0; thread_idx < results.size(); ++thread_idx) {
    threads.emplace_back([&, thread_idx] {
      for (int round = 0; round < 5 && results[thread_idx].ok(); ++round) {
        TrellisColumns read;
        const uint64_t first = (thread_idx * 397 + round * 211) % 1500;
        results[thread_idx] = shared.ReadColumns(first, 500, &read);
        if (results[thread_idx].ok() && !(read == Slice(*ReadTrellis(path_), first, 500))) {
          results[thread_idx] = Status::Corruption("different columns");
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (const Status& status : results) EXPECT_TRUE(status.ok()) << status.ToString();
}

}  // namespace
}  // namespace motif::testing
