// Crash safety: count the file-system steps of a successful create or append, then fail each
// step in turn (once, or for good: a disk that stays full, the closest a test gets to a crash
// since nothing after the failing step reaches the disk) and check the archive afterwards: the
// previous version exactly (bit-identical rows), Verify passing, or, if the failure came after
// the commit point, exactly the new version. A later append must then work.
#include <filesystem>
#include <functional>

#include <gtest/gtest.h>

#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/formats/frame_file/frame_file_test_util.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint32_t kCrashJoints = 3;

FrameFileWriterOptions Options(FileSystem* file_system) {
  FrameFileWriterOptions options;
  options.block_frames = 16;
  options.file_system = file_system;
  return options;
}

std::vector<ClipFrames> BaseClips() {
  return {MakeClip("base0", kCrashJoints, 30, 1), MakeClip("base1", kCrashJoints, 25, 2)};
}

std::vector<ClipFrames> NewClips() {
  return {MakeClip("new0", kCrashJoints, 20, 3), MakeClip("new1", kCrashJoints, 27, 4)};
}

enum class AfterFailure {
  kDiskRecovers,  // non-sticky: only step k fails
  kStaysFull,     // sticky: every step from k on fails, also the writer's cleanup
  kRecoversLate,  // sticky, but the disk recovers before the writer is destroyed
};

// Runs an append of NewClips() through `file_system`; the writer is destroyed on return, after
// `recover` (if given) has run.
Status RunAppend(const std::string& path, FileSystem* file_system,
                 const std::function<void()>& recover = nullptr) {
  Status status = [&]() -> Status {
    auto writer = FrameFileWriter::OpenForAppend(path, Options(file_system));
    if (!writer.ok()) return writer.status();
    for (const ClipFrames& clip : NewClips()) {
      Status appended = (*writer)->AppendClip(clip);
      if (!appended.ok()) {
        if (recover) recover();
        return appended;
      }
    }
    Status committed = (*writer)->Commit();
    if (recover) recover();
    return committed;
  }();
  return status;
}

Status RunCreate(const std::string& path, FileSystem* file_system,
                 const std::function<void()>& recover = nullptr) {
  auto writer =
      FrameFileWriter::Create(path, MakeSkeleton(kCrashJoints), 120.0, Options(file_system));
  if (!writer.ok()) return writer.status();
  Status status;
  for (const ClipFrames& clip : BaseClips()) {
    status = (*writer)->AppendClip(clip);
    if (!status.ok()) break;
  }
  if (status.ok()) status = (*writer)->Commit();
  if (recover) recover();
  return status;
}

// Index of the first step whose description starts with `prefix`.
int64_t StepIndex(const std::vector<std::string>& steps, const std::string& prefix) {
  for (size_t step_idx = 0; step_idx < steps.size(); ++step_idx) {
    if (steps[step_idx].rfind(prefix, 0) == 0) return static_cast<int64_t>(step_idx);
  }
  return -1;
}

void ExpectVersion(const std::string& path, const ArchiveContents& expected,
                   const std::string& context) {
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << context << ": " << reader.status().ToString();
  Status verified = (*reader)->Verify();
  EXPECT_TRUE(verified.ok()) << context << ": " << verified.ToString();
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok()) << context;
  SCOPED_TRACE(context);
  ExpectSameContents(expected, *contents);
}

// A commit whose slot write was torn: its bytes were synced before, so the version is whole and
// is read from its footer at the end of the file; Verify reports the slot.
void ExpectTornCommit(const std::string& path, const ArchiveContents& expected,
                      const std::string& context) {
  auto reader = FrameFileReader::Open(path);
  ASSERT_TRUE(reader.ok()) << context << ": " << reader.status().ToString();
  EXPECT_NE((*reader)->summary().damaged_slot_reason, "") << context;
  Status verified = (*reader)->Verify();
  EXPECT_TRUE(verified.IsCorruption()) << context;
  EXPECT_NE(verified.message().find("read from its footer"), std::string::npos) << context;
  auto contents = ReadContents(path);
  ASSERT_TRUE(contents.ok()) << context;
  SCOPED_TRACE(context);
  ExpectSameContents(expected, *contents);
}

class FrameFileCrashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_path_ = dir_.File("base.mfs");
    WriteArchive(base_path_, MakeSkeleton(kCrashJoints), BaseClips(), Options(PosixFileSystem()));
    auto previous = ReadContents(base_path_);
    ASSERT_TRUE(previous.ok());
    previous_ = *previous;
    base_bytes_ = ReadBytes(base_path_);
  }

  // The contents after a successful append, and its steps.
  void LearnAppend(const std::string& base_bytes) {
    const std::string path = dir_.File("reference.mfs");
    WriteBytes(path, base_bytes);
    RecordingFileSystem recording;
    ASSERT_TRUE(RunAppend(path, &recording).ok());
    steps_ = recording.steps();
    auto next = ReadContents(path);
    ASSERT_TRUE(next.ok());
    next_ = *next;
    FaultInjectingFileSystem counting;
    WriteBytes(path, base_bytes);
    ASSERT_TRUE(RunAppend(path, &counting).ok());
    ASSERT_EQ(counting.steps(), static_cast<int64_t>(steps_.size()));
    std::filesystem::remove(path);
  }

  void CheckAppendAtEveryStep(const std::string& base_bytes) {
    LearnAppend(base_bytes);
    // The commit point: the write of a 40-byte commit slot at offset 48 or 88.
    int64_t commit_step = StepIndex(steps_, "write 88 40");
    if (commit_step < 0) commit_step = StepIndex(steps_, "write 48 40");
    ASSERT_GT(commit_step, 0);
    for (AfterFailure mode :
         {AfterFailure::kDiskRecovers, AfterFailure::kStaysFull, AfterFailure::kRecoversLate}) {
      for (int64_t step = 0; step < static_cast<int64_t>(steps_.size()); ++step) {
        const std::string context = "append, step " + std::to_string(step) + " (" + steps_[step] +
                                    "), mode " + std::to_string(static_cast<int>(mode));
        // A new file each time (rewriting one with O_TRUNC makes ext4 flush it on close).
        const std::string path =
            dir_.File(Numbered("a", step) + Numbered("-", static_cast<int>(mode)) + ".mfs");
        WriteBytes(path, base_bytes);
        FaultInjectingFileSystem faulty;
        faulty.FailAt(step, mode != AfterFailure::kDiskRecovers);
        std::function<void()> recover;
        if (mode == AfterFailure::kRecoversLate) recover = [&] { faulty.FailAt(-1); };
        Status status = RunAppend(path, &faulty, recover);
        EXPECT_FALSE(status.ok()) << context;
        EXPECT_TRUE(faulty.injected()) << context;
        if (step == commit_step) {
          ExpectTornCommit(path, next_, context);
        } else if (step < commit_step) {
          ExpectVersion(path, previous_, context);
          if (step < commit_step && mode != AfterFailure::kStaysFull) {
            // The writer truncated its tail away: the file is byte for byte the old one
            // (unless the old file itself had a tail, which OpenForAppend dropped first).
            const std::string after = ReadBytes(path);
            EXPECT_TRUE(after == base_bytes || after == base_bytes_) << context;
          }
        } else {
          ExpectVersion(path, next_, context);
        }
        // Recovery: the next writer drops any leftovers and appends.
        auto writer = FrameFileWriter::OpenForAppend(path, Options(PosixFileSystem()));
        ASSERT_TRUE(writer.ok()) << context << ": " << writer.status().ToString();
        ASSERT_TRUE((*writer)->AppendClip(MakeClip("later", kCrashJoints, 9, 8)).ok()) << context;
        ASSERT_TRUE((*writer)->Commit().ok()) << context;
        auto reader = FrameFileReader::Open(path);
        ASSERT_TRUE(reader.ok()) << context;
        EXPECT_TRUE((*reader)->Verify().ok()) << context;
        EXPECT_EQ((*reader)->summary().uncommitted_bytes, 0u) << context;
        const size_t expected_clips = (step < commit_step ? previous_ : next_).clips.size() + 1;
        EXPECT_EQ((*reader)->clips().size(), expected_clips) << context;
        if (::testing::Test::HasFailure()) return;
      }
    }
  }

  TempDir dir_;
  std::string base_path_;
  std::string base_bytes_;
  ArchiveContents previous_;
  ArchiveContents next_;
  std::vector<std::string> steps_;
};

TEST_F(FrameFileCrashTest, AppendSurvivesAFailureAtEveryStep) {
  CheckAppendAtEveryStep(base_bytes_);
  // open, 4 blocks (47 frames in 16-frame blocks = 3 blocks), metadata, fsync, slot, fsync.
  EXPECT_GE(steps_.size(), 7u);
}

TEST_F(FrameFileCrashTest, AppendOverAnInterruptedAppendSurvivesAFailureAtEveryStep) {
  // Leftovers of an earlier interrupted append: OpenForAppend truncates them (one more step).
  CheckAppendAtEveryStep(base_bytes_ + std::string(777, '\x5a'));
  EXPECT_GE(StepIndex(steps_, "truncate"), 0);
}

TEST_F(FrameFileCrashTest, CreateSurvivesAFailureAtEveryStep) {
  RecordingFileSystem recording;
  const std::string reference = dir_.File("reference.mfs");
  ASSERT_TRUE(RunCreate(reference, &recording).ok());
  const std::vector<std::string> steps = recording.steps();
  auto created = ReadContents(reference);
  ASSERT_TRUE(created.ok());
  std::filesystem::remove(reference);
  const int64_t rename_step = StepIndex(steps, "rename");
  ASSERT_GT(rename_step, 0);
  EXPECT_EQ(steps.back(), "fsync directory");

  for (AfterFailure mode :
       {AfterFailure::kDiskRecovers, AfterFailure::kStaysFull, AfterFailure::kRecoversLate}) {
    for (int64_t step = 0; step < static_cast<int64_t>(steps.size()); ++step) {
      const std::string context = "create, step " + std::to_string(step) + " (" + steps[step] +
                                  "), mode " + std::to_string(static_cast<int>(mode));
      TempDir dir;
      const std::string path = dir.File("a.mfs");
      FaultInjectingFileSystem faulty;
      faulty.FailAt(step, mode != AfterFailure::kDiskRecovers);
      std::function<void()> recover;
      if (mode == AfterFailure::kRecoversLate) recover = [&] { faulty.FailAt(-1); };
      Status status = RunCreate(path, &faulty, recover);
      EXPECT_FALSE(status.ok()) << context;
      const std::vector<std::string> files = ListDir(dir.path());
      if (step <= rename_step) {
        EXPECT_FALSE(std::filesystem::exists(path)) << context;
      } else {
        ExpectVersion(path, *created, context);
      }
      if (mode == AfterFailure::kStaysFull) {
        // The cleanup's own remove failed too: at most the temporary file is left over.
        for (const std::string& file : files) {
          EXPECT_TRUE(file == "a.mfs" || file.rfind("a.mfs.tmp-", 0) == 0) << context << file;
        }
      } else {
        for (const std::string& file : files) EXPECT_EQ(file, "a.mfs") << context;
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
}

}  // namespace
}  // namespace motif::testing
