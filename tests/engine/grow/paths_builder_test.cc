// BuildPaths: the grow stage from an archive and its trellis to a paths file, its reuse of an
// up-to-date file and its refusal of a trellis built over another archive.
#include "engine/grow/paths_builder.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/engine/grow/grow_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

class PathsBuilderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    archive_ = dir_->File("s.mfs");
    trellis_ = dir_->File("s.mtr");
    ASSERT_TRUE(WriteSynthArchive(archive_, 4000, 5).ok());
    TrellisOptions options;
    options.exact = true;
    options.k_max = 64;
    auto built = BuildTrellis(archive_, trellis_, options);
    ASSERT_TRUE(built.ok()) << built.status().ToString();
  }
  static void TearDownTestSuite() { delete dir_; }

  static TempDir* dir_;
  static std::string archive_;
  static std::string trellis_;
};

TempDir* PathsBuilderTest::dir_ = nullptr;
std::string PathsBuilderTest::archive_;
std::string PathsBuilderTest::trellis_;

TEST_F(PathsBuilderTest, GrowsWritesAndThenReuses) {
  const std::string paths = dir_->File("grow1.mpa");
  PathsOptions options;
  std::vector<std::pair<uint64_t, uint64_t>> calls;
  options.progress = [&](uint64_t done, uint64_t total) { calls.push_back({done, total}); };
  auto report = BuildPaths(archive_, trellis_, paths, options);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  EXPECT_FALSE(report->reused);
  EXPECT_EQ(report->params.min_length, 60u);  // 0.5 s at 120 fps
  EXPECT_EQ(report->params.branch, 5u);
  EXPECT_EQ(report->params.frame_count, 4000u);
  EXPECT_GT(report->candidates, 0u);
  ASSERT_FALSE(calls.empty());
  EXPECT_EQ(calls.front(), std::make_pair(uint64_t{0}, uint64_t{4000}));
  EXPECT_EQ(calls.back(), std::make_pair(uint64_t{4000}, uint64_t{4000}));

  auto trellis = TrellisFileReader::Open(trellis_);
  ASSERT_TRUE(trellis.ok());
  auto reader = PathsFileReader::Open(paths);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ(reader.value()->params().trellis_identity, (*trellis)->identity());
  EXPECT_EQ(reader.value()->params(), report->params);
  EXPECT_EQ(reader.value()->candidates().size(), report->candidates);
  const auto bytes = std::filesystem::last_write_time(paths);

  calls.clear();
  auto again = BuildPaths(archive_, trellis_, paths, options);
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(again->reused);
  EXPECT_EQ(again->candidates, report->candidates);
  EXPECT_TRUE(calls.empty());
  EXPECT_EQ(std::filesystem::last_write_time(paths), bytes);

  // Another branch factor or lambda: grown again, and the file records the new parameters.
  options.branch = 3;
  options.min_length_frames = 40;
  auto changed = BuildPaths(archive_, trellis_, paths, options);
  ASSERT_TRUE(changed.ok());
  EXPECT_FALSE(changed->reused);
  EXPECT_EQ(changed->params.min_length, 40u);
  auto reread = PathsFileReader::Open(paths);
  ASSERT_TRUE(reread.ok());
  EXPECT_EQ(reread.value()->params().branch, 3u);
}

TEST_F(PathsBuilderTest, ADamagedPathsFileIsGrownAgain) {
  const std::string paths = dir_->File("grow2.mpa");
  auto first = BuildPaths(archive_, trellis_, paths, {});
  ASSERT_TRUE(first.ok());
  {
    std::fstream file(paths, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(100);
    file.put('\x7f');
  }
  EXPECT_FALSE(PathsFileReader::Open(paths).ok());
  auto second = BuildPaths(archive_, trellis_, paths, {});
  ASSERT_TRUE(second.ok());
  EXPECT_FALSE(second->reused);
  EXPECT_EQ(second->candidates, first->candidates);
  EXPECT_TRUE(PathsFileReader::Open(paths).ok());
}

TEST_F(PathsBuilderTest, RefusesATrellisOfAnotherArchive) {
  const std::string other = dir_->File("other.mfs");
  ASSERT_TRUE(WriteSynthArchive(other, 4000, 6).ok());
  auto report = BuildPaths(other, trellis_, dir_->File("o.mpa"), {});
  ASSERT_FALSE(report.ok());
  EXPECT_TRUE(report.status().IsInvalidArgument()) << report.status().ToString();
  EXPECT_NE(report.status().message().find("s.mtr"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir_->File("o.mpa")));
  auto missing = BuildPaths(archive_, dir_->File("none.mtr"), dir_->File("o.mpa"), {});
  EXPECT_TRUE(missing.status().IsNotFound());
  PathsOptions zero;
  zero.branch = 0;
  EXPECT_TRUE(
      BuildPaths(archive_, trellis_, dir_->File("o.mpa"), zero).status().IsInvalidArgument());
}

// Appends a copy of the archive's first clip, as another import would.
void AppendCopyOfFirstClip(const std::string& archive) {
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  ClipFrames copy;
  copy.info = (*reader)->clips().front();
  copy.info.name += "_copy";
  ASSERT_TRUE((*reader)->ReadFrames(0, copy.info.frame_count, &copy.rows).ok());
  auto writer = FrameFileWriter::OpenForAppend(archive);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  ASSERT_TRUE((*writer)->AppendClip(copy).ok());
  ASSERT_TRUE((*writer)->Commit().ok());
}

// A take appended between the trellis and the grower (an import while `mine` runs): the stages
// given the version opened first finish on it; without it the grower refuses the trellis.
TEST(PathsBuilder, StagesPinnedToAVersionIgnoreALaterAppend) {
  TempDir dir;
  const std::string archive = dir.File("a.mfs");
  ASSERT_TRUE(WriteSynthArchive(archive, 4000, 7).ok());
  auto opened = FrameFileReader::Open(archive);
  ASSERT_TRUE(opened.ok());
  const FrameFileVersion pinned = (*opened)->version();
  EXPECT_EQ(pinned.generation, 1u);
  EXPECT_EQ(pinned.committed_bytes, std::filesystem::file_size(archive));

  TrellisOptions trellis_options;
  trellis_options.exact = true;
  trellis_options.k_max = 32;
  trellis_options.archive_version = pinned;
  ASSERT_TRUE(BuildTrellis(archive, dir.File("a.mtr"), trellis_options).ok());
  ASSERT_NO_FATAL_FAILURE(AppendCopyOfFirstClip(archive));
  ASSERT_EQ(FrameFileReader::Open(archive).value()->summary().generation, 2u);

  EXPECT_TRUE(BuildPaths(archive, dir.File("a.mtr"), dir.File("newest.mpa"), {})
                  .status()
                  .IsInvalidArgument());
  PathsOptions paths_options;
  paths_options.archive_version = pinned;
  auto paths = BuildPaths(archive, dir.File("a.mtr"), dir.File("a.mpa"), paths_options);
  ASSERT_TRUE(paths.ok()) << paths.status().ToString();
  EXPECT_EQ(paths->params.frame_count, 4000u);
  EXPECT_EQ(paths->params.archive_identity, (*opened)->summary().identity);
}

TEST(PathsBuilder, DefaultPathAndLambdaInFrames) {
  EXPECT_EQ(DefaultPathsPath("data/take.mfs"), "data/take.mpa");
  EXPECT_EQ(DefaultPathsPath("data/take"), "data/take.mpa");
  EXPECT_EQ(MinLengthFrames(0.5, 120), 60u);
  EXPECT_EQ(MinLengthFrames(0.5, 30), 15u);
  EXPECT_EQ(MinLengthFrames(0.001, 30), 1u);
}

}  // namespace
}  // namespace motif::testing
