// Golden bytes: the tiny trellis of the spec's worked example (docs/formats/trellis_file.md,
// "Worked example") is written and compared byte for byte with the fixture
// tests/data/trellis_file/tiny.mtr.golden and with the hexdump in the spec, so the document, the
// fixture and the code cannot drift apart. After an intended format change, regenerate both with
//   MOTIF_UPDATE_GOLDEN=1 ./trellis_file_test --gtest_filter='TrellisFileGolden.*'
// which rewrites the fixture and prints the annotated hexdump to paste into the spec.
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/testing/golden_hexdump.h"

#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_format.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

const std::string kSourceDir = MOTIF_SOURCE_DIR;
const std::string kFixture = kSourceDir + "/tests/data/trellis_file/tiny.mtr.golden";
const std::string kSpec = kSourceDir + "/docs/formats/trellis_file.md";

TrellisParams TinyParams() {
  TrellisParams params;
  params.frame_count = 6;
  params.archive_identity = 0x0123456789abcdefull;
  params.eps = 1.0f;
  params.mu = 3.0f;
  params.sigma = 1.0f;
  params.k_max = 4;
  params.exclusion_frames = 2;
  params.search_mode = 0;
  params.seed = 42;
  params.weights_hash = 0xfedcba9876543210ull;
  params.search_params = "exact";
  return params;
}

// The worked example's columns: frame t's neighbours j (|t - j| >= 2) and their distances.
TrellisColumns TinyColumns() {
  return {
      {{3, 0.5f}, {4, 0.25f}, {5, 0.125f}},  // column 0: one run of three
      {{4, 0.25f}, {5, 0.5f}},               // column 1
      {},                                    // column 2: no neighbour
      {{0, 0.5f}, {1, 0.75f}, {5, 1.0f}},    // column 3: two runs
      {{0, 0.25f}, {1, 0.0f}, {2, 0.125f}},  // column 4 (second block)
      {{0, 0.125f}, {3, 1.0f}},              // column 5
  };
}

std::string WriteTiny(const TempDir& dir) {
  TrellisFileWriterOptions options;
  options.block_columns = 4;
  const std::string path = dir.File("tiny.mtr");
  const Status status = WriteTrellis(path, TinyParams(), TinyColumns(), options);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return path;
}

// The annotated hexdump of the spec's worked example.
std::string AnnotatedHexdump(const std::string& bytes) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  trellis_file::FileHeader header;
  uint64_t header_bytes = 0;
  EXPECT_TRUE(
      trellis_file::FileHeader::DecodeFrom(data, bytes.size(), &header, &header_bytes).ok());
  const uint64_t footer_offset = bytes.size() - trellis_file::kFooterBytes;
  trellis_file::Footer footer;
  EXPECT_TRUE(trellis_file::Footer::DecodeFrom(data + footer_offset, &footer).ok());
  std::ostringstream out;
  out << "# File header (" << header_bytes << " bytes)\n";
  DumpHexLines(bytes, 0x00, 8, "magic \"\\x89MTR\\r\\n\\x1a\\n\"", &out);
  DumpHexLines(bytes, 0x08, 8,
               "format_major 1, format_minor 0, header_bytes " + std::to_string(header_bytes),
               &out);
  DumpHexLines(bytes, 0x10, 8, "block_columns 4, params_bytes " + std::to_string(header_bytes - 40),
               &out);
  DumpHexLines(bytes, 0x18, 8, "reserved", &out);
  DumpHexLines(bytes, 0x20, 8, "params: frame_count 6", &out);
  DumpHexLines(bytes, 0x28, 8, "params: archive_identity", &out);
  DumpHexLines(bytes, 0x30, 12, "params: eps 1.0, mu 3.0, sigma 1.0 (f32)", &out);
  DumpHexLines(bytes, 0x3c, 12, "params: k_max 4, exclusion_frames 2, search_mode 0", &out);
  DumpHexLines(bytes, 0x48, 8, "params: seed 42", &out);
  DumpHexLines(bytes, 0x50, 8, "params: weights_hash", &out);
  DumpHexLines(bytes, 0x58, 4 + header.params.search_params.size(),
               "params: search_params \"" + header.params.search_params + "\"", &out);
  DumpHexLines(
      bytes, header_bytes - 8, 8,
      "header_checksum: XXH3-64 of bytes [0x00, " + trellis_file::Hex(header_bytes - 8) + ")",
      &out);
  std::vector<trellis_file::BlockHandle> blocks;
  for (uint64_t block_idx = 0; block_idx < footer.block_count; ++block_idx) {
    blocks.push_back(trellis_file::BlockHandle::DecodeFrom(
        data + footer.index_offset + block_idx * trellis_file::kBlockEntryBytes));
  }
  for (size_t block_idx = 0; block_idx < blocks.size(); ++block_idx) {
    const trellis_file::BlockHandle& block = blocks[block_idx];
    trellis_file::BlockHeader block_header;
    EXPECT_TRUE(trellis_file::BlockHeader::DecodeFrom(data + block.offset, &block_header).ok());
    const uint64_t at = block.offset;
    out << "# Block " << block_idx << ": columns [" << block.first_column << ", "
        << block.first_column + block.column_count << "), " << block.bytes << " bytes\n";
    DumpHexLines(bytes, at, 8, "\"MTBK\", column_count " + std::to_string(block.column_count),
                 &out);
    DumpHexLines(bytes, at + 8, 8, "first_column " + std::to_string(block.first_column), &out);
    DumpHexLines(bytes, at + 16, 8,
                 "neighbour_count " + std::to_string(block_header.neighbour_count) +
                     ", ids_raw_bytes " + std::to_string(block_header.ids_raw_bytes),
                 &out);
    DumpHexLines(bytes, at + 24, 8,
                 "ids_bytes " + std::to_string(block_header.ids_bytes) + ", distances_bytes " +
                     std::to_string(block_header.distances_bytes),
                 &out);
    DumpHexLines(bytes, at + 32, 8, "reserved", &out);
    DumpHexLines(bytes, at + 40, block_header.ids_bytes, "id section: zstd frame", &out);
    DumpHexLines(bytes, at + 40 + block_header.ids_bytes, block_header.distances_bytes,
                 "distance section: zstd frame", &out);
    DumpHexLines(bytes, at + block.bytes - 8, 8,
                 "block checksum: XXH3-64 of the block's first " + std::to_string(block.bytes - 8) +
                     " bytes",
                 &out);
  }
  out << "# Block index (" << blocks.size() << " entries of 40 bytes)\n";
  for (size_t block_idx = 0; block_idx < blocks.size(); ++block_idx) {
    const uint64_t entry = footer.index_offset + block_idx * trellis_file::kBlockEntryBytes;
    DumpHexLines(bytes, entry, 8, "block " + std::to_string(block_idx) + ": offset", &out);
    DumpHexLines(bytes, entry + 8, 8, "bytes", &out);
    DumpHexLines(bytes, entry + 16, 8, "first_column", &out);
    DumpHexLines(bytes, entry + 24, 8, "column_count, neighbour_count", &out);
    DumpHexLines(bytes, entry + 32, 8, "checksum (= the block's trailer)", &out);
  }
  out << "# Footer (64 bytes)\n";
  DumpHexLines(bytes, footer_offset, 8, "magic \"\\x89MTREND\\n\"", &out);
  DumpHexLines(bytes, footer_offset + 8, 8, "format_major 1, format_minor 0, footer_bytes 64",
               &out);
  DumpHexLines(bytes, footer_offset + 16, 8, "index_offset", &out);
  DumpHexLines(bytes, footer_offset + 24, 8, "block_count", &out);
  DumpHexLines(bytes, footer_offset + 32, 8, "neighbour_count", &out);
  DumpHexLines(bytes, footer_offset + 40, 8, "index_checksum: XXH3-64 of the index", &out);
  DumpHexLines(bytes, footer_offset + 48, 8, "header_checksum (copy)", &out);
  DumpHexLines(bytes, footer_offset + 56, 8,
               "footer_checksum: XXH3-64 of the footer's first 56 bytes", &out);
  return out.str();
}

TEST(TrellisFileGolden, TinyTrellisMatchesTheFixtureAndTheSpecHexdump) {
  TempDir dir;
  const std::string written = ReadBytes(WriteTiny(dir));
  ASSERT_FALSE(written.empty());
  if (std::getenv("MOTIF_UPDATE_GOLDEN") != nullptr) {
    WriteBytes(kFixture, written);
    std::printf("%s\n```\n%s```\n%s\n", kGoldenBegin, AnnotatedHexdump(written).c_str(),
                kGoldenEnd);
  }
  EXPECT_EQ(written, ReadBytes(kFixture)) << "the writer's bytes differ from " << kFixture;
  std::string error;
  const std::string from_spec = BytesFromSpecHexdump(kSpec, &error);
  ASSERT_TRUE(error.empty()) << error;
  EXPECT_EQ(written, from_spec) << "the writer's bytes differ from the hexdump in " << kSpec;
}

TEST(TrellisFileGolden, TheFixtureDecodesToTheWorkedExample) {
  auto reader = TrellisFileReader::Open(kFixture);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_TRUE((*reader)->Verify().ok());
  EXPECT_TRUE((*reader)->params() == TinyParams());
  EXPECT_EQ((*reader)->block_count(), 2u);
  EXPECT_EQ((*reader)->neighbour_count(), 13u);
  TrellisColumns columns;
  ASSERT_TRUE((*reader)->ReadColumns(0, 6, &columns).ok());
  ExpectSameWithinBound(TinyColumns(), columns, 1.0f);
  // The values the spec's decoding walk-through arrives at.
  EXPECT_EQ(columns[0][0].distance, static_cast<float>(32768.0 / 65535));  // 0.5: code 0x8000
  EXPECT_EQ(columns[0][2].distance, static_cast<float>(8192.0 / 65535));   // 0.125: 0x2000
  EXPECT_FLOAT_EQ(columns[0][0].distance, 0.50000763f);
  EXPECT_FLOAT_EQ(columns[3][1].distance, 0.74999619f);
  EXPECT_EQ(columns[3][2].distance, 1.0f);  // eps is exact
  EXPECT_EQ(columns[4][1].distance, 0.0f);  // 0 is exact
}

}  // namespace
}  // namespace motif::testing
