// Crash safety: count the file-system steps of a whole build (open, header, every block's write
// and fsync, the index and footer, the rename, the directory sync), then fail each step in turn,
// once or for good (a disk that stays full: nothing after the failing step reaches the disk, the
// closest a test gets to a crash). Afterwards a finished file, if there is one, must be the
// uninterrupted build byte for byte, and a resume must complete to exactly that file. The steps
// run over NoSyncFileSystem: an fsync is still a step that can fail, but it costs nothing, so
// the hundreds of builds stay fast (the reference build syncs for real).
#include <filesystem>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint32_t kCrashBlockColumns = 8;
constexpr uint64_t kCrashFrames = 5 * kCrashBlockColumns - 3;

TrellisFileWriterOptions CrashOptions(FileSystem* file_system) {
  TrellisFileWriterOptions options;
  options.block_columns = kCrashBlockColumns;
  options.file_system = file_system;
  return options;
}

// A whole build through `file_system`, stopping at the first failure (the writer is destroyed,
// as a crashed process would leave it). Returns how many blocks AppendBlock accepted.
Status Build(const std::string& path, const TrellisParams& params, const TrellisColumns& columns,
             FileSystem* file_system, uint64_t* blocks_appended) {
  *blocks_appended = 0;
  MOTIF_ASSIGN_OR_RETURN(auto writer,
                         TrellisFileWriter::OpenOrResume(path, params, CrashOptions(file_system)));
  while (writer->next_column() < params.frame_count) {
    const uint64_t first = writer->next_column();
    const uint64_t count = std::min<uint64_t>(kCrashBlockColumns, params.frame_count - first);
    MOTIF_RETURN_IF_ERROR(writer->AppendBlock(Slice(columns, first, count)));
    ++*blocks_appended;
  }
  return writer->Finish();
}

class TrellisFileCrashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    params_ = MakeParams(kCrashFrames, 50);
    columns_ = MakeRunColumns(kCrashFrames, params_.eps, 5, 40, 77);
    const std::string reference = dir_.File("reference.mtr");
    FaultInjectingFileSystem counting(PosixFileSystem());
    uint64_t blocks = 0;
    ASSERT_TRUE(Build(reference, params_, columns_, &counting, &blocks).ok());
    steps_ = counting.steps();
    reference_ = ReadBytes(reference);
  }

  TempDir dir_;
  TrellisParams params_;
  TrellisColumns columns_;
  std::string reference_;
  int64_t steps_ = 0;
};

TEST_F(TrellisFileCrashTest, AFailureAtEveryStepLeavesNoWrongFileAndResumesToTheSameBytes) {
  // open, header write, fsync, directory fsync; 5 blocks x (write, fsync); index and footer
  // write, fsync, rename, directory fsync.
  EXPECT_EQ(steps_, 4 + 5 * 2 + 4);
  for (bool sticky : {false, true}) {
    for (int64_t step = 0; step < steps_; ++step) {
      const std::string context =
          "step " + std::to_string(step) + (sticky ? " (disk stays full)" : " (fails once)");
      SCOPED_TRACE(context);
      TempDir dir;
      const std::string path = dir.File("t.mtr");
      FaultInjectingFileSystem faulty(NoSyncFileSystem());
      faulty.FailAt(step, sticky);
      uint64_t blocks_appended = 0;
      const Status status = Build(path, params_, columns_, &faulty, &blocks_appended);
      EXPECT_FALSE(status.ok());
      EXPECT_TRUE(faulty.injected());
      EXPECT_EQ(status.code(), Status::Code::kResourceExhausted) << status.ToString();
      // A finished file appears only once complete (the rename), and then it is the reference.
      if (FileExists(path)) {
        EXPECT_TRUE(ReadBytes(path) == reference_);
        EXPECT_FALSE(FileExists(TrellisFileWriter::PartialPath(path)));
      }
      // Resume on a working disk: at least the blocks acknowledged before the failure are kept.
      auto writer =
          TrellisFileWriter::OpenOrResume(path, params_, CrashOptions(NoSyncFileSystem()));
      ASSERT_TRUE(writer.ok()) << writer.status().ToString();
      const uint64_t resumed = (*writer)->next_column();
      EXPECT_EQ(resumed % kCrashBlockColumns == 0 || resumed == kCrashFrames, true);
      if (!FileExists(path)) {
        EXPECT_GE(resumed, std::min<uint64_t>(kCrashFrames, blocks_appended * kCrashBlockColumns));
      }
      writer->reset();
      uint64_t blocks = 0;
      ASSERT_TRUE(Build(path, params_, columns_, NoSyncFileSystem(), &blocks).ok());
      EXPECT_TRUE(ReadBytes(path) == reference_);
      EXPECT_FALSE(FileExists(TrellisFileWriter::PartialPath(path)));
      if (HasFailure()) return;
    }
  }
}

// A failure while resuming (the truncation of a torn tail, the writes after it) is itself
// resumable.
TEST_F(TrellisFileCrashTest, AFailureWhileResumingATornBuildIsResumableToo) {
  const std::string path = dir_.File("torn.mtr");
  const std::string partial = TrellisFileWriter::PartialPath(path);
  {
    auto writer = TrellisFileWriter::OpenOrResume(path, params_, CrashOptions(NoSyncFileSystem()));
    ASSERT_TRUE(writer.ok());
    for (uint64_t block_idx = 0; block_idx < 3; ++block_idx) {
      ASSERT_TRUE(
          (*writer)
              ->AppendBlock(Slice(columns_, block_idx * kCrashBlockColumns, kCrashBlockColumns))
              .ok());
    }
  }
  const std::string torn = ReadBytes(partial);
  const std::string torn_tail = torn.substr(0, torn.size() - 10);
  for (bool sticky : {false, true}) {
    for (int64_t step = 0;; ++step) {
      SCOPED_TRACE("step " + std::to_string(step) + (sticky ? " sticky" : ""));
      std::filesystem::remove(path);
      WriteBytes(partial, torn_tail);
      FaultInjectingFileSystem faulty(NoSyncFileSystem());
      faulty.FailAt(step, sticky);
      uint64_t blocks = 0;
      const Status status = Build(path, params_, columns_, &faulty, &blocks);
      if (!faulty.injected()) {
        ASSERT_TRUE(status.ok());
        break;
      }
      ASSERT_TRUE(Build(path, params_, columns_, NoSyncFileSystem(), &blocks).ok());
      EXPECT_TRUE(ReadBytes(path) == reference_);
      if (HasFailure()) return;
    }
  }
}

}  // namespace
}  // namespace motif::testing
