#include "formats/frame_file/frame_file_format.h"

#include <cstring>

#include <gtest/gtest.h>

#include "formats/frame_file/archive_metadata.h"
#include "tests/formats/frame_file/frame_file_test_util.h"

namespace motif::frame_file {
namespace {

const uint8_t* Bytes(const std::string& text) {
  return reinterpret_cast<const uint8_t*>(text.data());
}

// Rewrites the u64 at `offset` and recomputes the checksum stored at `checksum_offset` over
// [start, checksum_offset): a structure that is well-formed except for the changed field.
void PatchU64(std::string* bytes, size_t offset, uint64_t value, size_t start,
              size_t checksum_offset) {
  std::string encoded;
  PutU64(&encoded, value);
  bytes->replace(offset, 8, encoded);
  encoded.clear();
  PutU64(&encoded, Checksum64(bytes->data() + start, checksum_offset - start));
  bytes->replace(checksum_offset, 8, encoded);
}

TEST(FrameFileFormat, HeaderRoundTripsAndStartsWithTheMagic) {
  FileHeader header;
  header.slots[1] = {7, 1000, 1064};
  std::string bytes;
  header.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), kHeaderBytes);
  EXPECT_EQ(std::memcmp(bytes.data(), "\x89MFS\r\n\x1a\n", 8), 0);
  FileHeader decoded;
  ASSERT_TRUE(FileHeader::DecodeFixedFrom(Bytes(bytes), bytes.size(), &decoded).ok());
  EXPECT_EQ(decoded.format_major, kFormatMajor);
  EXPECT_EQ(decoded.format_minor, kFormatMinor);
  CommitSlot slot;
  bool is_empty = false;
  ASSERT_TRUE(CommitSlot::DecodeFrom(Bytes(bytes) + kSlotOffsets[0], &slot, &is_empty).ok());
  EXPECT_TRUE(is_empty);
  ASSERT_TRUE(CommitSlot::DecodeFrom(Bytes(bytes) + kSlotOffsets[1], &slot, &is_empty).ok());
  EXPECT_FALSE(is_empty);
  EXPECT_EQ(slot.generation, 7u);
  EXPECT_EQ(slot.footer_offset, 1000u);
  EXPECT_EQ(slot.committed_length, 1064u);
}

TEST(FrameFileFormat, HeaderRejectsBadMagicVersionChecksumAndReserved) {
  FileHeader header;
  std::string good;
  header.EncodeTo(&good);
  FileHeader decoded;

  std::string bad = good;
  bad[1] = 'X';
  Status status = FileHeader::DecodeFixedFrom(Bytes(bad), bad.size(), &decoded);
  EXPECT_TRUE(status.IsCorruption());
  EXPECT_NE(status.message().find("bad magic"), std::string::npos);

  bad = good;
  bad[8] = 2;  // major 2, checksum left as it was: the version is checked first
  status = FileHeader::DecodeFixedFrom(Bytes(bad), bad.size(), &decoded);
  EXPECT_TRUE(status.IsNotSupported());
  EXPECT_NE(status.message().find("major version 2"), std::string::npos) << status.message();

  bad = good;
  bad[10] = 5;  // minor changed without fixing the checksum
  EXPECT_TRUE(FileHeader::DecodeFixedFrom(Bytes(bad), bad.size(), &decoded).IsCorruption());

  bad = good;
  PatchU64(&bad, 24, 1, 0, 40);  // a reserved field, with a matching checksum
  status = FileHeader::DecodeFixedFrom(Bytes(bad), bad.size(), &decoded);
  EXPECT_TRUE(status.IsCorruption());
  EXPECT_NE(status.message().find("reserved"), std::string::npos);

  EXPECT_TRUE(FileHeader::DecodeFixedFrom(Bytes(good), 100, &decoded).IsCorruption());
}

TEST(FrameFileFormat, SlotRejectsChecksumMismatchAndNonZeroReserved) {
  CommitSlot slot{3, 500, 564};
  std::string bytes;
  slot.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), kSlotBytes);
  CommitSlot decoded;
  bool is_empty = true;
  ASSERT_TRUE(CommitSlot::DecodeFrom(Bytes(bytes), &decoded, &is_empty).ok());
  EXPECT_FALSE(is_empty);
  for (size_t byte_idx = 0; byte_idx < kSlotBytes; ++byte_idx) {
    std::string bad = bytes;
    bad[byte_idx] ^= 0x10;
    EXPECT_TRUE(CommitSlot::DecodeFrom(Bytes(bad), &decoded, &is_empty).IsCorruption()) << byte_idx;
  }
  std::string reserved = bytes;
  PatchU64(&reserved, 24, 9, 0, 32);
  EXPECT_TRUE(CommitSlot::DecodeFrom(Bytes(reserved), &decoded, &is_empty).IsCorruption());
}

TEST(FrameFileFormat, FooterRoundTripsAndRejectsDamage) {
  Footer footer;
  footer.generation = 2;
  footer.metadata_offset = 4096;
  footer.metadata_bytes = 333;
  footer.metadata_checksum = 0x1234567890abcdefull;
  std::string bytes;
  footer.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), kFooterBytes);
  Footer decoded;
  ASSERT_TRUE(Footer::DecodeFrom(Bytes(bytes), &decoded).ok());
  EXPECT_EQ(decoded.generation, 2u);
  EXPECT_EQ(decoded.metadata_offset, 4096u);
  EXPECT_EQ(decoded.metadata_bytes, 333u);
  EXPECT_EQ(decoded.metadata_checksum, 0x1234567890abcdefull);
  for (size_t byte_idx = 0; byte_idx < kFooterBytes; ++byte_idx) {
    std::string bad = bytes;
    bad[byte_idx] ^= 0x01;
    EXPECT_TRUE(Footer::DecodeFrom(Bytes(bad), &decoded).IsCorruption()) << byte_idx;
  }
  std::string reserved = bytes;
  PatchU64(&reserved, 48, 1, 0, 56);
  EXPECT_TRUE(Footer::DecodeFrom(Bytes(reserved), &decoded).IsCorruption());
}

ArchiveMetadata SampleMetadata() {
  ArchiveMetadata metadata;
  metadata.fps = 120;
  metadata.joint_count = 3;
  metadata.block_frames = 64;
  metadata.skeleton = testing::MakeSkeleton(3);
  metadata.columns = DefaultColumns(3, ColumnDefaults());
  for (int clip_idx = 0; clip_idx < 2; ++clip_idx) {
    ClipInfo clip = testing::MakeClip(testing::Numbered("clip", clip_idx), 3, 50, clip_idx).info;
    clip.first_frame = 50 * clip_idx;
    metadata.clips.push_back(clip);
  }
  metadata.frame_count = 100;
  metadata.blocks.push_back({kHeaderBytes, 500, 0, 64, 11});
  metadata.blocks.push_back({kHeaderBytes + 500, 400, 64, 36, 22});
  return metadata;
}

constexpr uint64_t kSampleMetadataOffset = 2000;

TEST(FrameFileFormat, MetadataRoundTrips) {
  const ArchiveMetadata metadata = SampleMetadata();
  std::string bytes;
  metadata.EncodeTo(&bytes);
  ArchiveMetadata decoded;
  Status status =
      ArchiveMetadata::DecodeFrom(Bytes(bytes), bytes.size(), kSampleMetadataOffset, &decoded);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(decoded.fps, metadata.fps);
  EXPECT_EQ(decoded.frame_count, metadata.frame_count);
  EXPECT_EQ(decoded.block_frames, metadata.block_frames);
  testing::ExpectSameSkeleton(metadata.skeleton, decoded.skeleton);
  EXPECT_EQ(decoded.columns, metadata.columns);
  ASSERT_EQ(decoded.clips.size(), 2u);
  for (size_t clip_idx = 0; clip_idx < 2; ++clip_idx) {
    testing::ExpectSameClipInfo(metadata.clips[clip_idx], decoded.clips[clip_idx]);
  }
  ASSERT_EQ(decoded.blocks.size(), 2u);
  EXPECT_EQ(decoded.blocks[1].offset, metadata.blocks[1].offset);
  EXPECT_EQ(decoded.blocks[1].checksum, 22u);
}

// Compatibility: a later minor version may add sections and append fields to records and
// entries; this reader skips them.
TEST(FrameFileFormat, MetadataSkipsSectionsAndFieldsAddedByLaterMinorVersions) {
  ArchiveMetadata metadata = SampleMetadata();
  std::string bytes;
  metadata.EncodeTo(&bytes);
  // Append an unknown section (tag 9).
  PutU32(&bytes, 9);
  PutU32(&bytes, 0);
  PutU64(&bytes, 5);
  bytes += "extra";
  ArchiveMetadata decoded;
  ASSERT_TRUE(
      ArchiveMetadata::DecodeFrom(Bytes(bytes), bytes.size(), kSampleMetadataOffset, &decoded)
          .ok());

  // Longer column entries: rebuild the COLUMNS section with 32-byte entries.
  std::string columns_payload;
  PutU32(&columns_payload, static_cast<uint32_t>(metadata.columns.size()));
  PutU32(&columns_payload, 32);
  std::string plain;
  metadata.EncodeTo(&plain);
  // Find the COLUMNS section and copy its entries, padding each with 8 bytes.
  ByteReader reader(Bytes(plain), plain.size());
  std::string rebuilt;
  while (reader.remaining() > 0) {
    uint32_t tag = 0, reserved = 0;
    uint64_t length = 0;
    const uint8_t* payload = nullptr;
    ASSERT_TRUE(reader.GetU32(&tag) && reader.GetU32(&reserved) && reader.GetU64(&length) &&
                reader.GetBytes(length, &payload));
    std::string section(reinterpret_cast<const char*>(payload), length);
    if (tag == static_cast<uint32_t>(SectionTag::kColumns)) {
      for (size_t column_idx = 0; column_idx < metadata.columns.size(); ++column_idx) {
        columns_payload += section.substr(8 + column_idx * kColumnEntryBytes, kColumnEntryBytes);
        columns_payload += std::string(8, '\x7f');
      }
      section = columns_payload;
    }
    PutU32(&rebuilt, tag);
    PutU32(&rebuilt, 0);
    PutU64(&rebuilt, section.size());
    rebuilt += section;
  }
  Status status =
      ArchiveMetadata::DecodeFrom(Bytes(rebuilt), rebuilt.size(), kSampleMetadataOffset, &decoded);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(decoded.columns, metadata.columns);
}

TEST(FrameFileFormat, MetadataRejectsBrokenInvariants) {
  auto expect_corruption = [](const ArchiveMetadata& metadata, const char* what) {
    std::string bytes;
    metadata.EncodeTo(&bytes);
    ArchiveMetadata decoded;
    Status status =
        ArchiveMetadata::DecodeFrom(Bytes(bytes), bytes.size(), kSampleMetadataOffset, &decoded);
    EXPECT_TRUE(status.IsCorruption()) << what << ": " << status.ToString();
  };
  ArchiveMetadata metadata = SampleMetadata();
  metadata.clips[1].first_frame = 49;
  expect_corruption(metadata, "clips overlap");
  metadata = SampleMetadata();
  metadata.clips[1].name = metadata.clips[0].name;
  expect_corruption(metadata, "duplicate clip name");
  metadata = SampleMetadata();
  metadata.frame_count = 101;
  expect_corruption(metadata, "frame count disagrees");
  metadata = SampleMetadata();
  metadata.blocks[1].offset = kHeaderBytes + 499;
  expect_corruption(metadata, "blocks overlap");
  metadata = SampleMetadata();
  metadata.blocks[1].offset = kSampleMetadataOffset - 100;
  expect_corruption(metadata, "block runs into the metadata");
  metadata = SampleMetadata();
  metadata.columns.pop_back();
  expect_corruption(metadata, "a row float has no column");
  metadata = SampleMetadata();
  metadata.columns[0].encoding.delta_order = 5;
  expect_corruption(metadata, "bad encoding");
  metadata = SampleMetadata();
  metadata.skeleton.mutable_joints()[2].parent = 5;
  expect_corruption(metadata, "bad skeleton");
  metadata = SampleMetadata();
  metadata.fps = 0;
  expect_corruption(metadata, "fps 0");
  metadata = SampleMetadata();
  metadata.clips[0].joint_offsets.pop_back();
  expect_corruption(metadata, "joint offsets missing");

  std::string bytes;
  SampleMetadata().EncodeTo(&bytes);
  ArchiveMetadata decoded;
  for (size_t cut = 0; cut < bytes.size(); cut += 7) {
    EXPECT_TRUE(ArchiveMetadata::DecodeFrom(Bytes(bytes), cut, kSampleMetadataOffset, &decoded)
                    .IsCorruption())
        << "cut at " << cut;
  }
}

}  // namespace
}  // namespace motif::frame_file
