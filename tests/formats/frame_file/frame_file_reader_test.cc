#include "formats/frame_file/frame_file_reader.h"

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "common/peak_memory.h"
#include "tests/formats/frame_file/frame_file_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint32_t kReaderJoints = 4;

// An archive of several clips in blocks of 50 frames, plus one appended generation.
std::string MakeArchive(const TempDir& dir) {
  const std::string path = dir.File("a.mfs");
  FrameFileWriterOptions options;
  options.block_frames = 50;
  std::vector<ClipFrames> clips;
  for (int clip_idx = 0; clip_idx < 4; ++clip_idx) {
    clips.push_back(MakeClip(Numbered("c", clip_idx), kReaderJoints, 61 + 17 * clip_idx, clip_idx));
  }
  WriteArchive(path, MakeSkeleton(kReaderJoints), clips, options);
  AppendToArchive(path, {MakeClip("appended", kReaderJoints, 77, 99)}, options);
  return path;
}

TEST(FrameFileReader, AnArchiveCutUnderTheReaderIsDamageNamingItNotASigbus) {
  TempDir dir;
  const std::string path = dir.File("big.mfs");
  FrameFileWriterOptions options;
  options.block_frames = 256;
  WriteArchive(path, MakeSkeleton(20), {MakeClip("long", 20, 4000, 5)}, options);
  for (const int kind : {0, 1, 2}) {
    auto reader = FrameFileReader::Open(path);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    const std::string whole = ReadFileToString(path).value();
    ASSERT_EQ(::truncate(path.c_str(), 200), 0);
    Status status;
    std::vector<float> rows;
    if (kind == 0) status = (*reader)->ReadFrames(0, (*reader)->frame_count(), &rows);
    if (kind == 1) status = (*reader)->Verify();
    if (kind == 2) {
      auto stream = (*reader)->Stream(0, (*reader)->frame_count());
      Result<bool> next = true;
      while (next.ok() && *next) next = stream->Next();
      if (!next.ok()) status = next.status();
    }
    EXPECT_TRUE(status.IsCorruption()) << kind << ": " << status.ToString();
    EXPECT_NE(status.message().find(path + ": the file was cut while it was being read"),
              std::string::npos)
        << status.message();
    reader->reset();
    ASSERT_TRUE(AtomicWriteFile(path, whole).ok());
  }
}

TEST(FrameFileReader, StreamEqualsRandomAccess) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  std::vector<float> all;
  ASSERT_TRUE((*reader)->ReadFrames(0, (*reader)->frame_count(), &all).ok());
  const size_t stride = (*reader)->layout().stride();

  auto stream = (*reader)->Stream();
  std::vector<float> streamed;
  uint64_t expected_first = 0;
  int runs = 0;
  while (true) {
    Result<bool> next = stream->Next();
    ASSERT_TRUE(next.ok()) << next.status().ToString();
    if (!*next) break;
    EXPECT_EQ(stream->first_frame(), expected_first);
    EXPECT_GT(stream->frame_count(), 0u);
    EXPECT_LE(stream->frame_count(), 50u);
    streamed.insert(streamed.end(), stream->rows(),
                    stream->rows() + stream->frame_count() * stride);
    expected_first += stream->frame_count();
    ++runs;
  }
  EXPECT_EQ(expected_first, (*reader)->frame_count());
  EXPECT_EQ(static_cast<uint64_t>(runs), (*reader)->summary().block_count);
  EXPECT_TRUE(SameBits(all, streamed));
  Result<bool> after_end = stream->Next();
  ASSERT_TRUE(after_end.ok());
  EXPECT_FALSE(*after_end);
}

TEST(FrameFileReader, StreamOverASubrangeStartsAndEndsMidBlock) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  const size_t stride = (*reader)->layout().stride();
  std::vector<float> expected;
  ASSERT_TRUE((*reader)->ReadFrames(73, 160 - 73, &expected).ok());
  auto stream = (*reader)->Stream(73, 160);
  std::vector<float> streamed;
  std::vector<uint64_t> firsts;
  while (true) {
    Result<bool> next = stream->Next();
    ASSERT_TRUE(next.ok());
    if (!*next) break;
    firsts.push_back(stream->first_frame());
    streamed.insert(streamed.end(), stream->rows(),
                    stream->rows() + stream->frame_count() * stride);
  }
  EXPECT_EQ(firsts, (std::vector<uint64_t>{73, 100, 150}));
  EXPECT_TRUE(SameBits(expected, streamed));

  auto empty = (*reader)->Stream((*reader)->frame_count() + 5);
  Result<bool> next = empty->Next();
  ASSERT_TRUE(next.ok());
  EXPECT_FALSE(*next);
}

TEST(FrameFileReader, ReadFramesOfAnyRangeMatchesTheWholeRead) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  const uint64_t total = (*reader)->frame_count();
  const size_t stride = (*reader)->layout().stride();
  std::vector<float> all;
  ASSERT_TRUE((*reader)->ReadFrames(0, total, &all).ok());
  std::mt19937 random(3);
  std::vector<float> rows;
  for (int trial = 0; trial < 200; ++trial) {
    const uint64_t first = random() % total;
    const uint64_t count = random() % (total - first + 1);
    ASSERT_TRUE((*reader)->ReadFrames(first, count, &rows).ok());
    ASSERT_EQ(rows.size(), count * stride);
    const std::vector<float> expected(all.begin() + first * stride,
                                      all.begin() + (first + count) * stride);
    ASSERT_TRUE(SameBits(expected, rows)) << first << " +" << count;
  }
}

TEST(FrameFileReader, ReadFramesRejectsRangesOutsideTheArchive) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  const uint64_t total = (*reader)->frame_count();
  std::vector<float> rows;
  EXPECT_TRUE((*reader)->ReadFrames(total, 0, &rows).ok());
  EXPECT_TRUE(rows.empty());
  EXPECT_TRUE((*reader)->ReadFrames(total - 1, 2, &rows).IsInvalidArgument());
  EXPECT_TRUE((*reader)->ReadFrames(total + 1, 0, &rows).IsInvalidArgument());
  EXPECT_TRUE((*reader)->ReadFrames(5, UINT64_MAX, &rows).IsInvalidArgument());
}

TEST(FrameFileReader, ClipOfFrameFindsTheClip) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  const std::vector<ClipInfo>& clips = (*reader)->clips();
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    EXPECT_EQ((*reader)->ClipOfFrame(clips[clip_idx].first_frame), clip_idx);
    EXPECT_EQ((*reader)->ClipOfFrame(clips[clip_idx].first_frame + clips[clip_idx].frame_count - 1),
              clip_idx);
  }
}

TEST(FrameFileReader, SummaryDescribesTheArchive) {
  TempDir dir;
  const std::string path = MakeArchive(dir);
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  const FrameFileSummary summary = (*reader)->summary();
  EXPECT_EQ(summary.file_bytes, ReadBytes(path).size());
  EXPECT_EQ(summary.generation, 2u);
  EXPECT_EQ(summary.format_major, 1u);
  EXPECT_EQ(summary.format_minor, 0u);
  EXPECT_EQ(summary.block_frames, 50u);
  EXPECT_EQ(summary.block_count, 9u);  // 346 frames -> 7 blocks, then 77 appended -> 2
  EXPECT_GT(summary.compressed_bytes, 0u);
  EXPECT_LT(summary.compressed_bytes, summary.file_bytes);
  EXPECT_EQ(summary.uncommitted_bytes, 0u);
  EXPECT_TRUE(summary.fallback_reason.empty());
  EXPECT_EQ((*reader)->path(), path);
}

TEST(FrameFileReader, VerifyReportsProgressForEveryBlock) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  std::vector<std::pair<uint64_t, uint64_t>> calls;
  ASSERT_TRUE((*reader)
                  ->Verify([&](uint64_t done, uint64_t total) { calls.emplace_back(done, total); })
                  .ok());
  const uint64_t blocks = (*reader)->summary().block_count;
  ASSERT_EQ(calls.size(), blocks);
  EXPECT_EQ(calls.back(), std::make_pair(blocks, blocks));
}

TEST(FrameFileReader, ConcurrentReadsAgree) {
  TempDir dir;
  auto reader = FrameFileReader::Open(MakeArchive(dir));
  ASSERT_TRUE(reader.ok());
  const FrameFileReader& shared = **reader;
  std::vector<float> all;
  ASSERT_TRUE(shared.ReadFrames(0, shared.frame_count(), &all).ok());
  const size_t stride = shared.layout().stride();
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int thread_idx = 0; thread_idx < 4; ++thread_idx) {
    threads.emplace_back([&, thread_idx] {
      std::mt19937 random(thread_idx);
      std::vector<float> rows;
      for (int trial = 0; trial < 100; ++trial) {
        const uint64_t first = random() % shared.frame_count();
        const uint64_t count = std::min<uint64_t>(random() % 120, shared.frame_count() - first);
        if (!shared.ReadFrames(first, count, &rows).ok() ||
            std::memcmp(rows.data(), all.data() + first * stride, count * stride * 4) != 0) {
          ++mismatches[thread_idx];
        }
        if (trial % 25 == 0 && !shared.Verify().ok()) ++mismatches[thread_idx];
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(mismatches, std::vector<int>(4, 0));
}

TEST(FrameFileReader, OpenReportsAMissingFileAsNotFound) {
  TempDir dir;
  auto reader = FrameFileReader::Open(dir.File("none.mfs"));
  ASSERT_FALSE(reader.ok());
  EXPECT_TRUE(reader.status().IsNotFound());
  EXPECT_NE(reader.status().message().find("none.mfs"), std::string::npos);
}

#if defined(__linux__)
// Resident file-backed pages of this process (RssFile in /proc/self/status), in bytes.
uint64_t ResidentFileBytes() { return ProcessStatusBytes("RssFile:"); }

TEST(FrameFileReader, StreamGivesBackThePagesOfConsumedBlocks) {
  TempDir dir;
  const std::string path = dir.File("big.mfs");
  // ~16 MB of barely compressible frames (lossless noise), 4096-frame blocks.
  FrameFileWriterOptions options;
  options.lossless = true;
  options.zstd_level = 1;
  ClipFrames clip = MakeClip("noise", 1, 500000, 5);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (float& value : clip.rows) value = uniform(random);
  WriteArchive(path, MakeSkeleton(1), {clip}, options);
  const uint64_t file_bytes = ReadBytes(path).size();
  ASSERT_GT(file_bytes, 8u << 20);

  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  const uint64_t resident_before = ResidentFileBytes();
  auto stream = (*reader)->Stream();
  uint64_t frames = 0;
  uint64_t peak = 0;
  while (true) {
    Result<bool> next = stream->Next();
    ASSERT_TRUE(next.ok());
    if (!*next) break;
    frames += stream->frame_count();
    peak = std::max(peak, ResidentFileBytes());
  }
  EXPECT_EQ(frames, 500000u);
  // Without the release, the whole mapping would become resident.
  EXPECT_LT(peak - std::min(peak, resident_before), file_bytes / 4)
      << "resident before " << resident_before << ", peak " << peak;
}
#endif

}  // namespace
}  // namespace motif::testing
