// Golden bytes: the paths file of the spec's worked example (docs/formats/paths_file.md,
// "Worked example") is encoded and its annotated hexdump compared with the one in the spec, so
// the document and the code cannot drift apart. After an intended format change, print the
// new hexdump to paste into the spec with
//   MOTIF_UPDATE_GOLDEN=1 ./paths_file_test --gtest_filter='PathsFileGolden.*'
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/testing/golden_hexdump.h"

#include "common/file_util.h"
#include "formats/paths_file/paths_file_format.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/paths_file/paths_file_writer.h"

namespace motif::testing {
namespace {

const std::string kSpec = std::string(MOTIF_SOURCE_DIR) + "/docs/formats/paths_file.md";

PathsParams ExampleParams() {
  PathsParams params;
  params.trellis_identity = 0x1122334455667788ull;
  params.archive_identity = 0x0123456789abcdefull;
  params.frame_count = 1000;
  params.branch = 5;
  params.min_length = 60;
  params.all_branches = true;
  return params;
}

// Two branches of one tree, and the mirror path.
std::vector<PathCandidate> ExampleCandidates() {
  return {{100, 180, 500, 570, 100, 500},
          {100, 190, 500, 575, 100, 500},
          {500, 570, 100, 180, 500, 100}};
}

std::string AnnotatedHexdump(const std::string& bytes) {
  std::ostringstream out;
  out << "```\n# Header (96 bytes)\n";
  DumpHexLines(bytes, 0x00, 8, "magic \"\\x89MPA\\r\\n\\x1a\\n\"", &out);
  DumpHexLines(bytes, 0x08, 8, "format_major 1, format_minor 0, header_bytes 96", &out);
  DumpHexLines(bytes, 0x10, 8, "trellis_identity", &out);
  DumpHexLines(bytes, 0x18, 8, "archive_identity", &out);
  DumpHexLines(bytes, 0x20, 8, "frame_count 1000", &out);
  DumpHexLines(bytes, 0x28, 8, "branch 5, flags 1 (all_branches)", &out);
  DumpHexLines(bytes, 0x30, 8, "min_length 60", &out);
  DumpHexLines(bytes, 0x38, 8, "candidate_count 3", &out);
  DumpHexLines(bytes, 0x40, 8, "records_raw_bytes", &out);
  DumpHexLines(bytes, 0x48, 8, "records_bytes", &out);
  DumpHexLines(bytes, 0x50, 8, "records_checksum: XXH3-64 of the records section", &out);
  DumpHexLines(bytes, 0x58, 8, "header_checksum: XXH3-64 of bytes [0x00, 0x58)", &out);
  out << "# Records section (" << bytes.size() - 96 << " bytes): one zstd frame\n";
  DumpHexLines(bytes, 0x60, bytes.size() - 0x60, "zstd frame", &out);
  out << "```\n";
  return out.str();
}

TEST(PathsFileGolden, TheSpecsHexdumpIsTheEncodedExample) {
  auto bytes = EncodePathsFile(ExampleParams(), ExampleCandidates());
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  ExpectSpecHexdump(kSpec, AnnotatedHexdump(*bytes), *bytes);
  auto reader = PathsFileReader::FromBytes(*bytes, "example.mpa");
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ((*reader)->candidates(), ExampleCandidates());
}

TEST(PathsFileGolden, TheRecordsAreTheSpecsVarints) {
  std::string raw;
  paths_file::EncodeRecords(ExampleParams(), ExampleCandidates(), &raw);
  const char expected[] =
      "\x64\xe8\x07\x14\x0a\x00\x00"
      "\x00\x00\x1e\x0f\x00\x00"
      "\x90\x03\x9f\x06\x0a\x14\x00\x00";
  EXPECT_EQ(raw, std::string(expected, sizeof(expected) - 1));
}

}  // namespace
}  // namespace motif::testing
