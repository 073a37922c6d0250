// The on-disk structures alone (formats/trellis_file/trellis_file_format.h): exact sizes, round
// trips, and rejection of bad magic, versions, sizes and non-zero reserved fields.
#include "formats/trellis_file/trellis_file_format.h"

#include <gtest/gtest.h>

#include "tests/formats/trellis_file/trellis_test_util.h"

namespace motif::testing {
namespace {

using trellis_file::BlockHandle;
using trellis_file::BlockHeader;
using trellis_file::FileHeader;
using trellis_file::Footer;

const uint8_t* Bytes(const std::string& bytes) {
  return reinterpret_cast<const uint8_t*>(bytes.data());
}

// Re-seals a header after a change: its checksum is its last 8 bytes.
void Reseal(std::string* header) {
  const size_t body = header->size() - 8;
  const uint64_t checksum = trellis_file::Checksum64(header->data(), body);
  header->resize(body);
  trellis_file::PutU64(header, checksum);
}

TEST(TrellisFileFormat, HeaderRoundTripsWithItsParams) {
  FileHeader header;
  header.block_columns = 4096;
  header.params = MakeParams(123456, 1000);
  std::string bytes;
  header.EncodeTo(&bytes);
  EXPECT_EQ(bytes.size(), trellis_file::kHeaderFixedBytes + trellis_file::kParamsFixedBytes +
                              header.params.search_params.size() + 8);
  FileHeader decoded;
  uint64_t header_bytes = 0;
  ASSERT_TRUE(FileHeader::DecodeFrom(Bytes(bytes), bytes.size(), &decoded, &header_bytes).ok());
  EXPECT_EQ(header_bytes, bytes.size());
  EXPECT_EQ(decoded.block_columns, 4096u);
  EXPECT_TRUE(decoded.params == header.params);
}

TEST(TrellisFileFormat, HeaderSkipsParamsFieldsOfALaterMinorVersion) {
  FileHeader header;
  header.block_columns = 16;
  header.params = MakeParams(10);
  std::string bytes;
  header.EncodeTo(&bytes);
  // A 1.1 writer appends 8 bytes of a new field to the params.
  bytes.resize(bytes.size() - 8);
  bytes.insert(bytes.size(), 8, '\x07');
  const uint32_t params_bytes = trellis_file::LoadU32(Bytes(bytes) + 20) + 8;
  std::string patched;
  trellis_file::PutU32(&patched, static_cast<uint32_t>(bytes.size() + 8));
  bytes.replace(12, 4, patched);
  patched.clear();
  trellis_file::PutU32(&patched, params_bytes);
  bytes.replace(20, 4, patched);
  bytes[10] = 1;  // format_minor
  bytes.resize(bytes.size() + 8);
  Reseal(&bytes);
  FileHeader decoded;
  uint64_t header_bytes = 0;
  const Status status = FileHeader::DecodeFrom(Bytes(bytes), bytes.size(), &decoded, &header_bytes);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(decoded.format_minor, 1);
  EXPECT_TRUE(decoded.params == header.params);
}

TEST(TrellisFileFormat, HeaderRejectsNonZeroReservedFieldsAndBadValues) {
  FileHeader header;
  header.block_columns = 16;
  header.params = MakeParams(10);
  std::string good;
  header.EncodeTo(&good);
  FileHeader decoded;
  uint64_t header_bytes = 0;
  const auto expect_corruption = [&](std::string bytes, const std::string& what) {
    Reseal(&bytes);
    const Status status =
        FileHeader::DecodeFrom(Bytes(bytes), bytes.size(), &decoded, &header_bytes);
    EXPECT_TRUE(status.IsCorruption()) << what << ": " << status.ToString();
  };
  std::string bytes = good;
  bytes[0x18] = 1;
  expect_corruption(bytes, "reserved");
  bytes = good;
  bytes[0x10] = 0;
  bytes[0x11] = 0;
  expect_corruption(bytes, "block_columns 0");
  bytes = good;
  bytes.replace(0x20 + 16, 4, std::string("\0\0\0\0", 4));
  expect_corruption(bytes, "eps 0");
  bytes = good;
  bytes.replace(0x20 + 28, 4, std::string("\0\0\0\0", 4));
  expect_corruption(bytes, "k_max 0");
  bytes = good;
  bytes[0x20 + 4] = 2;  // frame_count 2^33 + 10
  expect_corruption(bytes, "frame_count above 2^32");
  bytes = good;
  bytes[0x20 + 56] = static_cast<char>(0xff);  // search_params length past the params
  expect_corruption(bytes, "string length");
  bytes = good;
  bytes[12] = static_cast<char>(bytes[12] + 1);  // header_bytes disagrees with params_bytes
  expect_corruption(bytes, "header size");
  // Not resealed: a checksum mismatch.
  bytes = good;
  bytes[0x30] ^= 1;
  EXPECT_TRUE(
      FileHeader::DecodeFrom(Bytes(bytes), bytes.size(), &decoded, &header_bytes).IsCorruption());
}

TEST(TrellisFileFormat, FooterRoundTripsAndChecksItself) {
  Footer footer;
  footer.index_offset = 0x1234;
  footer.block_count = 7;
  footer.neighbour_count = 99999;
  footer.index_checksum = 0xabcdef;
  footer.header_checksum = 0x123456;
  std::string bytes;
  footer.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), trellis_file::kFooterBytes);
  Footer decoded;
  ASSERT_TRUE(Footer::DecodeFrom(Bytes(bytes), &decoded).ok());
  EXPECT_EQ(decoded.index_offset, 0x1234u);
  EXPECT_EQ(decoded.block_count, 7u);
  EXPECT_EQ(decoded.neighbour_count, 99999u);
  EXPECT_EQ(decoded.index_checksum, 0xabcdefu);
  EXPECT_EQ(decoded.header_checksum, 0x123456u);
  for (size_t byte_idx = 0; byte_idx < bytes.size(); ++byte_idx) {
    std::string damaged = bytes;
    damaged[byte_idx] ^= 4;
    EXPECT_TRUE(Footer::DecodeFrom(Bytes(damaged), &decoded).IsCorruption()) << byte_idx;
  }
}

TEST(TrellisFileFormat, BlockHeaderAndHandleHaveTheirSpecifiedSizes) {
  BlockHeader header;
  header.column_count = 3;
  header.first_column = 1ull << 33;
  header.neighbour_count = 5;
  header.ids_raw_bytes = 6;
  header.ids_bytes = 7;
  header.distances_bytes = 8;
  std::string bytes;
  header.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), trellis_file::kBlockHeaderBytes);
  EXPECT_EQ(header.block_bytes(), 40u + 7 + 8 + 8);
  BlockHeader decoded;
  ASSERT_TRUE(BlockHeader::DecodeFrom(Bytes(bytes), &decoded).ok());
  EXPECT_EQ(decoded.first_column, 1ull << 33);
  EXPECT_EQ(decoded.distances_bytes, 8u);
  bytes[33] = 1;
  EXPECT_TRUE(BlockHeader::DecodeFrom(Bytes(bytes), &decoded).IsCorruption());
  bytes[0] = 'X';
  EXPECT_TRUE(BlockHeader::DecodeFrom(Bytes(bytes), &decoded).IsCorruption());

  BlockHandle handle;
  handle.offset = 1;
  handle.bytes = 2;
  handle.first_column = 3;
  handle.column_count = 4;
  handle.neighbour_count = 5;
  handle.checksum = 6;
  bytes.clear();
  handle.EncodeTo(&bytes);
  ASSERT_EQ(bytes.size(), trellis_file::kBlockEntryBytes);
  const BlockHandle back = BlockHandle::DecodeFrom(Bytes(bytes));
  EXPECT_EQ(back.offset, 1u);
  EXPECT_EQ(back.neighbour_count, 5u);
  EXPECT_EQ(back.checksum, 6u);
}

TEST(TrellisFileFormat, ParamsEqualityComparesFloatsByTheirBits) {
  TrellisParams a = MakeParams(10);
  TrellisParams b = a;
  EXPECT_TRUE(a == b);
  b.mu = -0.0f;
  a.mu = 0.0f;
  EXPECT_FALSE(a == b);
}

}  // namespace
}  // namespace motif::testing
