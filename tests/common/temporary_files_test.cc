#include "common/temporary_files.h"

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "common/writable_file.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

void Touch(const std::string& path) { std::ofstream(path) << "partial"; }

// In a child: one temporary file renamed into place, one left half-written, then the signal.
void WriteThenReceive(const std::string& out, int signal_number) {
  RemoveTemporaryFilesOnTermination();
  const std::string kept = TemporaryPathFor(out);
  Touch(kept);
  if (!PosixFileSystem()->Rename(kept, out).ok()) std::abort();
  Touch(TemporaryPathFor(out + ".next"));
  ::raise(signal_number);
}

TEST(TemporaryFilesDeathTest, ASignalRemovesTheTemporariesAndEndsTheProcessByIt) {
  for (int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    testing::TempDir dir;
    const std::string out = dir.File("archive.mfs");
    EXPECT_EXIT(WriteThenReceive(out, signal_number), ::testing::KilledBySignal(signal_number),
                "");
    std::vector<std::string> left;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      left.push_back(entry.path().filename().string());
    }
    EXPECT_EQ(left, std::vector<std::string>{"archive.mfs"}) << "signal " << signal_number;
  }
}

TEST(TemporaryFiles, ARemovedOrRenamedFileIsNoLongerTracked) {
  testing::TempDir dir;
  // Many more files than slots, each renamed or removed: none stays tracked, so a later one is.
  for (int round = 0; round < 2000; ++round) {
    const std::string temp = TemporaryPathFor(dir.File("x"));
    Touch(temp);
    ASSERT_TRUE((round % 2 ? PosixFileSystem()->Remove(temp)
                           : PosixFileSystem()->Rename(temp, dir.File("x")))
                    .ok());
  }
  const std::string out = dir.File("y");
  EXPECT_EXIT(WriteThenReceive(out, SIGTERM), ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir.File("y.next")));
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 2u);  // x and y
}

}  // namespace
}  // namespace motif
