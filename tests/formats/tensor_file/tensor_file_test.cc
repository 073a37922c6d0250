// The tensor file (docs/formats/tensor_file.md): round trips, the golden bytes of the spec's
// worked example, and corruption (every flipped byte, truncation, appended bytes, another major
// version, another kind). After an intended format change, print the new hexdump to paste into
// the spec with
//   MOTIF_UPDATE_GOLDEN=1 ./tensor_file_test --gtest_filter='TensorFileGolden.*'
#include "formats/tensor_file/tensor_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "formats/tensor_file/tensor_file_format.h"
#include "tests/testing/byte_files.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/golden_hexdump.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

const std::string kSpec = std::string(MOTIF_SOURCE_DIR) + "/docs/formats/tensor_file.md";

// The spec's worked example: two motifs of two dimensions and their sizes.
TensorFile ExampleFile() {
  TensorFile file("motifs");
  const float centroids[4] = {1.0f, -2.0f, 0.5f, 0.25f};
  file.AddF32Matrix("centroids", 2, 2, centroids);
  const uint64_t sizes[2] = {3, 5};
  file.AddU64("cluster.sizes", sizes);
  const uint16_t ids[3] = {1, 0, 1};
  file.AddU16("word.motifs", ids);
  return file;
}

std::string AnnotatedHexdump(const std::string& bytes) {
  std::ostringstream out;
  out << "```\n# Header (64 bytes)\n";
  DumpHexLines(bytes, 0x00, 8, "magic \"\\x89MWT\\r\\n\\x1a\\n\"", &out);
  DumpHexLines(bytes, 0x08, 8, "format_major 1, format_minor 0, header_bytes 64", &out);
  DumpHexLines(bytes, 0x10, 16, "kind \"motifs\", NUL-padded", &out);
  DumpHexLines(bytes, 0x20, 8, "tensor_count 3, flags 0", &out);
  DumpHexLines(bytes, 0x28, 8, "data_bytes 38", &out);
  DumpHexLines(bytes, 0x30, 8, "table_checksum: XXH3-64 of bytes [0x40, 0x130)", &out);
  DumpHexLines(bytes, 0x38, 8, "header_checksum: XXH3-64 of bytes [0x00, 0x38)", &out);
  const char* names[3] = {"\"centroids\"", "\"cluster.sizes\"", "\"word.motifs\""};
  const char* shapes[3] = {"type 5 (f32), rank 2, reserved 0", "type 4 (u64), rank 1, reserved 0",
                           "type 2 (u16), rank 1, reserved 0"};
  const char* dims[3] = {"rows 2, cols 2", "rows 2, cols 1", "rows 3, cols 1"};
  const char* place[3] = {"offset 0x130, bytes 16", "offset 0x140, bytes 16",
                          "offset 0x150, bytes 6"};
  for (size_t idx = 0; idx < 3; ++idx) {
    const size_t entry = 0x40 + idx * 80;
    out << "# Table entry " << idx << " (80 bytes)\n";
    DumpHexLines(bytes, entry, 32, std::string("name ") + names[idx], &out);
    DumpHexLines(bytes, entry + 32, 8, shapes[idx], &out);
    DumpHexLines(bytes, entry + 40, 16, dims[idx], &out);
    DumpHexLines(bytes, entry + 56, 16, place[idx], &out);
    DumpHexLines(bytes, entry + 72, 8, "checksum: XXH3-64 of the tensor's bytes", &out);
  }
  out << "# Data (38 bytes)\n";
  DumpHexLines(bytes, 0x130, 16, "centroids: 1.0, -2.0, 0.5, 0.25 (f32)", &out);
  DumpHexLines(bytes, 0x140, 16, "cluster.sizes: 3, 5 (u64)", &out);
  DumpHexLines(bytes, 0x150, 6, "word.motifs: 1, 0, 1 (u16); the file ends here", &out);
  out << "```\n";
  return out.str();
}

TEST(TensorFileGolden, TheSpecsHexdumpIsTheEncodedExample) {
  auto bytes = EncodeTensorFile(ExampleFile());
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  ExpectSpecHexdump(kSpec, AnnotatedHexdump(*bytes), *bytes);
}

TEST(TensorFile, RoundTripsEveryTypeAndShape) {
  TempDir dir;
  TensorFile file("signatures");
  const uint8_t u8[3] = {1, 2, 255};
  const uint32_t u32[2] = {7, 4000000000u};
  const float f32[1] = {-0.0f};
  const double f64[6] = {1, 2, 3, 4, 5, 6.5};
  file.AddU8("a", u8);
  file.AddU32("b.c", u32);
  file.AddF32("empty", std::span<const float>());
  file.AddF32("f", f32);
  file.AddF64Matrix("m_2x3", 2, 3, f64);
  file.AddString("text", "hello");
  uint64_t written_identity = 0;
  ASSERT_TRUE(WriteTensorFile(dir.File("t.mws"), file, PosixFileSystem(), &written_identity).ok());
  auto read = ReadTensorFile(dir.File("t.mws"), "signatures");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->identity(), written_identity);
  EXPECT_EQ(read->kind(), "signatures");
  EXPECT_EQ(*read->U8("a"), std::vector<uint8_t>(u8, u8 + 3));
  EXPECT_EQ(*read->U32("b.c", 2), std::vector<uint32_t>(u32, u32 + 2));
  EXPECT_TRUE(read->F32("empty", 0)->empty());
  EXPECT_TRUE(std::signbit((*read->F32("f"))[0]));
  EXPECT_EQ(*read->F64Matrix("m_2x3", 2, 3), std::vector<double>(f64, f64 + 6));
  EXPECT_EQ(*read->String("text"), "hello");
  // Typed reads check type and shape.
  EXPECT_TRUE(read->F32("a").status().IsCorruption());
  EXPECT_TRUE(read->U32("b.c", 3).status().IsCorruption());
  EXPECT_TRUE(read->F64Matrix("m_2x3", 3, 2).status().IsCorruption());
  EXPECT_TRUE(read->F64("m_2x3").status().IsCorruption());
  EXPECT_TRUE(read->U8("missing").status().IsCorruption());
  EXPECT_NE(read->U8("missing").status().message().find("'missing'"), std::string::npos);
  // Another kind is refused; a different content has a different identity.
  EXPECT_TRUE(ReadTensorFile(dir.File("t.mws"), "motifs").status().IsInvalidArgument());
  file.AddU8("z", u8);
  uint64_t other_identity = 0;
  ASSERT_TRUE(EncodeTensorFile(file, &other_identity).ok());
  EXPECT_NE(other_identity, written_identity);
  EXPECT_TRUE(ReadTensorFile(dir.File("none.mws")).status().IsNotFound());
}

TEST(TensorFile, RefusesBadNamesKindsAndDuplicates) {
  const uint8_t byte[1] = {0};
  TensorFile upper("motifs");
  upper.AddU8("Bad", byte);
  EXPECT_TRUE(EncodeTensorFile(upper).status().IsInvalidArgument());
  TensorFile long_name("motifs");
  long_name.AddU8(std::string(32, 'a'), byte);
  EXPECT_TRUE(EncodeTensorFile(long_name).status().IsInvalidArgument());
  TensorFile fine("motifs");
  fine.AddU8(std::string(31, 'a'), byte);
  EXPECT_TRUE(EncodeTensorFile(fine).ok());
  EXPECT_TRUE(EncodeTensorFile(TensorFile("")).status().IsInvalidArgument());
  EXPECT_TRUE(EncodeTensorFile(TensorFile("a kind")).status().IsInvalidArgument());
  Tensor bad;
  bad.name = "x";
  bad.type = TensorType::kF32;
  bad.rows = 3;
  bad.data = std::string(8, '\0');  // 2 floats for 3
  TensorFile wrong_size("motifs");
  wrong_size.Add(bad);
  EXPECT_TRUE(EncodeTensorFile(wrong_size).status().IsInvalidArgument());
}

class TensorFileCorruptionTest : public ::testing::Test {
 protected:
  void SetUp() override { bytes_ = *EncodeTensorFile(ExampleFile()); }
  void ExpectCorruption(const std::string& bytes, const std::string& what) {
    auto file = DecodeTensorFile(bytes, "damaged.mwm");
    EXPECT_FALSE(file.ok()) << what;
    if (!file.ok()) {
      // A damaged major version reads as a future one (NotSupported, exit 15).
      EXPECT_TRUE(file.status().IsCorruption() || file.status().IsNotSupported())
          << what << ": " << file.status().ToString();
      EXPECT_NE(file.status().message().find("damaged.mwm"), std::string::npos) << what;
    }
  }
  std::string bytes_;
};

TEST_F(TensorFileCorruptionTest, RejectsEveryFlippedByte) {
  ForEachFlippedByte(bytes_, [&](const std::string& damaged, const std::string& what) {
    ExpectCorruption(damaged, what);
  });
}

TEST_F(TensorFileCorruptionTest, RejectsTruncationAppendedBytesAndAnotherMajorVersion) {
  for (size_t size = 0; size < bytes_.size(); ++size) {
    ExpectCorruption(bytes_.substr(0, size), "truncated to " + std::to_string(size));
    if (HasFailure()) return;
  }
  ExpectCorruption(bytes_ + std::string(1, '\0'), "one byte appended");
  std::string v2 = bytes_;
  v2[8] = 2;
  auto file = DecodeTensorFile(v2, "v2.mwm");
  ASSERT_FALSE(file.ok());
  EXPECT_NE(file.status().message().find("major version 2"), std::string::npos)
      << file.status().ToString();
  std::string paths = bytes_;
  paths.replace(0, 4, "\x89MPA");
  ExpectCorruption(paths, "a paths file's magic");
}

TEST(TensorFile, AFailedWriteLeavesThePreviousFile) {
  TempDir dir;
  const std::string path = dir.File("m.mwm");
  ASSERT_TRUE(WriteTensorFile(path, ExampleFile()).ok());
  const std::string before = ReadBytes(path);
  TensorFile bigger = ExampleFile();
  const float more[2] = {1, 2};
  bigger.AddF32("more", more);
  const std::string after = *EncodeTensorFile(bigger);
  int failures = 0;
  for (int step = 0; step < 8; ++step) {
    FaultInjectingFileSystem faulty(PosixFileSystem());
    faulty.FailAt(step);
    const Status status = WriteTensorFile(path, bigger, &faulty);
    const std::string now = ReadBytes(path);
    // Never a half-written file: the old one, or (a failure after the rename) the new one.
    EXPECT_TRUE(now == before || now == after) << "failing step " << step;
    if (!status.ok()) {
      ++failures;
      ASSERT_TRUE(WriteTensorFile(path, ExampleFile()).ok());
    }
  }
  EXPECT_GE(failures, 3);
}

}  // namespace
}  // namespace motif::testing
