#include "formats/import/take_descriptions.h"

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

Result<std::unordered_map<std::string, std::string>> ReadText(const testing::TempDir& dir,
                                                              const std::string& text) {
  const std::string path = dir.File("index.tsv");
  EXPECT_TRUE(AtomicWriteFile(path, text).ok());
  return ReadTakeDescriptions(path);
}

TEST(TakeDescriptions, ReadsTheFileAndDescriptionColumnsByTheHeader) {
  testing::TempDir dir;
  auto read = ReadText(dir,
                       "# an index\n"
                       "file\tformat\tdescription\n"
                       "bvh/01_01.bvh\tbvh\tplayground - forward jumps\r\n"
                       "\n"
                       "asfamc/90/90_30.amc\tamc\trussian dance\n"
                       "02_01\tbvh\t\n");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->size(), 3u);
  EXPECT_EQ(read->at("01_01"), "playground - forward jumps");
  EXPECT_EQ(read->at("90_30"), "russian dance");
  EXPECT_EQ(read->at("02_01"), "");
}

TEST(TakeDescriptions, RefusesAMissingColumnAShortLineAndTwoDescriptions) {
  testing::TempDir dir;
  auto no_column = ReadText(dir, "file\tdesc\nx\ty\n");
  ASSERT_FALSE(no_column.ok());
  EXPECT_NE(no_column.status().message().find("index.tsv:1"), std::string::npos);
  EXPECT_NE(no_column.status().message().find("'description'"), std::string::npos);
  auto short_line = ReadText(dir, "file\tformat\tdescription\nx.bvh\tbvh\n");
  ASSERT_FALSE(short_line.ok());
  EXPECT_NE(short_line.status().message().find("index.tsv:2"), std::string::npos);
  auto twice = ReadText(dir, "file\tdescription\na/x.bvh\twalk\nb/x.amc\trun\n");
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.status().message().find("'x'"), std::string::npos);
  EXPECT_TRUE(ReadText(dir, "file\tdescription\na/x.bvh\twalk\nb/x.amc\twalk\n").ok());
  EXPECT_FALSE(ReadText(dir, "").ok());
  EXPECT_FALSE(ReadText(dir, "file\tdescription\nx\t\xff\xfe\n").ok());
  EXPECT_FALSE(ReadTakeDescriptions(dir.File("missing.tsv")).ok());
}

}  // namespace
}  // namespace motif
