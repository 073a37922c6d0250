#include "common/mapped_file.h"

#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

constexpr uint64_t kPages = 4;

std::string WritePages(const testing::TempDir& dir, uint64_t page_bytes) {
  const std::string path = dir.File("mapped.bin");
  std::ofstream out(path, std::ios::binary);
  out << std::string(kPages * page_bytes, '\x5a');
  return path;
}

uint64_t PageBytes() { return static_cast<uint64_t>(::sysconf(_SC_PAGESIZE)); }

TEST(MappedFile, AFileCutWhileMappedReadsZerosAndIsReportedNotASigbus) {
  testing::TempDir dir;
  const std::string path = WritePages(dir, PageBytes());
  auto file = MappedFile::Open(path);
  ASSERT_TRUE(file.ok()) << file.status().ToString();
  EXPECT_EQ((*file)->data()[3 * PageBytes()], 0x5a);
  EXPECT_TRUE((*file)->CheckNotCut().ok());
  ASSERT_EQ(::truncate(path.c_str(), 200), 0);
  // Past the new end: without the guard, this read is killed by SIGBUS.
  const volatile uint8_t* past_end = (*file)->data() + 2 * PageBytes() + 7;
  EXPECT_EQ(*past_end, 0);
  EXPECT_TRUE((*file)->cut());
  const Status status = (*file)->CheckNotCut();
  EXPECT_TRUE(status.IsCorruption()) << status.ToString();
  EXPECT_NE(status.message().find(path), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("cut while it was being read"), std::string::npos);
  EXPECT_NE(status.message().find("now 200 bytes"), std::string::npos) << status.message();
}

TEST(MappedFile, AShorterFileIsReportedBeforeAnyReadFaults) {
  testing::TempDir dir;
  const std::string path = WritePages(dir, PageBytes());
  auto file = MappedFile::Open(path);
  ASSERT_TRUE(file.ok());
  ASSERT_EQ(::truncate(path.c_str(), PageBytes()), 0);
  EXPECT_FALSE((*file)->cut());
  EXPECT_TRUE((*file)->CheckNotCut().IsCorruption());
}

TEST(MappedFile, AGuardLastsAsLongAsItsMappingAndFreesItsSlot) {
  testing::TempDir dir;
  const std::string path = WritePages(dir, PageBytes());
  // More files, one after the other, than there are guard slots: each gets one.
  for (int round = 0; round < 2000; ++round) {
    auto file = MappedFile::Open(path);
    ASSERT_TRUE(file.ok());
    ASSERT_TRUE((*file)->CheckNotCut().ok());
  }
  auto file = MappedFile::Open(path);
  ASSERT_EQ(::truncate(path.c_str(), 0), 0);
  EXPECT_EQ(*static_cast<const volatile uint8_t*>((*file)->data() + PageBytes()), 0);
  EXPECT_TRUE((*file)->cut());
}

TEST(MappedFileDeathTest, ASigbusElsewhereStillKillsTheProcess) {
  testing::TempDir dir;
  auto file = MappedFile::Open(WritePages(dir, PageBytes()));  // the guard's handler is in place
  ASSERT_TRUE(file.ok());
  // Killed by SIGBUS, or by the handler that was there before the guard's (AddressSanitizer's
  // reports the signal and aborts).
  EXPECT_DEATH(::raise(SIGBUS), "");
}

}  // namespace
}  // namespace motif
