// The checks shared by the binary formats' readers: each failed check returns its exact Status
// code and message (the formats' corruption tests and specs quote them), the checks run in the
// documented order, and a section's bounds are checked without a product that could wrap.
#include "formats/format_checks/format_checks.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/byte_coding.h"

namespace motif {
namespace {

constexpr std::array<uint8_t, 8> kMagic = {0x89, 'T', 'S', 'T', '\r', '\n', 0x1A, '\n'};

const uint8_t* Bytes(const std::string& text) {
  return reinterpret_cast<const uint8_t*>(text.data());
}

void ExpectCorruption(const Status& status, const std::string& message) {
  EXPECT_TRUE(status.IsCorruption()) << status.ToString();
  EXPECT_EQ(status.message(), message);
}

TEST(CheckMagicAndMajor, ChecksEmptinessMagicLengthAndVersionInThatOrder) {
  std::string file(kMagic.begin(), kMagic.end());
  PutU16(&file, 1);
  EXPECT_TRUE(CheckMagicAndMajor(Bytes(file), file.size(), kMagic.data(), "test file", 1).ok());
  ExpectCorruption(CheckMagicAndMajor(Bytes(file), 0, kMagic.data(), "test file", 1), "empty file");
  ExpectCorruption(CheckMagicAndMajor(Bytes(file), 7, kMagic.data(), "test file", 1),
                   "bad magic at offset 0x0: not a test file");
  ExpectCorruption(CheckMagicAndMajor(Bytes(file), 9, kMagic.data(), "test file", 1),
                   "file of 9 bytes: truncated header");
  std::string other = file;
  other[1] = 'X';
  ExpectCorruption(CheckMagicAndMajor(Bytes(other), other.size(), kMagic.data(), "test file", 1),
                   "bad magic at offset 0x0: not a test file");
  const Status newer = CheckMagicAndMajor(Bytes(file), file.size(), kMagic.data(), "test file", 0);
  EXPECT_TRUE(newer.IsNotSupported()) << newer.ToString();
  EXPECT_EQ(newer.message(), "unsupported format major version 1 (this reader knows 0)");
}

TEST(CheckFileHoldsHeader, RefusesAFileShorterThanItsHeader) {
  EXPECT_TRUE(CheckFileHoldsHeader(96, 96).ok());
  ExpectCorruption(CheckFileHoldsHeader(95, 96),
                   "file of 95 bytes is shorter than the header (96 bytes): truncated");
}

TEST(CheckHeaderChecksum, ComparesTheTrailingChecksumWithTheBytesBeforeIt) {
  std::string header(24, '\x05');
  PutU64(&header, Checksum64(header.data(), header.size()));
  uint64_t stored = 0;
  EXPECT_TRUE(CheckHeaderChecksum(Bytes(header), header.size(), &stored).ok());
  EXPECT_EQ(stored, Checksum64(header.data(), 24));
  header[3] = '\x06';
  ExpectCorruption(CheckHeaderChecksum(Bytes(header), header.size(), &stored),
                   "header at offset 0x0: checksum mismatch (stored at 0x18)");
  EXPECT_EQ(stored, Checksum64(std::string(24, '\x05').data(), 24));  // set even when it fails
}

// A 64-byte footer frame: magic, major, minor 3, size, 40 bytes of fields, checksum.
std::string Footer(uint16_t major, uint32_t size_field) {
  std::string footer(kMagic.begin(), kMagic.end());
  PutU16(&footer, major);
  PutU16(&footer, 3);
  PutU32(&footer, size_field);
  for (int field = 0; field < 5; ++field) PutU64(&footer, 1000 + field);
  PutU64(&footer, Checksum64(footer.data(), footer.size()));
  return footer;
}

constexpr FooterFrame kFrame{kMagic, 1, 64, "bad footer magic (not a test footer?)"};

TEST(CheckFooterFrame, AcceptsAWholeFooterAndReadsItsVersion) {
  const std::string footer = Footer(1, 64);
  ASSERT_EQ(footer.size(), 64u);
  uint16_t major = 0;
  uint16_t minor = 0;
  EXPECT_TRUE(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor).ok());
  EXPECT_EQ(major, 1);
  EXPECT_EQ(minor, 3);
}

TEST(CheckFooterFrame, ChecksMagicChecksumVersionAndSizeInThatOrder) {
  uint16_t major = 0;
  uint16_t minor = 0;
  // Every check fails here: the magic is reported.
  std::string footer = Footer(2, 65);
  footer[0] = 'x';
  ExpectCorruption(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor),
                   "bad footer magic (not a test footer?)");
  footer = Footer(1, 64);
  footer[20] ^= 1;  // a field
  ExpectCorruption(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor),
                   "footer checksum mismatch");
  footer = Footer(1, 64);
  footer[63] ^= 1;  // the checksum itself
  ExpectCorruption(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor),
                   "footer checksum mismatch");
  footer = Footer(2, 65);  // checksum right: the version is reported before the size
  ExpectCorruption(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor),
                   "footer has unsupported format major version 2");
  EXPECT_EQ(major, 2);  // read before it is checked
  footer = Footer(1, 65);
  ExpectCorruption(CheckFooterFrame(Bytes(footer), kFrame, &major, &minor),
                   "footer size 65, expected 64");
  const FooterFrame plain{kMagic, 1, 64};
  footer[0] = 'x';
  ExpectCorruption(CheckFooterFrame(Bytes(footer), plain, &major, &minor), "bad footer magic");
}

TEST(SectionEndsAt, ASectionOfBytesEndsExactlyAtTheNextStructure) {
  EXPECT_TRUE(SectionEndsAt(100, 20, 1, 50, 120));
  EXPECT_TRUE(SectionEndsAt(120, 0, 1, 50, 120));   // empty, right before the footer
  EXPECT_TRUE(SectionEndsAt(50, 70, 1, 50, 120));   // right after the header
  EXPECT_FALSE(SectionEndsAt(49, 71, 1, 50, 120));  // inside the header
  EXPECT_FALSE(SectionEndsAt(121, 0, 1, 50, 120));  // after the footer's start
  EXPECT_FALSE(SectionEndsAt(100, 19, 1, 50, 120));
  EXPECT_FALSE(SectionEndsAt(100, 21, 1, 50, 120));
  // After the end, with a size that wraps: offset + size is 120 in u64 arithmetic.
  EXPECT_FALSE(SectionEndsAt(200, UINT64_MAX - 79, 1, 0, 120));
}

TEST(SectionEndsAt, ASectionOfEntriesHoldsExactlyItsCount) {
  EXPECT_TRUE(SectionEndsAt(0, 3, 40, 0, 120));
  EXPECT_TRUE(SectionEndsAt(120, 0, 40, 0, 120));
  EXPECT_FALSE(SectionEndsAt(0, 3, 40, 0, 121));  // a partial entry
  EXPECT_FALSE(SectionEndsAt(0, 2, 40, 0, 120));
  // 2^61 entries of 40 bytes are 5 x 2^64 bytes: a product would wrap to 0 and match an empty
  // section.
  EXPECT_FALSE(SectionEndsAt(120, uint64_t{1} << 61, 40, 0, 120));
}

}  // namespace
}  // namespace motif
