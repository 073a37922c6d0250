// The O(N·K²) pairwise reference grower gives exactly the streaming grower's candidates: on the
// hand-built cases, on random trellises (clips, noise, stalls, skips, every branch factor), and
// on the trellis of a synthetic archive with planted motifs.
#include "engine/grow/reference_grower.h"

#include <gtest/gtest.h>

#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/engine/grow/grow_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

TEST(ReferenceGrower, MatchesTheHandBuiltFigure2Step) {
  GrowColumns columns = EmptyColumns(40);
  for (uint64_t frame : {26, 27, 29}) AddNode(&columns, 12, frame);
  for (uint64_t frame : {7, 27, 28, 29, 31}) AddNode(&columns, 13, frame);
  GrowOptions options;
  options.branch = 3;
  options.min_length = 1;
  options.all_branches = true;
  auto reference = GrowPathsReference(columns, {0}, options);
  ASSERT_TRUE(reference.ok());
  // 26 takes 27 and 28, 27 takes 29, 29 takes 31; 7 is a new tree.
  const std::vector<PathCandidate> expected = {Candidate(12, 14, 26, 28), Candidate(12, 14, 26, 29),
                                               Candidate(12, 14, 27, 30), Candidate(12, 14, 29, 32),
                                               Candidate(13, 14, 7, 8)};
  EXPECT_EQ(*reference, expected) << Describe(*reference);
  auto streaming = GrowInMemory(columns, {0}, options);
  ASSERT_TRUE(streaming.ok());
  EXPECT_EQ(*streaming, *reference);
}

TEST(ReferenceGrower, EqualsTheStreamingGrowerOnRandomTrellises) {
  int compared = 0;
  uint64_t candidates = 0;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    const uint64_t frame_count = 50 + seed * 17 % 400;
    const GrowColumns columns =
        RandomColumns(frame_count, seed, 5 + static_cast<int>(seed % 20),
                      static_cast<int>(seed % 6), static_cast<uint32_t>(1 + seed % 4));
    const std::vector<uint64_t> clips =
        RandomClipStarts(frame_count, seed * 31, 1 + static_cast<int>(seed % 7));
    for (uint32_t branch : {1u, 2u, 3u, 5u, 8u}) {
      for (uint64_t min_length : {1u, 4u, 15u}) {
        GrowOptions options;
        options.branch = branch;
        options.min_length = min_length;
        options.all_branches = (seed + branch + min_length) % 2 == 0;
        GrowStats streaming_stats;
        GrowStats reference_stats;
        auto grower = PathGrower::Create(frame_count, clips, options);
        ASSERT_TRUE(grower.ok());
        for (const auto& column : columns) {
          ASSERT_TRUE((*grower)->AddColumn(column.data(), column.size()).ok());
        }
        auto streaming = (*grower)->Finish();
        streaming_stats = (*grower)->stats();
        auto reference = GrowPathsReference(columns, clips, options, &reference_stats);
        ASSERT_TRUE(streaming.ok() && reference.ok());
        ASSERT_EQ(*streaming, *reference)
            << "seed " << seed << " B " << branch << " lambda " << min_length << " all "
            << options.all_branches << "\nstreaming\n"
            << Describe(*streaming) << "reference\n"
            << Describe(*reference);
        EXPECT_EQ(streaming_stats.trees, reference_stats.trees);
        EXPECT_EQ(streaming_stats.dead_paths, reference_stats.dead_paths);
        EXPECT_EQ(streaming_stats.entries, reference_stats.entries);
        EXPECT_EQ(streaming_stats.long_paths, reference_stats.long_paths);
        EXPECT_EQ(streaming_stats.candidates, streaming->size());
        ++compared;
        candidates += streaming->size();
      }
    }
  }
  EXPECT_EQ(compared, 60 * 15);
  EXPECT_GT(candidates, 5000u);  // the comparison is not vacuous
}

// A synthetic archive with planted motifs (several clips), its exact trellis, and both growers.
TEST(ReferenceGrower, EqualsTheStreamingGrowerOnASyntheticArchivesTrellis) {
  TempDir dir;
  const std::string archive = dir.File("synth.mfs");
  ASSERT_TRUE(WriteSynthArchive(archive, 6000, 3).ok());
  TrellisOptions trellis_options;
  trellis_options.exact = true;
  trellis_options.k_max = 64;
  trellis_options.block_columns = 1000;
  const std::string trellis_path = dir.File("synth.mtr");
  auto built = BuildTrellis(archive, trellis_path, trellis_options);
  ASSERT_TRUE(built.ok()) << built.status().ToString();
  auto archive_reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(archive_reader.ok());
  std::vector<uint64_t> clips;
  for (const ClipInfo& clip : (*archive_reader)->clips()) clips.push_back(clip.first_frame);
  ASSERT_GT(clips.size(), 2u);
  auto trellis = TrellisFileReader::Open(trellis_path);
  ASSERT_TRUE(trellis.ok());
  for (uint32_t branch : {3u, 5u}) {
    for (uint64_t min_length : {20u, 60u}) {
      GrowOptions options;
      options.branch = branch;
      options.min_length = min_length;
      options.all_branches = branch == 3;
      auto streaming = GrowPaths(**trellis, clips, options);
      auto reference = GrowPathsReference(**trellis, clips, options);
      ASSERT_TRUE(streaming.ok() && reference.ok());
      EXPECT_EQ(*streaming, *reference) << "B " << branch << " lambda " << min_length;
      EXPECT_FALSE(streaming->empty()) << "B " << branch << " lambda " << min_length;
    }
  }
}

}  // namespace
}  // namespace motif::testing
