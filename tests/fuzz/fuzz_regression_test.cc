// Replays the inputs kept for one fuzz target (tests/data/fuzz/<target>/: every crash a fuzzer
// found, after its fix, and a few seeds) through that target's LLVMFuzzerTestOneInput, in the
// normal build, without libFuzzer. The target aborts on a broken promise (tests/fuzz/
// fuzz_support.h), so a regression fails this test by crashing it; in a sanitizer build a
// memory error does too. One executable per target (tests/fuzz/CMakeLists.txt) keeps the entry
// points apart: MOTIF_FUZZ_SUITE names the suite, MOTIF_FUZZ_INPUT_DIR the folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> KeptInputs() {
  std::vector<fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(MOTIF_FUZZ_INPUT_DIR, error)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(MOTIF_FUZZ_SUITE, ReplaysEveryKeptInput) {
  const std::vector<fs::path> files = KeptInputs();
  ASSERT_FALSE(files.empty()) << "no inputs in " << MOTIF_FUZZ_INPUT_DIR;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::ifstream in(file, std::ios::binary);
    ASSERT_TRUE(in) << "cannot read " << file;
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    // libFuzzer never passes a null pointer, even for an empty input.
    const uint8_t empty = 0;
    EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.empty() ? &empty : bytes.data(), bytes.size()), 0);
  }
}

// The empty input, which every target must also survive.
TEST(MOTIF_FUZZ_SUITE, SurvivesTheEmptyInput) {
  const uint8_t empty = 0;
  EXPECT_EQ(LLVMFuzzerTestOneInput(&empty, 0), 0);
}

}  // namespace
