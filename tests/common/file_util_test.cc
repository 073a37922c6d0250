#include "common/file_util.h"

#include <sys/stat.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "common/writable_file.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TEST(AtomicWriteFile, WritesAndReplaces) {
  testing::TempDir dir;
  const std::string path = dir.File("out.json");
  ASSERT_TRUE(AtomicWriteFile(path, "first").ok());
  ASSERT_TRUE(AtomicWriteFile(path, "second").ok());
  EXPECT_EQ(ReadFileToString(path).value(), "second");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(FileSystemRename, NoReplaceLeavesAnExistingFileAndSaysBusy) {
  testing::TempDir dir;
  for (FileSystem* file_system : {PosixFileSystem(), NoSyncFileSystem()}) {
    ASSERT_TRUE(AtomicWriteFile(dir.File("new"), "new").ok());
    ASSERT_TRUE(AtomicWriteFile(dir.File("old"), "old").ok());
    const Status refused = file_system->RenameNoReplace(dir.File("new"), dir.File("old"));
    EXPECT_TRUE(refused.IsBusy()) << refused.ToString();
    EXPECT_EQ(ReadFileToString(dir.File("old")).value(), "old");
    ASSERT_TRUE(file_system->RenameNoReplace(dir.File("new"), dir.File("moved")).ok());
    EXPECT_EQ(ReadFileToString(dir.File("moved")).value(), "new");
    EXPECT_FALSE(std::filesystem::exists(dir.File("new")));
    std::filesystem::remove(dir.File("moved"));
  }
}

TEST(AtomicWriteFile, AMissingFolderIsNamed) {
  testing::TempDir dir;
  const Status missing = AtomicWriteFile(dir.File("absent/x.txt"), "x");
  EXPECT_TRUE(missing.IsIOError());
  EXPECT_EQ(missing.message(), "cannot write " + dir.File("absent/x.txt") + ": " +
                                   dir.File("absent") + " does not exist");
  ASSERT_TRUE(AtomicWriteFile(dir.File("plain"), "x").ok());
  EXPECT_NE(AtomicWriteFile(dir.File("plain/x.txt"), "x").message().find("is not a folder"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.File("absent")));
}

TEST(AtomicWriteFile, FailureAtAnyStepKeepsTheOldContent) {
  testing::TempDir dir;
  const std::string path = dir.File("out.json");
  ASSERT_TRUE(AtomicWriteFile(path, "old").ok());
  testing::FaultInjectingFileSystem counting;
  ASSERT_TRUE(AtomicWriteFile(path, "counted", &counting).ok());
  ASSERT_TRUE(AtomicWriteFile(path, "old").ok());
  const int64_t steps = counting.steps();
  ASSERT_GE(steps, 5);
  for (int64_t step = 0; step < steps; ++step) {
    testing::FaultInjectingFileSystem file_system;
    file_system.FailAt(step);
    Status status = AtomicWriteFile(path, "new content", &file_system);
    const std::string content = ReadFileToString(path).value();
    if (status.ok()) {
      EXPECT_EQ(content, "new content") << "step " << step;
    } else {
      // Up to the rename the old file stands; only a failed directory sync comes after it.
      EXPECT_TRUE(content == "old" || content == "new content") << "step " << step;
      if (content == "new content") {
        ASSERT_TRUE(AtomicWriteFile(path, "old").ok());
      }
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      EXPECT_EQ(entry.path().filename(), "out.json") << "temporary file left at step " << step;
    }
  }
}

TEST(ReadFileToString, MissingFileIsNotFound) {
  testing::TempDir dir;
  EXPECT_TRUE(ReadFileToString(dir.File("absent")).status().IsNotFound());
}

TEST(ReadFileToString, ReadsAWholeFileAndRefusesFoldersFifosAndDevicesWithoutBlocking) {
  testing::TempDir dir;
  const std::string text(200000, 'x');  // more than one read
  ASSERT_TRUE(AtomicWriteFile(dir.File("big"), text).ok());
  EXPECT_EQ(ReadFileToString(dir.File("big")).value(), text);
  ASSERT_TRUE(AtomicWriteFile(dir.File("empty"), "").ok());
  EXPECT_EQ(ReadFileToString(dir.File("empty")).value(), "");

  auto folder = ReadFileToString(dir.path());
  ASSERT_FALSE(folder.ok());
  EXPECT_TRUE(folder.status().IsInvalidArgument()) << folder.status().ToString();
  // A FIFO with no writer would block a plain open forever; /dev/zero would never end.
  const std::string fifo = dir.File("take.bvh");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/zero", dir.File("zero.bvh"));
  for (const std::string& path : {fifo, dir.File("zero.bvh")}) {
    auto read = ReadFileToString(path);
    ASSERT_FALSE(read.ok()) << path;
    EXPECT_TRUE(read.status().IsInvalidArgument()) << read.status().ToString();
    EXPECT_NE(read.status().message().find(path + ": not a regular file"), std::string::npos)
        << read.status().ToString();
  }
}

// A size limit refuses a larger file on its size, naming it, and reads one at the limit whole.
TEST(ReadFileToString, RefusesAFileLargerThanTheLimit) {
  testing::TempDir dir;
  ASSERT_TRUE(AtomicWriteFile(dir.File("ten"), "0123456789").ok());
  EXPECT_EQ(ReadFileToString(dir.File("ten"), 10).value(), "0123456789");
  auto refused = ReadFileToString(dir.File("ten"), 9);
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(refused.status().IsInvalidArgument());
  EXPECT_EQ(refused.status().message(),
            dir.File("ten") + ": 10 bytes, more than the 9 allowed for this file");
}

}  // namespace
}  // namespace motif
