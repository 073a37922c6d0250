// instances.csv: the exact text of a small hand-made document (a clip named with a comma and
// quotes, a clip starting at its file's frame 2 and resampled from 100 fps), the ranks and
// their tie rule, and the file read back by an independent RFC 4180 reader.
#include "engine/cluster/instances_csv.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "tests/testing/csv_rows.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

const char* const kQuotedName = "walk, \"fast\"";

MotifsJsonInstance Instance(const std::string& clip, uint64_t start, uint64_t end,
                            std::optional<double> distance) {
  MotifsJsonInstance instance{clip, start, end, 0};
  instance.distance = distance;
  return instance;
}

MotifsDocument SmallDocument() {
  MotifsDocument document;
  document.archive = "a.mfs";
  document.frames = 1500;
  document.clips = {{kQuotedName, "/takes/walk, \"fast\".bvh", 1000, 120, 0, 1, 120},
                    {"07_02", "/takes/07_02.bvh", 500, 120, 1000, 2, 100}};
  MotifsJsonMotif first;
  first.id = 0;
  first.instances = {Instance(kQuotedName, 100, 220, 0.5), Instance(kQuotedName, 400, 460, 0.0),
                     Instance("07_02", 3, 9, 0.25), Instance("07_02", 50, 170, 0.5)};
  first.representative = 1;
  MotifsJsonMotif copies;  // an identical copy of the representative: as near, ranked after it
  copies.id = 1;
  copies.instances = {Instance(kQuotedName, 600, 660, 0.0), Instance(kQuotedName, 700, 760, 0.0)};
  copies.representative = 1;
  MotifsJsonMotif unmeasured;  // written without the archive: no rank, no distance
  unmeasured.id = 2;
  unmeasured.instances = {Instance("07_02", 200, 260, std::nullopt),
                          Instance("07_02", 300, 360, std::nullopt)};
  document.motifs = {first, copies, unmeasured};
  return document;
}

TEST(InstancesCsvTest, RanksByDistanceToTheRepresentativeTiesToTheFirstListed) {
  const MotifsDocument document = SmallDocument();
  EXPECT_EQ(InstanceRanks(document.motifs[0]), (std::vector<uint32_t>{2, 0, 1, 3}));
  EXPECT_EQ(InstanceRanks(document.motifs[1]), (std::vector<uint32_t>{1, 0}));
  EXPECT_TRUE(InstanceRanks(document.motifs[2]).empty());
}

TEST(InstancesCsvTest, QuotesAFieldOnlyWhenItMust) {
  EXPECT_EQ(CsvField("05_01"), "05_01");
  EXPECT_EQ(CsvField(kQuotedName), "\"walk, \"\"fast\"\"\"");
  EXPECT_EQ(CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(CsvField(""), "");
}

TEST(InstancesCsvTest, ExactTextOfASmallDocument) {
  // File frames: 05_01-like clip + 1; 07_02: 2 + round(k x 100 / 120). Seconds in the file:
  // source_first_frame / source fps + k / 120.
  const std::string expected =
      "motif,rank,clip,source,start,end,file_first_frame,file_last_frame,start_seconds,"
      "end_seconds,distance\n"
      "0,2,\"walk, \"\"fast\"\"\",\"/takes/walk, \"\"fast\"\".bvh\",100,220,101,220,0.841667,"
      "1.841667,0.5\n"
      "0,0,\"walk, \"\"fast\"\"\",\"/takes/walk, \"\"fast\"\".bvh\",400,460,401,460,3.341667,"
      "3.841667,0\n"
      "0,1,07_02,/takes/07_02.bvh,3,9,5,9,0.045000,0.095000,0.25\n"
      "0,3,07_02,/takes/07_02.bvh,50,170,44,143,0.436667,1.436667,0.5\n"
      "1,1,\"walk, \"\"fast\"\"\",\"/takes/walk, \"\"fast\"\".bvh\",600,660,601,660,5.008333,"
      "5.508333,0\n"
      "1,0,\"walk, \"\"fast\"\"\",\"/takes/walk, \"\"fast\"\".bvh\",700,760,701,760,5.841667,"
      "6.341667,0\n"
      "2,,07_02,/takes/07_02.bvh,200,260,169,218,1.686667,2.186667,\n"
      "2,,07_02,/takes/07_02.bvh,300,360,252,301,2.520000,3.020000,\n";
  EXPECT_EQ(InstancesCsvText(SmallDocument()), expected);
}

TEST(InstancesCsvTest, WrittenAtomicallyAndReadBackByAnRfc4180Reader) {
  testing::TempDir dir;
  const std::string path = dir.File("instances.csv");
  ASSERT_TRUE(WriteInstancesCsv(path, SmallDocument()).ok());
  const auto rows = testing::ParseCsvRows(ReadFileToString(path).value());
  ASSERT_EQ(rows.size(), 9u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), 11u);
  EXPECT_EQ(rows[0][2], "clip");
  EXPECT_EQ(rows[1][2], kQuotedName);
  EXPECT_EQ(rows[1][3], "/takes/walk, \"fast\".bvh");
  EXPECT_EQ(rows[3][2], "07_02");
  EXPECT_EQ(rows[8][10], "");
  // No temporary file is left beside it.
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(names, std::vector<std::string>{"instances.csv"});

  const Status missing =
      WriteInstancesCsv(dir.File("no/such/folder/instances.csv"), SmallDocument());
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("instances file"), std::string::npos) << missing.message();
}

}  // namespace
}  // namespace motif
