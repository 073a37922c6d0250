// The paths file: round trips, the writer's rules, damage of every kind (every truncation,
// every flipped byte, appended bytes, another version) reported as Corruption naming the file,
// and atomic replacement when any file-system step fails.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "formats/paths_file/paths_file_format.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/paths_file/paths_file_writer.h"
#include "tests/testing/byte_files.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

PathsParams Params(uint64_t frame_count = 10000, uint64_t min_length = 60) {
  PathsParams params;
  params.trellis_identity = 0x1122334455667788ull;
  params.archive_identity = 0x0123456789abcdefull;
  params.frame_count = frame_count;
  params.branch = 5;
  params.min_length = min_length;
  params.all_branches = true;
  return params;
}

PathCandidate Make(uint64_t top_start, uint64_t top_end, uint64_t match_start, uint64_t match_end) {
  return {top_start, top_end, match_start, match_end, top_start, match_start};
}

// `count` valid candidates, sorted, as a grower would produce them (roots at their starts), plus
// a few with a root before the start (the format allows it).
std::vector<PathCandidate> RandomCandidates(const PathsParams& params, size_t count,
                                            uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<PathCandidate> candidates;
  const uint64_t n = params.frame_count;
  const uint64_t lambda = params.min_length;
  while (candidates.size() < count) {
    PathCandidate c;
    c.top_start = rng() % (n - lambda);
    c.top_end = c.top_start + lambda + rng() % (n - lambda - c.top_start + 1);
    c.match_start = rng() % (n - lambda);
    c.match_end =
        c.match_start + lambda + rng() % std::min<uint64_t>(400, n - lambda - c.match_start + 1);
    c.root_column = rng() % 8 == 0 ? c.top_start - std::min<uint64_t>(c.top_start, 3) : c.top_start;
    c.root_frame = rng() % 8 == 0 ? rng() % n : c.match_start;
    candidates.push_back(c);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const PathCandidate& a, const PathCandidate& b) {
              return std::tie(a.top_start, a.match_start, a.top_end, a.match_end, a.root_column,
                              a.root_frame) < std::tie(b.top_start, b.match_start, b.top_end,
                                                       b.match_end, b.root_column, b.root_frame);
            });
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  return candidates;
}

TEST(PathsFile, RoundTripsThroughAFile) {
  TempDir dir;
  const PathsParams params = Params();
  const auto candidates = RandomCandidates(params, 5000, 1);
  const std::string path = dir.File("a.mpa");
  ASSERT_TRUE(WritePathsFile(path, params, candidates).ok());
  auto reader = PathsFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->params(), params);
  EXPECT_EQ((*reader)->candidates(), candidates);
  EXPECT_EQ((*reader)->path(), path);
  EXPECT_EQ((*reader)->format_minor(), 0);
  EXPECT_EQ((*reader)->file_bytes(), std::filesystem::file_size(path));
  // Delta coding and zstd: well under the 48 bytes a candidate takes in memory.
  EXPECT_LT((*reader)->file_bytes(), candidates.size() * 12);
  // Deterministic bytes.
  EXPECT_EQ(ReadFileToString(path).value(), EncodePathsFile(params, candidates).value());
}

TEST(PathsFile, RoundTripsNoCandidatesAndExtremeValues) {
  const PathsParams params = Params(uint64_t{1} << 32, 1);
  for (const std::vector<PathCandidate>& candidates :
       {std::vector<PathCandidate>{},
        std::vector<PathCandidate>{
            Make(0, 1, (uint64_t{1} << 32) - 1, uint64_t{1} << 32),
            Make((uint64_t{1} << 32) - 1, uint64_t{1} << 32, 0, uint64_t{1} << 32)}}) {
    auto bytes = EncodePathsFile(params, candidates);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    auto reader = PathsFileReader::FromBytes(*bytes, "x.mpa");
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    EXPECT_EQ((*reader)->candidates(), candidates);
  }
}

TEST(PathsFile, WriterRejectsCandidatesThatBreakTheRulesAndWritesNothing) {
  TempDir dir;
  const PathsParams params = Params(1000, 60);
  const std::vector<std::vector<PathCandidate>> bad = {
      {Make(100, 200, 0, 100), Make(0, 100, 0, 100)},  // unsorted
      {Make(0, 100, 0, 100), Make(0, 100, 0, 100)},    // duplicate
      {Make(0, 59, 0, 100)},                           // top shorter than lambda
      {Make(0, 100, 0, 59)},                           // match shorter than lambda
      {Make(0, 1001, 0, 100)},                         // beyond the frames
      {Make(0, 100, 950, 1010)},
      {{10, 100, 0, 100, 11, 0}},     // root after the start
      {{10, 100, 0, 100, 10, 1000}},  // root frame outside
  };
  for (size_t idx = 0; idx < bad.size(); ++idx) {
    const std::string path = dir.File("bad" + std::to_string(idx) + ".mpa");
    const Status status = WritePathsFile(path, params, bad[idx]);
    EXPECT_TRUE(status.IsInvalidArgument()) << idx << ": " << status.ToString();
    EXPECT_FALSE(std::filesystem::exists(path)) << idx;
  }
  // One path per tree unless all_branches is set.
  PathsParams longest = params;
  longest.all_branches = false;
  EXPECT_TRUE(
      WritePathsFile(dir.File("t.mpa"), longest, {Make(0, 100, 0, 100), Make(0, 110, 0, 100)})
          .IsInvalidArgument());
  EXPECT_TRUE(
      WritePathsFile(dir.File("t.mpa"), longest, {Make(0, 100, 0, 100), Make(0, 110, 1, 100)})
          .ok());
  PathsParams zero_branch = params;
  zero_branch.branch = 0;
  EXPECT_TRUE(WritePathsFile(dir.File("b.mpa"), zero_branch, {}).IsInvalidArgument());
  PathsParams zero_lambda = params;
  zero_lambda.min_length = 0;
  EXPECT_TRUE(WritePathsFile(dir.File("b.mpa"), zero_lambda, {}).IsInvalidArgument());
  PathsParams huge = params;
  huge.frame_count = (uint64_t{1} << 32) + 1;
  EXPECT_TRUE(WritePathsFile(dir.File("b.mpa"), huge, {}).IsInvalidArgument());
}

class PathsFileCorruptionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    params_ = Params(500, 20);
    candidates_ = RandomCandidates(params_, 12, 7);
    bytes_ = EncodePathsFile(params_, candidates_).value();
  }

  void ExpectCorruption(const std::string& bytes, const std::string& context) {
    const std::string path = dir_.File("damaged.mpa");
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    auto reader = PathsFileReader::Open(path);
    ASSERT_FALSE(reader.ok()) << context << ": damage not detected";
    // A damaged major version reads as a future one (NotSupported, exit 15).
    EXPECT_TRUE(reader.status().IsCorruption() || reader.status().IsNotSupported())
        << context << ": " << reader.status().ToString();
    EXPECT_NE(reader.status().message().find(path), std::string::npos)
        << context << ": the message does not name the file: " << reader.status().ToString();
  }

  TempDir dir_;
  PathsParams params_;
  std::vector<PathCandidate> candidates_;
  std::string bytes_;
};

TEST_F(PathsFileCorruptionTest, TheUndamagedFileReadsBack) {
  auto reader = PathsFileReader::FromBytes(bytes_, "p.mpa");
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->candidates(), candidates_);
  EXPECT_LT(bytes_.size(), 300u);
}

TEST_F(PathsFileCorruptionTest, RejectsTruncationAtEveryLength) {
  for (size_t size = 0; size < bytes_.size(); ++size) {
    ExpectCorruption(bytes_.substr(0, size), "truncated to " + std::to_string(size));
  }
}

TEST_F(PathsFileCorruptionTest, RejectsEveryFlippedByte) {
  ForEachFlippedByte(bytes_, [&](const std::string& damaged, const std::string& what) {
    ExpectCorruption(damaged, what);
  });
}

TEST_F(PathsFileCorruptionTest, RejectsAppendedBytesAnotherVersionAndOtherFiles) {
  ExpectCorruption(bytes_ + std::string(1, '\0'), "one byte appended");
  ExpectCorruption(bytes_ + bytes_, "the file twice");
  std::string v2 = bytes_;
  v2[8] = 2;
  auto reader = PathsFileReader::FromBytes(v2, "v2.mpa");
  ASSERT_FALSE(reader.ok());
  EXPECT_NE(reader.status().message().find("major version 2"), std::string::npos)
      << reader.status().ToString();
  std::string trellis = bytes_;
  trellis.replace(0, 4, "\x89MTR");
  ExpectCorruption(trellis, "a trellis file's magic");
  // Records that decode but break the rules, under valid checksums: a record out of order.
  std::vector<PathCandidate> swapped = candidates_;
  std::swap(swapped[0], swapped[1]);
  std::string raw;
  paths_file::EncodeRecords(params_, swapped, &raw);
  std::vector<PathCandidate> decoded;
  const Status status = paths_file::DecodeRecords(reinterpret_cast<const uint8_t*>(raw.data()),
                                                  raw.size(), swapped.size(), params_, &decoded);
  EXPECT_TRUE(status.IsCorruption());
  EXPECT_NE(status.message().find("record 1"), std::string::npos) << status.ToString();
}

TEST_F(PathsFileCorruptionTest, ReportsMissingFilesAndDirectories) {
  auto missing = PathsFileReader::Open(dir_.File("missing.mpa"));
  EXPECT_TRUE(missing.status().IsNotFound());
  auto directory = PathsFileReader::Open(dir_.path());
  EXPECT_TRUE(directory.status().IsIOError());
}

// Replacing a paths file: whichever file-system step fails, the old file is still there and
// intact (or, once the rename happened, the new one is), and no temporary file is left behind.
TEST(PathsFileAtomicity, AFailureAtEveryStepLeavesTheOldOrTheNewFile) {
  const PathsParams params = Params(1000, 10);
  const auto old_candidates = RandomCandidates(params, 20, 1);
  const auto new_candidates = RandomCandidates(params, 30, 2);
  FaultInjectingFileSystem counting;
  {
    TempDir dir;
    PathsFileWriterOptions options;
    options.file_system = &counting;
    ASSERT_TRUE(WritePathsFile(dir.File("p.mpa"), params, new_candidates, options).ok());
  }
  const int64_t steps = counting.steps();
  EXPECT_EQ(steps, 5);  // open, write, fsync, rename, directory fsync
  for (int64_t step = 0; step < steps; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    TempDir dir;
    const std::string path = dir.File("p.mpa");
    ASSERT_TRUE(WritePathsFile(path, params, old_candidates).ok());
    FaultInjectingFileSystem faulty;
    faulty.FailAt(step);
    PathsFileWriterOptions options;
    options.file_system = &faulty;
    EXPECT_FALSE(WritePathsFile(path, params, new_candidates, options).ok());
    auto reader = PathsFileReader::Open(path);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    EXPECT_TRUE((*reader)->candidates() == old_candidates ||
                ((*reader)->candidates() == new_candidates && step >= 4));
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      (void)entry;
      ++files;
    }
    EXPECT_EQ(files, 1u);
  }
}

}  // namespace
}  // namespace motif::testing
