#include "formats/frame_file/frame_file_writer.h"

#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "formats/frame_file/frame_file_reader.h"
#include "tests/formats/frame_file/frame_file_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint32_t kWriterJoints = 5;

FrameFileWriterOptions SmallBlocks(uint32_t block_frames = 64) {
  FrameFileWriterOptions options;
  options.block_frames = block_frames;
  return options;
}

std::vector<ClipFrames> SomeClips(int count, uint64_t frames, uint32_t seed = 1,
                                  const std::string& prefix = "clip") {
  std::vector<ClipFrames> clips;
  for (int clip_idx = 0; clip_idx < count; ++clip_idx) {
    clips.push_back(MakeClip(prefix + std::to_string(clip_idx), kWriterJoints,
                             frames + 13 * clip_idx, seed + clip_idx));
  }
  return clips;
}

std::vector<float> Concatenate(const std::vector<ClipFrames>& clips) {
  std::vector<float> rows;
  for (const ClipFrames& clip : clips) rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
  return rows;
}

TEST(FrameFileWriter, RoundTripIsWithinTheQuantisationBound) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  const std::vector<ClipFrames> clips = SomeClips(3, 150);
  WriteArchive(path, MakeSkeleton(kWriterJoints), clips, SmallBlocks());
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok()) << contents.status().ToString();
  ExpectWithinQuantisationBound(Concatenate(clips), contents->rows, kWriterJoints);
}

TEST(FrameFileWriter, LosslessRoundTripIsBitExact) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  FrameFileWriterOptions options = SmallBlocks();
  options.lossless = true;
  const std::vector<ClipFrames> clips = SomeClips(2, 100);
  WriteArchive(path, MakeSkeleton(kWriterJoints), clips, options);
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  EXPECT_TRUE(SameBits(Concatenate(clips), contents->rows));
}

TEST(FrameFileWriter, ReReadingGivesBitIdenticalRows) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  WriteArchive(path, MakeSkeleton(kWriterJoints), SomeClips(2, 200), SmallBlocks());
  auto first = ReadContents(path);
  auto second = ReadContents(path);
  ASSERT_TRUE(first.ok() && second.ok());
  ExpectSameContents(*first, *second);
}

TEST(FrameFileWriter, KeepsEveryClipAndSkeletonField) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  const Skeleton skeleton = MakeSkeleton(kWriterJoints);
  std::vector<ClipFrames> clips = SomeClips(3, 40);
  WriteArchive(path, skeleton, clips, SmallBlocks(32));
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  ExpectSameSkeleton(skeleton, (*reader)->skeleton());
  EXPECT_EQ((*reader)->fps(), 120.0);
  EXPECT_EQ((*reader)->layout().joint_count, kWriterJoints);
  ASSERT_EQ((*reader)->clips().size(), clips.size());
  uint64_t first_frame = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    clips[clip_idx].info.first_frame = first_frame;  // assigned by the writer
    first_frame += clips[clip_idx].info.frame_count;
    ExpectSameClipInfo(clips[clip_idx].info, (*reader)->clips()[clip_idx]);
  }
  EXPECT_EQ((*reader)->frame_count(), first_frame);
}

// The optional source fields of a clip record: a clip with any of them keeps all three; a clip
// with none writes the record of 1.0 (its record is as long as before the fields existed).
TEST(FrameFileWriter, KeepsTheSourceFieldsOfTheClipsThatHaveThem) {
  TempDir dir;
  const Skeleton skeleton = MakeSkeleton(kWriterJoints);
  std::vector<ClipFrames> clips = SomeClips(4, 40);
  clips[0].info.source_first_frame = 1;
  clips[1].info.source_joint_names = {"Hips", "LeftUpLeg", "LeftLeg", "RightUpLeg", "RightLeg"};
  clips[2].info.description = "walk, then a turn \u00e0 gauche";
  const std::string with = dir.File("with.mfs");
  WriteArchive(with, skeleton, clips, SmallBlocks(32));
  auto reader = FrameFileReader::Open(with);
  ASSERT_TRUE(reader.ok());
  uint64_t first_frame = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    clips[clip_idx].info.first_frame = first_frame;
    first_frame += clips[clip_idx].info.frame_count;
    ExpectSameClipInfo(clips[clip_idx].info, (*reader)->clips()[clip_idx]);
  }
  // Without them, each record is as 1.0 wrote it: the file is shorter by exactly the three
  // clips' fields (u64, name count u32, description length u32; the 5 names; the text).
  for (ClipFrames& clip : clips) {
    clip.info.source_first_frame = 0;
    clip.info.source_joint_names.clear();
    clip.info.description.clear();
  }
  const std::string without = dir.File("without.mfs");
  WriteArchive(without, skeleton, clips, SmallBlocks(32));
  const uint64_t names = 5 * 4 + 4 + 9 + 7 + 10 + 8;  // lengths and "Hips".."RightLeg"
  const uint64_t description = std::string("walk, then a turn \u00e0 gauche").size();
  EXPECT_EQ(std::filesystem::file_size(with) - std::filesystem::file_size(without),
            3 * 16 + names + description);
}

TEST(FrameFileWriter, BlocksSpanClipBoundaries) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  std::vector<ClipFrames> clips;
  for (int clip_idx = 0; clip_idx < 7; ++clip_idx) {
    clips.push_back(MakeClip(Numbered("c", clip_idx), kWriterJoints, 37, clip_idx));
  }
  WriteArchive(path, MakeSkeleton(kWriterJoints), clips, SmallBlocks(100));
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  const FrameFileSummary summary = (*reader)->summary();
  EXPECT_EQ(summary.block_count, 3u);  // 259 frames: 100 + 100 + 59
  EXPECT_EQ(summary.block_frames, 100u);
  EXPECT_EQ(summary.generation, 1u);
  EXPECT_EQ(summary.format_major, 1u);
  EXPECT_EQ(summary.file_bytes, std::filesystem::file_size(path));
  EXPECT_EQ((*reader)->ClipOfFrame(0), 0u);
  EXPECT_EQ((*reader)->ClipOfFrame(36), 0u);
  EXPECT_EQ((*reader)->ClipOfFrame(37), 1u);
  EXPECT_EQ((*reader)->ClipOfFrame(258), 6u);
  std::vector<float> rows;
  ASSERT_TRUE((*reader)->ReadFrames(0, 259, &rows).ok());
  ExpectWithinQuantisationBound(Concatenate(clips), rows, kWriterJoints);
}

TEST(FrameFileWriter, StreamingClipCallsWriteTheSameFileAsAppendClip) {
  TempDir dir;
  const std::vector<ClipFrames> clips = SomeClips(2, 170);
  WriteArchive(dir.File("whole.mfs"), MakeSkeleton(kWriterJoints), clips, SmallBlocks(50));

  auto writer = FrameFileWriter::Create(dir.File("streamed.mfs"), MakeSkeleton(kWriterJoints),
                                        120.0, SmallBlocks(50));
  ASSERT_TRUE(writer.ok());
  const size_t stride = FrameLayout{kWriterJoints}.stride();
  for (const ClipFrames& clip : clips) {
    ClipInfo info = clip.info;
    info.frame_count = 12345;  // ignored
    ASSERT_TRUE((*writer)->BeginClip(info).ok());
    for (uint64_t frame_idx = 0; frame_idx < clip.info.frame_count; frame_idx += 23) {
      const size_t count = std::min<uint64_t>(23, clip.info.frame_count - frame_idx);
      ASSERT_TRUE((*writer)->AppendFrames(&clip.rows[frame_idx * stride], count).ok());
    }
    ASSERT_TRUE((*writer)->EndClip().ok());
  }
  EXPECT_EQ((*writer)->frame_count(), 170u + 183u);
  ASSERT_TRUE((*writer)->Commit().ok());
  EXPECT_EQ(ReadBytes(dir.File("whole.mfs")), ReadBytes(dir.File("streamed.mfs")));
}

TEST(FrameFileWriter, SameInputWritesIdenticalBytes) {
  TempDir dir;
  const std::vector<ClipFrames> clips = SomeClips(3, 120);
  WriteArchive(dir.File("a.mfs"), MakeSkeleton(kWriterJoints), clips, SmallBlocks());
  WriteArchive(dir.File("b.mfs"), MakeSkeleton(kWriterJoints), clips, SmallBlocks());
  AppendToArchive(dir.File("a.mfs"), SomeClips(1, 77, 50, "more"), SmallBlocks());
  AppendToArchive(dir.File("b.mfs"), SomeClips(1, 77, 50, "more"), SmallBlocks());
  const std::string a = ReadBytes(dir.File("a.mfs"));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, ReadBytes(dir.File("b.mfs")));
}

TEST(FrameFileWriter, AppendRoundTripKeepsExistingBlocks) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  const std::vector<ClipFrames> first = SomeClips(2, 90);
  WriteArchive(path, MakeSkeleton(kWriterJoints), first, SmallBlocks());
  const std::string before = ReadBytes(path);
  auto before_contents = ReadContents(path);
  ASSERT_TRUE(before_contents.ok());

  const std::vector<ClipFrames> second = SomeClips(2, 70, 100, "new");
  AppendToArchive(path, second, SmallBlocks(48));
  const std::string after = ReadBytes(path);
  // Existing bytes are untouched except the commit slot the append took over.
  ASSERT_GT(after.size(), before.size());
  EXPECT_EQ(after.substr(0, 88), before.substr(0, 88));
  EXPECT_EQ(after.substr(128, before.size() - 128), before.substr(128));

  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ASSERT_EQ(contents->clips.size(), 4u);
  EXPECT_EQ(contents->clips[2].name, "new0");
  EXPECT_EQ(contents->clips[2].first_frame, 90u + 103u);
  // The old frames decode exactly as before; the new ones within the bound.
  std::vector<float> old_rows(contents->rows.begin(),
                              contents->rows.begin() + before_contents->rows.size());
  EXPECT_TRUE(SameBits(before_contents->rows, old_rows));
  std::vector<float> new_rows(contents->rows.begin() + before_contents->rows.size(),
                              contents->rows.end());
  ExpectWithinQuantisationBound(Concatenate(second), new_rows, kWriterJoints);
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ((*reader)->summary().generation, 2u);
  EXPECT_TRUE((*reader)->Verify().ok());
}

TEST(FrameFileWriter, ManyAppendsAccumulate) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  std::vector<ClipFrames> all = SomeClips(1, 60, 1, "c0_");
  WriteArchive(path, MakeSkeleton(kWriterJoints), all, SmallBlocks(40));
  for (int append_idx = 1; append_idx <= 6; ++append_idx) {
    std::vector<ClipFrames> more = SomeClips(append_idx % 3 + 1, 20 + append_idx, 10 * append_idx,
                                             Numbered("c", append_idx) + "_");
    AppendToArchive(path, more, SmallBlocks(40));
    all.insert(all.end(), more.begin(), more.end());
    auto reader = FrameFileReader::Open(path);
    ASSERT_TRUE(reader.ok());
    EXPECT_EQ((*reader)->summary().generation, static_cast<uint64_t>(append_idx + 1));
    EXPECT_TRUE((*reader)->Verify().ok());
  }
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ASSERT_EQ(contents->clips.size(), all.size());
  for (size_t clip_idx = 0; clip_idx < all.size(); ++clip_idx) {
    EXPECT_EQ(contents->clips[clip_idx].name, all[clip_idx].info.name);
  }
  ExpectWithinQuantisationBound(Concatenate(all), contents->rows, kWriterJoints);
}

TEST(FrameFileWriter, AppendKeepsTheArchiveColumnEncodings) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  FrameFileWriterOptions lossless = SmallBlocks();
  lossless.lossless = true;
  const std::vector<ClipFrames> first = SomeClips(1, 50);
  WriteArchive(path, MakeSkeleton(kWriterJoints), first, lossless);
  const std::vector<ClipFrames> second = SomeClips(1, 50, 9, "more");
  AppendToArchive(path, second, SmallBlocks());  // default options: lossy, but ignored
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  std::vector<float> expected = Concatenate(first);
  const std::vector<float> more = Concatenate(second);
  expected.insert(expected.end(), more.begin(), more.end());
  EXPECT_TRUE(SameBits(expected, contents->rows));
}

TEST(FrameFileWriter, RejectsClipNamesAlreadyInTheArchive) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  auto writer = FrameFileWriter::Create(path, MakeSkeleton(kWriterJoints), 120.0);
  ASSERT_TRUE(writer.ok());
  const ClipFrames clip = MakeClip("walk", kWriterJoints, 30, 1);
  ASSERT_TRUE((*writer)->AppendClip(clip).ok());
  Status duplicate = (*writer)->AppendClip(clip);
  EXPECT_TRUE(duplicate.IsInvalidArgument());
  EXPECT_NE(duplicate.message().find("walk"), std::string::npos);
  EXPECT_TRUE((*writer)->BeginClip(clip.info).IsInvalidArgument());
  ASSERT_TRUE((*writer)->Commit().ok());

  auto appender = FrameFileWriter::OpenForAppend(path);
  ASSERT_TRUE(appender.ok());
  EXPECT_TRUE((*appender)->AppendClip(MakeClip("walk", kWriterJoints, 10, 2)).IsInvalidArgument());
  EXPECT_TRUE((*appender)->AppendClip(MakeClip("run", kWriterJoints, 10, 2)).ok());
  ASSERT_TRUE((*appender)->Commit().ok());
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  EXPECT_EQ(contents->clips.size(), 2u);
}

// Two writers creating one archive (two imports starting it at once): the one that finishes
// second is busy (exit 17: retried, it appends), and the first one's archive stays.
TEST(FrameFileWriter, CreatingAnArchiveAnotherWriterCreatedMeanwhileIsBusy) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  auto late = FrameFileWriter::Create(path, MakeSkeleton(kWriterJoints), 120.0);
  ASSERT_TRUE(late.ok());
  ASSERT_TRUE((*late)->AppendClip(MakeClip("late", kWriterJoints, 30, 1)).ok());
  WriteArchive(path, MakeSkeleton(kWriterJoints), {MakeClip("first", kWriterJoints, 20, 2)});
  const Status committed = (*late)->Commit();
  EXPECT_TRUE(committed.IsBusy()) << committed.ToString();
  EXPECT_NE(committed.message().find("created by another writer"), std::string::npos);
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ASSERT_EQ(contents->clips.size(), 1u);
  EXPECT_EQ(contents->clips[0].name, "first");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);  // no temporary file left
}

TEST(FrameFileWriter, RejectsNonFiniteValuesAndLeavesTheWriterUsable) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  auto writer = FrameFileWriter::Create(path, MakeSkeleton(kWriterJoints), 120.0, SmallBlocks(16));
  ASSERT_TRUE(writer.ok());
  ClipFrames bad = MakeClip("bad", kWriterJoints, 40, 1);
  bad.rows[33 * FrameLayout{kWriterJoints}.stride() + 6] = std::numeric_limits<float>::quiet_NaN();
  Status status = (*writer)->AppendClip(bad);
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("frame 33"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("not finite"), std::string::npos) << status.message();
  bad.rows[33 * FrameLayout{kWriterJoints}.stride() + 6] = std::numeric_limits<float>::infinity();
  EXPECT_TRUE((*writer)->AppendClip(bad).IsInvalidArgument());
  ClipFrames bad_info = MakeClip("bad_info", kWriterJoints, 10, 1);
  bad_info.info.start_position[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE((*writer)->AppendClip(bad_info).IsInvalidArgument());

  const ClipFrames good = MakeClip("good", kWriterJoints, 40, 2);
  ASSERT_TRUE((*writer)->AppendClip(good).ok());
  EXPECT_EQ((*writer)->clips().size(), 1u);
  ASSERT_TRUE((*writer)->Commit().ok());
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok());
  ASSERT_EQ(contents->clips.size(), 1u);
  ExpectWithinQuantisationBound(good.rows, contents->rows, kWriterJoints);
}

TEST(FrameFileWriter, RejectsValuesThatOverflowTheQuantisedRange) {
  TempDir dir;
  auto writer = FrameFileWriter::Create(dir.File("a.mfs"), MakeSkeleton(kWriterJoints), 120.0);
  ASSERT_TRUE(writer.ok());
  ClipFrames clip = MakeClip("spin", kWriterJoints, 10, 1);
  // Heading step 1e-5 rad: int32 holds +-21474 rad.
  clip.rows[5 * FrameLayout{kWriterJoints}.stride() + FrameLayout{kWriterJoints}.heading_offset()] =
      30000.0f;
  Status status = (*writer)->AppendClip(clip);
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("overflows int32"), std::string::npos) << status.message();
}

TEST(FrameFileWriter, RejectsMalformedClips) {
  TempDir dir;
  auto writer = FrameFileWriter::Create(dir.File("a.mfs"), MakeSkeleton(kWriterJoints), 120.0);
  ASSERT_TRUE(writer.ok());
  ClipFrames clip = MakeClip("c", kWriterJoints, 10, 1);
  clip.rows.pop_back();
  EXPECT_TRUE((*writer)->AppendClip(clip).IsInvalidArgument());
  clip = MakeClip("c", kWriterJoints, 10, 1);
  clip.info.joint_offsets.pop_back();
  EXPECT_TRUE((*writer)->AppendClip(clip).IsInvalidArgument());
  clip = MakeClip("c", kWriterJoints, 10, 1, 60.0);  // archive at 120 fps
  EXPECT_TRUE((*writer)->AppendClip(clip).IsInvalidArgument());
  clip = MakeClip("", kWriterJoints, 10, 1);
  EXPECT_TRUE((*writer)->AppendClip(clip).IsInvalidArgument());
  clip = MakeClip("empty", kWriterJoints, 0, 1);
  EXPECT_TRUE((*writer)->AppendClip(clip).IsInvalidArgument());
  ASSERT_TRUE((*writer)->BeginClip(clip.info).ok());
  EXPECT_TRUE((*writer)->EndClip().IsInvalidArgument());
  EXPECT_TRUE((*writer)->AppendFrames(nullptr, 0).IsInvalidArgument());  // no clip open
  ASSERT_TRUE((*writer)->BeginClip(MakeClip("open", kWriterJoints, 1, 1).info).ok());
  EXPECT_TRUE((*writer)->Commit().IsInvalidArgument());  // clip still open
}

TEST(FrameFileWriter, CreateRejectsBadArguments) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  EXPECT_TRUE(FrameFileWriter::Create(path, Skeleton(), 120.0).status().IsInvalidArgument());
  EXPECT_TRUE(FrameFileWriter::Create(path, MakeSkeleton(2), 0.0).status().IsInvalidArgument());
  FrameFileWriterOptions options;
  options.block_frames = 0;
  EXPECT_TRUE(
      FrameFileWriter::Create(path, MakeSkeleton(2), 30.0, options).status().IsInvalidArgument());
  options = FrameFileWriterOptions();
  options.zstd_level = 1000;
  EXPECT_TRUE(
      FrameFileWriter::Create(path, MakeSkeleton(2), 30.0, options).status().IsInvalidArgument());
  options = FrameFileWriterOptions();
  options.height_step = -1;
  EXPECT_TRUE(
      FrameFileWriter::Create(path, MakeSkeleton(2), 30.0, options).status().IsInvalidArgument());
  EXPECT_TRUE(ListDir(dir.path()).empty());

  WriteBytes(path, "exists");
  Status exists = FrameFileWriter::Create(path, MakeSkeleton(2), 30.0).status();
  EXPECT_TRUE(exists.IsInvalidArgument());
  EXPECT_NE(exists.message().find("already exists"), std::string::npos);
}

TEST(FrameFileWriter, CreateWritesATemporaryFileUntilCommit) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  auto writer = FrameFileWriter::Create(path, MakeSkeleton(kWriterJoints), 120.0, SmallBlocks(16));
  ASSERT_TRUE(writer.ok());
  ASSERT_TRUE((*writer)->AppendClip(MakeClip("c", kWriterJoints, 100, 1)).ok());
  EXPECT_FALSE(std::filesystem::exists(path));
  ASSERT_EQ(ListDir(dir.path()).size(), 1u);
  EXPECT_NE(ListDir(dir.path())[0].find("a.mfs.tmp-"), std::string::npos);
  ASSERT_TRUE((*writer)->Commit().ok());
  EXPECT_EQ(ListDir(dir.path()), std::vector<std::string>{"a.mfs"});
  EXPECT_TRUE((*writer)->AppendClip(MakeClip("late", kWriterJoints, 1, 1)).IsInvalidArgument());
}

TEST(FrameFileWriter, AbandonedCreateLeavesNoFile) {
  TempDir dir;
  {
    auto writer = FrameFileWriter::Create(dir.File("a.mfs"), MakeSkeleton(kWriterJoints), 120.0,
                                          SmallBlocks(16));
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE((*writer)->AppendClip(MakeClip("c", kWriterJoints, 100, 1)).ok());
  }
  EXPECT_TRUE(ListDir(dir.path()).empty());
}

TEST(FrameFileWriter, AbandonedAppendLeavesTheArchiveUnchanged) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  WriteArchive(path, MakeSkeleton(kWriterJoints), SomeClips(2, 50), SmallBlocks(16));
  const std::string before = ReadBytes(path);
  {
    auto writer = FrameFileWriter::OpenForAppend(path, SmallBlocks(16));
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE((*writer)->AppendClip(MakeClip("more", kWriterJoints, 100, 5)).ok());
    EXPECT_GT(std::filesystem::file_size(path), before.size());  // blocks already written
  }
  EXPECT_EQ(ReadBytes(path), before);
}

TEST(FrameFileWriter, OpenForAppendDiscardsAnUncommittedTail) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  WriteArchive(path, MakeSkeleton(kWriterJoints), SomeClips(2, 50), SmallBlocks(16));
  const std::string committed = ReadBytes(path);
  WriteBytes(path, committed + std::string(3000, '\xab'));  // an interrupted append's leftovers
  {
    auto reader = FrameFileReader::Open(path);
    ASSERT_TRUE(reader.ok());
    EXPECT_EQ((*reader)->summary().uncommitted_bytes, 3000u);
    EXPECT_TRUE((*reader)->Verify().ok());
  }
  AppendToArchive(path, SomeClips(1, 30, 7, "more"), SmallBlocks(16));
  const std::string after = ReadBytes(path);
  EXPECT_EQ(after.substr(128, committed.size() - 128), committed.substr(128));
  EXPECT_EQ(after.find(std::string(16, '\xab')), std::string::npos);
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ((*reader)->summary().uncommitted_bytes, 0u);
  EXPECT_EQ((*reader)->clips().size(), 3u);
  EXPECT_TRUE((*reader)->Verify().ok());
}

TEST(FrameFileWriter, SecondWriterFailsFastBecauseTheArchiveIsLocked) {
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  WriteArchive(path, MakeSkeleton(kWriterJoints), SomeClips(1, 20), SmallBlocks(16));
  auto first = FrameFileWriter::OpenForAppend(path);
  ASSERT_TRUE(first.ok());
  {
    // A reader (another descriptor of the file) opening and closing must not drop the lock.
    auto reader = FrameFileReader::Open(path);
    ASSERT_TRUE(reader.ok());
  }
  auto second = FrameFileWriter::OpenForAppend(path);
  ASSERT_FALSE(second.ok());
  EXPECT_TRUE(second.status().IsBusy());
  EXPECT_NE(second.status().message().find("locked"), std::string::npos)
      << second.status().message();
  ASSERT_TRUE((*first)->AppendClip(MakeClip("x", kWriterJoints, 5, 3)).ok());
  ASSERT_TRUE((*first)->Commit().ok());
  // Released at commit.
  auto third = FrameFileWriter::OpenForAppend(path);
  ASSERT_TRUE(third.ok()) << third.status().ToString();
  third->reset();
  auto fourth = FrameFileWriter::OpenForAppend(path);
  EXPECT_TRUE(fourth.ok());
}

TEST(FrameFileWriter, OpenForAppendReportsMissingAndDamagedArchives) {
  TempDir dir;
  EXPECT_TRUE(FrameFileWriter::OpenForAppend(dir.File("none.mfs")).status().IsNotFound());
  WriteBytes(dir.File("junk.mfs"), std::string(500, 'j'));
  EXPECT_TRUE(FrameFileWriter::OpenForAppend(dir.File("junk.mfs")).status().IsCorruption());
  WriteBytes(dir.File("empty.mfs"), "");
  EXPECT_TRUE(FrameFileWriter::OpenForAppend(dir.File("empty.mfs")).status().IsCorruption());
}

}  // namespace
}  // namespace motif::testing
