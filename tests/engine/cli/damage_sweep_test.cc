// Every byte of the header, the metadata and the footers of a two-commit archive flipped in turn,
// and the tool run on it as a user would: `verify` and `info` on every flip, `mine` and a
// following `import` on the flips of each range's first and last 16 bytes and of every 5th byte
// between (5: prime to the shard count, so each shard gets its share; they open the archive
// through the reader and older-version policy `info` uses, and running them on every byte was
// four fifths of the sweep's time). Each works on the newest version, intact, or refuses with a
// damage code, and no commit that verified before the flip is lost. (The frame blocks are swept
// by FrameFileCorruption.DetectsEveryFlipped* in tests/formats/frame_file.)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "formats/frame_file/frame_file_format.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunTool;

constexpr int kShards = 4;  // ctest runs them side by side

// A two-joint BVH take of `frames` frames: a swaying chest, `phase` apart between takes.
std::string SwayingTake(double phase, int frames) {
  std::string text =
      "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Xrotation Yrotation\n  JOINT Chest\n  {\n    OFFSET 0 10 0\n    CHANNELS 3 "
      "Zrotation Xrotation Yrotation\n    End Site\n    {\n      OFFSET 0 10 0\n    }\n  }\n}\n"
      "MOTION\nFrames: " +
      std::to_string(frames) + "\nFrame Time: 0.0083333\n";
  for (int f = 0; f < frames; ++f) {
    const double angle = 30 * std::sin(2 * M_PI * f / 80 + phase);
    char line[128];
    std::snprintf(line, sizeof line, "%.3f 90 0 0 %.3f 0 0 %.3f 0\n", f * 0.1, angle, angle / 2);
    text += line;
  }
  return text;
}

// [begin, end) byte ranges of the header and of each commit's metadata and footer.
std::vector<std::pair<size_t, size_t>> MetadataRanges(const std::string& bytes) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  std::vector<std::pair<size_t, size_t>> ranges = {{0, frame_file::kHeaderBytes}};
  for (size_t offset : frame_file::kSlotOffsets) {
    frame_file::CommitSlot slot;
    bool empty = false;
    EXPECT_TRUE(frame_file::CommitSlot::DecodeFrom(data + offset, &slot, &empty).ok());
    frame_file::Footer footer;
    EXPECT_TRUE(frame_file::Footer::DecodeFrom(data + slot.footer_offset, &footer).ok());
    ranges.push_back({footer.metadata_offset, slot.committed_length});
  }
  return ranges;
}

// The rows of frames [0, frames) of the archive's newest version.
std::vector<float> Frames(const std::string& archive, uint64_t frames) {
  std::vector<float> rows;
  auto reader = FrameFileReader::Open(archive);
  EXPECT_TRUE(reader.ok()) << reader.status().ToString();
  if (reader.ok()) {
    EXPECT_TRUE((*reader)->ReadFrames(0, frames, &rows).ok());
  }
  return rows;
}

bool RefusedAsDamaged(int exit_code) { return exit_code == 12 || exit_code == 15; }

class DamageSweep : public ::testing::TestWithParam<int> {};

TEST_P(DamageSweep, EveryFlippedMetadataByteIsReadIntactOrRefusedAndLosesNoCommit) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  std::vector<std::string> takes;
  for (int i = 0; i < 3; ++i) {
    takes.push_back(dir.File("take" + std::to_string(i) + ".bvh"));
    ASSERT_TRUE(AtomicWriteFile(takes.back(), SwayingTake(i, 240)).ok());
  }
  ASSERT_EQ(RunTool("import " + archive + " " + takes[0] + " --quiet").exit_code, 0);
  ASSERT_EQ(RunTool("import " + archive + " " + takes[1] + " --quiet").exit_code, 0);
  const std::string original = ReadFileToString(archive).value();
  const std::vector<float> newest_frames = Frames(archive, 480);

  int flips = 0, refused_by_verify = 0, mined = 0, imported = 0;
  for (const auto& [begin, end] : MetadataRanges(original)) {
    for (size_t offset = begin; offset < end; ++offset) {
      if (static_cast<int>(offset % kShards) != GetParam()) continue;
      ++flips;
      SCOPED_TRACE("byte " + std::to_string(offset) + " of " + std::to_string(original.size()));
      std::string damaged = original;
      damaged[offset] = static_cast<char>(damaged[offset] ^ 0xff);
      ASSERT_TRUE(AtomicWriteFile(archive, damaged).ok());

      const RunResult verify = RunTool("verify " + archive + " --quiet");
      ASSERT_TRUE(verify.exit_code == 0 || RefusedAsDamaged(verify.exit_code)) << verify.output;
      refused_by_verify += verify.exit_code != 0;

      const RunResult info = RunTool("info " + archive + " --json");
      ASSERT_TRUE(info.exit_code == 0 || RefusedAsDamaged(info.exit_code)) << info.output;
      if (info.exit_code == 0) {  // the newest version, never an older one in its place
        const nlohmann::json json = nlohmann::json::parse(info.output);
        EXPECT_EQ(json["generation"], 2) << info.output;
        EXPECT_EQ(json["clips"].size(), 2u) << info.output;
      }

      if (offset - begin >= 16 && end - offset > 16 && (offset - begin) % 5 != 0) continue;
      const std::string out = dir.File("m" + std::to_string(offset));
      const RunResult mine = RunTool("mine " + archive + " --out " + out + " --quiet --no-report");
      ASSERT_TRUE(mine.exit_code == 0 || RefusedAsDamaged(mine.exit_code)) << mine.output;
      if (mine.exit_code == 0) {
        ++mined;
        const nlohmann::json motifs =
            nlohmann::json::parse(ReadFileToString(out + "/motifs.json").value());
        EXPECT_EQ(motifs["archive_version"]["generation"], 2);
        EXPECT_EQ(motifs["frames"], 480);
      } else {
        EXPECT_FALSE(std::filesystem::exists(out + "/motifs.json"));
      }
      std::filesystem::remove_all(out);

      const RunResult import = RunTool("import " + archive + " " + takes[2] + " --quiet");
      ASSERT_TRUE(import.exit_code == 0 || RefusedAsDamaged(import.exit_code)) << import.output;
      if (import.exit_code == 0) {  // appended after the newest version, which is kept whole
        ++imported;
        EXPECT_EQ(RunTool("verify " + archive + " --quiet").exit_code, 0);
        auto reader = FrameFileReader::Open(archive);
        ASSERT_TRUE(reader.ok()) << reader.status().ToString();
        EXPECT_EQ((*reader)->summary().generation, 3u);
        EXPECT_EQ((*reader)->clips().size(), 3u);
        EXPECT_EQ(Frames(archive, 480), newest_frames);
      } else {  // nothing written: undoing the flip gives back every commit
        EXPECT_EQ(ReadFileToString(archive).value(), damaged);
      }
    }
  }
  // Both outcomes occur: damage to the header's fixed part and the newest commit is refused;
  // damage to the older commit's metadata and footer, which the newest no longer uses, is not.
  EXPECT_GT(flips, 100);
  EXPECT_GT(refused_by_verify, 0);
  EXPECT_GT(mined, 0);
  EXPECT_GT(imported, 0);
  std::printf("shard %d: %d bytes flipped; verify refused %d, mine ran on %d, import on %d\n",
              GetParam(), flips, refused_by_verify, mined, imported);
}

INSTANTIATE_TEST_SUITE_P(Shards, DamageSweep, ::testing::Range(0, kShards));

}  // namespace
}  // namespace motif
