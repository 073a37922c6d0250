// Golden bytes: the tiny archive of the spec's worked example (docs/formats/frame_file.md,
// "Worked example") is written and compared byte for byte with the fixture
// tests/data/frame_file/tiny.mfs.golden (not *.mfs, which .gitignore excludes) and with the
// hexdump in the spec, so the document, the fixture and the code cannot drift apart. After an
// intended format change, regenerate both with
//   MOTIF_UPDATE_GOLDEN=1 ./frame_file_test --gtest_filter='FrameFileGolden.*'
// which rewrites the fixture and prints the annotated hexdump to paste into the spec.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/testing/golden_hexdump.h"

#include "formats/frame_file/archive_loader.h"
#include "formats/frame_file/frame_file_format.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/formats/frame_file/frame_file_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

const std::string kSourceDir = MOTIF_SOURCE_DIR;
const std::string kFixture = kSourceDir + "/tests/data/frame_file/tiny.mfs.golden";
const std::string kSpec = kSourceDir + "/docs/formats/frame_file.md";

// The worked example: one joint, 30 fps, one clip of 3 frames, blocks of 2 frames.
std::string WriteTinyArchive(const TempDir& dir) {
  Joint root;
  root.name = "root";
  root.parent = -1;
  root.offset = {0, 0, 0};
  root.has_end_site = true;
  root.end_site = {0, 1, 0};
  root.channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition,
                   ChannelType::kZRotation, ChannelType::kXRotation, ChannelType::kYRotation};
  root.weight = 1.0f;
  const Skeleton skeleton("custom", {root});

  ClipFrames clip;
  clip.info.name = "t";
  clip.info.source_path = "t.bvh";
  clip.info.frame_count = 3;
  clip.info.fps = 30;
  clip.info.source_fps = 120;
  clip.info.meters_per_unit = 0.01;
  clip.info.content_hash = 0x0123456789abcdefull;
  clip.info.start_position = {1, 2, 3};
  clip.info.joint_offsets = {{0.0f, 0.0f, 0.0f}};
  clip.info.end_sites = {{0.0f, 1.0f, 0.0f}};
  // Row: w x y z | height | velocity x z | heading. A turn about Y by 0, 0.1 and 0.2 rad.
  for (int frame_idx = 0; frame_idx < 3; ++frame_idx) {
    const double angle = 0.1 * frame_idx;
    const std::vector<float> row = {static_cast<float>(std::cos(angle / 2)),
                                    0.0f,
                                    static_cast<float>(std::sin(angle / 2)),
                                    0.0f,
                                    0.9f + 0.01f * frame_idx,
                                    0.0f,
                                    1.5f,
                                    0.0125f * frame_idx};
    clip.rows.insert(clip.rows.end(), row.begin(), row.end());
  }
  FrameFileWriterOptions options;
  options.block_frames = 2;
  const std::string path = dir.File("tiny.mfs");
  WriteArchive(path, skeleton, {clip}, options, 30.0);
  return path;
}

// The annotated hexdump of the spec's worked example.
std::string AnnotatedHexdump(const std::string& bytes) {
  auto loaded = frame_file::LoadArchive("tiny.mfs", reinterpret_cast<const uint8_t*>(bytes.data()),
                                        bytes.size());
  EXPECT_TRUE(loaded.ok());
  if (!loaded.ok()) return "";
  const frame_file::ArchiveMetadata& metadata = loaded->metadata;
  std::ostringstream out;
  out << "# File header (128 bytes)\n";
  DumpHexLines(bytes, 0, 8, "magic \"\\x89MFS\\r\\n\\x1a\\n\"", &out);
  DumpHexLines(bytes, 8, 8, "format_major 1, format_minor 0, header_bytes 128", &out);
  DumpHexLines(bytes, 16, 24, "reserved (3 x u64, zero)", &out);
  DumpHexLines(bytes, 40, 8, "header_checksum: XXH3-64 of bytes [0x00, 0x28)", &out);
  DumpHexLines(bytes, 48, 8, "slot 0: generation 1", &out);
  DumpHexLines(bytes, 56, 8, "slot 0: footer_offset", &out);
  DumpHexLines(bytes, 64, 8, "slot 0: committed_length", &out);
  DumpHexLines(bytes, 72, 8, "slot 0: reserved", &out);
  DumpHexLines(bytes, 80, 8, "slot 0: checksum of [0x30, 0x48)", &out);
  DumpHexLines(bytes, 88, 40, "slot 1: empty (all zero)", &out);
  for (size_t block_idx = 0; block_idx < metadata.blocks.size(); ++block_idx) {
    const frame_file::BlockHandle& block = metadata.blocks[block_idx];
    out << "# Block " << block_idx << ": frames [" << block.first_frame << ", "
        << block.first_frame + block.frame_count << "), " << block.bytes << " bytes\n";
    DumpHexLines(bytes, block.offset, 8, "\"MFBK\", column_count 4", &out);
    DumpHexLines(bytes, block.offset + 8, 8, "first_frame", &out);
    DumpHexLines(bytes, block.offset + 16, 8, "frame_count, reserved", &out);
    size_t chunk_offset = block.offset + frame_file::kBlockHeaderBytes +
                          frame_file::kChunkEntryBytes * metadata.columns.size();
    std::vector<uint32_t> chunk_bytes;
    static const char* kColumnNames[] = {"root quaternion", "height", "velocity", "heading"};
    for (size_t column_idx = 0; column_idx < metadata.columns.size(); ++column_idx) {
      const size_t entry =
          block.offset + frame_file::kBlockHeaderBytes + frame_file::kChunkEntryBytes * column_idx;
      frame_file::ByteReader reader(reinterpret_cast<const uint8_t*>(bytes.data()) + entry, 8);
      uint32_t compressed = 0, raw = 0;
      reader.GetU32(&compressed);
      reader.GetU32(&raw);
      chunk_bytes.push_back(compressed);
      DumpHexLines(bytes, entry, 8,
                   "chunk " + std::to_string(column_idx) + " (" + kColumnNames[column_idx] +
                       "): " + std::to_string(compressed) + " bytes, raw " + std::to_string(raw),
                   &out);
    }
    for (size_t column_idx = 0; column_idx < metadata.columns.size(); ++column_idx) {
      DumpHexLines(bytes, chunk_offset, chunk_bytes[column_idx],
                   "chunk " + std::to_string(column_idx) + ": zstd frame", &out);
      chunk_offset += chunk_bytes[column_idx];
    }
  }
  const frame_file::Footer& footer = loaded->footer;
  out << "# Metadata (" << footer.metadata_bytes << " bytes)\n";
  static const char* kSectionNames[] = {"", "ARCHIVE", "SKELETON", "COLUMNS", "CLIPS", "BLOCKS"};
  frame_file::ByteReader reader(
      reinterpret_cast<const uint8_t*>(bytes.data()) + footer.metadata_offset,
      footer.metadata_bytes);
  while (reader.remaining() > 0) {
    const size_t section = footer.metadata_offset + reader.position();
    uint32_t tag = 0, reserved = 0;
    uint64_t length = 0;
    reader.GetU32(&tag);
    reader.GetU32(&reserved);
    reader.GetU64(&length);
    reader.Skip(length);
    DumpHexLines(bytes, section, 16,
                 std::string("section ") + kSectionNames[tag] + ": tag " + std::to_string(tag) +
                     ", reserved, payload_bytes " + std::to_string(length),
                 &out);
    if (tag == 3) {  // COLUMNS: one line per entry
      DumpHexLines(bytes, section + 16, 8, "column_count 4, entry_bytes 24", &out);
      for (size_t column_idx = 0; column_idx < 4; ++column_idx) {
        DumpHexLines(bytes, section + 24 + 24 * column_idx, 24,
                     "column " + std::to_string(column_idx) + " entry", &out);
      }
    } else {
      DumpHexLines(bytes, section + 16, length, std::string(kSectionNames[tag]) + " payload", &out);
    }
  }
  out << "# Footer (64 bytes)\n";
  const size_t footer_offset = loaded->slot.footer_offset;
  DumpHexLines(bytes, footer_offset, 8, "magic \"\\x89MFSEND\\n\"", &out);
  DumpHexLines(bytes, footer_offset + 8, 8, "format_major 1, format_minor 0, footer_bytes 64",
               &out);
  DumpHexLines(bytes, footer_offset + 16, 8, "generation 1", &out);
  DumpHexLines(bytes, footer_offset + 24, 8, "metadata_offset", &out);
  DumpHexLines(bytes, footer_offset + 32, 8, "metadata_bytes", &out);
  DumpHexLines(bytes, footer_offset + 40, 8, "metadata_checksum", &out);
  DumpHexLines(bytes, footer_offset + 48, 8, "reserved", &out);
  DumpHexLines(bytes, footer_offset + 56, 8,
               "footer_checksum: XXH3-64 of the footer's first 56 bytes", &out);
  return out.str();
}

TEST(FrameFileGolden, TinyArchiveMatchesTheFixtureAndTheSpecHexdump) {
  TempDir dir;
  const std::string written = ReadBytes(WriteTinyArchive(dir));
  ASSERT_FALSE(written.empty());
  if (std::getenv("MOTIF_UPDATE_GOLDEN") != nullptr) {
    WriteBytes(kFixture, written);
    std::printf("%s\n%s%s\n", kGoldenBegin, AnnotatedHexdump(written).c_str(), kGoldenEnd);
  }
  EXPECT_EQ(written, ReadBytes(kFixture)) << "the writer's bytes differ from " << kFixture;
  std::string error;
  const std::string from_spec = BytesFromSpecHexdump(kSpec, &error);
  ASSERT_TRUE(error.empty()) << error;
  EXPECT_EQ(written, from_spec) << "the writer's bytes differ from the hexdump in " << kSpec;
}

TEST(FrameFileGolden, TheFixtureDecodesToTheWorkedExample) {
  auto reader = FrameFileReader::Open(kFixture);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_TRUE((*reader)->Verify().ok());
  EXPECT_EQ((*reader)->fps(), 30.0);
  ASSERT_EQ((*reader)->clips().size(), 1u);
  EXPECT_EQ((*reader)->clips()[0].name, "t");
  EXPECT_EQ((*reader)->summary().block_count, 2u);
  std::vector<float> rows;
  ASSERT_TRUE((*reader)->ReadFrames(0, 3, &rows).ok());
  ASSERT_EQ(rows.size(), 24u);
  // The values the spec's decoding walk-through arrives at.
  EXPECT_FLOAT_EQ(rows[4], 0.9f);         // height, frame 0: 9000 * 1e-4
  EXPECT_FLOAT_EQ(rows[8 + 4], 0.91f);    // height, frame 1: 9100 * 1e-4
  EXPECT_FLOAT_EQ(rows[16 + 7], 0.025f);  // heading, frame 2: 2500 * 1e-5
  EXPECT_EQ(rows[6], 1.5f);               // velocity z: 1500 * 1e-3
}

}  // namespace
}  // namespace motif::testing
