// The streaming path grower on hand-built trellises whose paths are known: the paper's Figure 2
// step, the one-ancestor rule, clip boundaries on both sides, lambda on both sides, determinism
// and the checks on its input.
#include "engine/grow/path_grower.h"

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/engine/grow/grow_test_util.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// Every branch is kept, so each test sees the whole forest; KeepsTheLongestPathOfEachTree
// tests the default.
GrowOptions Options(uint32_t branch, uint64_t min_length, bool all_branches = true) {
  GrowOptions options;
  options.branch = branch;
  options.min_length = min_length;
  options.all_branches = all_branches;
  return options;
}

// Grows in memory and through a trellis file (two block sizes) and checks all three agree.
std::vector<PathCandidate> Grow(const GrowColumns& columns, const std::vector<uint64_t>& clips,
                                const GrowOptions& options) {
  auto in_memory = GrowInMemory(columns, clips, options);
  EXPECT_TRUE(in_memory.ok()) << in_memory.status().ToString();
  if (!in_memory.ok()) return {};
  TempDir dir;
  for (uint32_t block_columns : {1u, 7u, 4096u}) {
    auto through_file = GrowThroughFile(dir.File("t.mtr"), columns, clips, options, block_columns);
    EXPECT_TRUE(through_file.ok()) << through_file.status().ToString();
    if (through_file.ok()) {
      EXPECT_EQ(*through_file, *in_memory) << "blocks of " << block_columns;
    }
  }
  return *in_memory;
}

TEST(PathGrower, OneDiagonalAndItsMirrorGiveTwoCandidates) {
  GrowColumns columns = EmptyColumns(200);
  AddDiagonal(&columns, 0, 100, 100);  // frames 0..99 match 100..199
  AddDiagonal(&columns, 100, 0, 100);  // and the other way round
  const auto candidates = Grow(columns, {0}, Options(3, 60));
  const std::vector<PathCandidate> expected = {Candidate(0, 100, 100, 200),
                                               Candidate(100, 200, 0, 100)};
  EXPECT_EQ(candidates, expected) << Describe(candidates);
}

// Meng et al. 2008, Figure 2 (B = 3): the step from column 312 to 313. Frame 927 of column 312
// carries the path {Root = 857, Depth = 65} (rooted at column 247); it finds its next three
// temporal neighbours 927, 928, 929 marked in column 313's array and passes {857, 66} to all
// three; their cells are cleared, so 929 of column 312 (another path) checks 929..931 and can
// only branch to 931. Frame 700 of column 313 has no ancestor and starts a new tree. The paper
// also shows a frame 926 in column 312 that dies because 927 and 928 were taken first: the
// paper takes a column's leaves in its trellis row order, ours in frame order (926 would claim
// first), so 926 is left out here; PathGrower.LowerLeafClaimsFirst shows our order.
TEST(PathGrower, PaperFigure2Step) {
  GrowColumns columns = EmptyColumns(1000);
  std::vector<uint64_t> path_857;  // columns 247..312: 857 .. 927, one or two frames a column
  for (uint64_t column = 247; column <= 312; ++column) {
    path_857.push_back(857 + (column - 247) + (column > 307 ? column - 307 : 0));
  }
  ASSERT_EQ(path_857.back(), 927u);
  AddPath(&columns, 247, path_857);
  AddDiagonal(&columns, 300, 917, 13);  // columns 300..312: 917 .. 929
  for (uint64_t frame : {700, 927, 928, 929, 931}) AddNode(&columns, 313, frame);
  ASSERT_EQ(columns[313][2].frame, 928u);  // "928 is the 3rd neighbour of 313"

  // lambda 1: every path that dies is a candidate, so the whole forest shows. Column 314 is
  // empty: every leaf of column 313 dies there.
  auto forest = Grow(columns, {0}, Options(3, 1));
  const std::vector<PathCandidate> expected = {
      Candidate(247, 314, 857, 928),  // {857, 66} at 927
      Candidate(247, 314, 857, 929),  // {857, 66} at 928
      Candidate(247, 314, 857, 930),  // {857, 66} at 929: 927's branch, not 929's
      Candidate(300, 314, 917, 932),  // 929 -> 931 only
      Candidate(313, 314, 700, 701),  // a new tree
  };
  EXPECT_EQ(forest, expected) << Describe(forest);

  // lambda 60 (the paper's): the three branches of the 67-column path remain.
  auto valid = Grow(columns, {0}, Options(3, 60));
  EXPECT_EQ(valid, std::vector<PathCandidate>(expected.begin(), expected.begin() + 3))
      << Describe(valid);
}

// By default a tree gives one candidate: its longest path (by top length, then match length).
TEST(PathGrower, KeepsTheLongestPathOfEachTreeByDefault) {
  GrowColumns columns = EmptyColumns(100);
  // One tree: 10 -> {11, 12} at column 1; 11, the lower leaf, takes 13 at column 2 and goes
  // on to 14 at column 3, so the branch at 12 dies at column 1; a second tree at 50 .. 53.
  AddPath(&columns, 0, {10, 12, 13, 14});
  AddNode(&columns, 1, 11);
  AddDiagonal(&columns, 0, 50, 4);
  const std::vector<PathCandidate> all = {Candidate(0, 2, 10, 13), Candidate(0, 4, 10, 15),
                                          Candidate(0, 4, 50, 54)};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 1, true)), all);
  const std::vector<PathCandidate> longest = {Candidate(0, 4, 10, 15), Candidate(0, 4, 50, 54)};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 1, false)), longest);
  EXPECT_EQ(Grow(columns, {0}, GrowOptions{3, 1}), longest);  // the default

  // Same top length: the longer match wins. 20 -> {20, 21, 22}, all die at column 1.
  GrowColumns same = EmptyColumns(40);
  AddNode(&same, 0, 20);
  for (uint64_t frame : {20, 21, 22}) AddNode(&same, 1, frame);
  EXPECT_EQ(Grow(same, {0}, Options(3, 1, false)),
            std::vector<PathCandidate>{Candidate(0, 2, 20, 23)});
  // Lambda applies to each path: here every path spans 2 columns, so lambda 3 leaves none.
  EXPECT_EQ(Grow(same, {0}, Options(3, 3, false)), std::vector<PathCandidate>{});
}

// Each node has one ancestor: the lower leaf claims every marked cell of its window first.
TEST(PathGrower, LowerLeafClaimsFirst) {
  GrowColumns columns = EmptyColumns(20);
  for (uint64_t frame : {10, 11}) AddNode(&columns, 0, frame);
  for (uint64_t frame : {11, 12, 13}) AddNode(&columns, 1, frame);
  // 10 claims 11 and 12 (window 10..12); 11 finds 11 and 12 cleared and claims 13.
  auto candidates = Grow(columns, {0}, Options(3, 1));
  const std::vector<PathCandidate> expected = {Candidate(0, 2, 10, 12), Candidate(0, 2, 10, 13),
                                               Candidate(0, 2, 11, 14)};
  EXPECT_EQ(candidates, expected) << Describe(candidates);
}

TEST(PathGrower, ALeafWhoseCellsWereTakenDies) {
  GrowColumns columns = EmptyColumns(20);
  for (uint64_t frame : {10, 11}) AddNode(&columns, 0, frame);
  AddNode(&columns, 1, 12);
  // 10 claims 12; 11 (window 11..13) finds it cleared and dies at column 0.
  auto candidates = Grow(columns, {0}, Options(3, 1));
  const std::vector<PathCandidate> expected = {Candidate(0, 2, 10, 13), Candidate(0, 1, 11, 12)};
  EXPECT_EQ(candidates, expected) << Describe(candidates);
  // With B = 2 the window of 10 is 10..11: 12 is out of reach; 11 claims it.
  candidates = Grow(columns, {0}, Options(2, 1));
  const std::vector<PathCandidate> b2 = {Candidate(0, 1, 10, 11), Candidate(0, 2, 11, 13)};
  EXPECT_EQ(candidates, b2) << Describe(candidates);
}

TEST(PathGrower, StallsAndSkipsWithinTheWindow) {
  GrowColumns columns = EmptyColumns(400);
  // Half speed (a stall every other column) and double speed, B = 3.
  std::vector<uint64_t> slow, fast;
  for (uint64_t step = 0; step < 100; ++step) slow.push_back(200 + step / 2);
  for (uint64_t step = 0; step < 50; ++step) fast.push_back(300 + 2 * step);
  AddPath(&columns, 0, slow);    // top [0, 100), match [200, 250)
  AddPath(&columns, 120, fast);  // top [120, 170), match [300, 399)
  EXPECT_EQ(Grow(columns, {0}, Options(3, 60)), std::vector<PathCandidate>{})
      << "lambda applies to both sides";
  const std::vector<PathCandidate> at_50 = {Candidate(0, 100, 200, 250),
                                            Candidate(120, 170, 300, 399)};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 50)), at_50);
  const std::vector<PathCandidate> at_51 = {};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 51)), at_51);
  // B = 2 cannot follow the double-speed path: it breaks into one-column paths.
  const std::vector<PathCandidate> b2 = {Candidate(0, 100, 200, 250)};
  EXPECT_EQ(Grow(columns, {0}, Options(2, 50)), b2);
}

TEST(PathGrower, LambdaCountsFramesOnEachSide) {
  GrowColumns columns = EmptyColumns(300);
  AddDiagonal(&columns, 0, 150, 60);  // exactly 60 columns and 60 frames
  AddDiagonal(&columns, 70, 220, 59);
  const std::vector<PathCandidate> expected = {Candidate(0, 60, 150, 210)};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 60)), expected);
}

TEST(PathGrower, EveryPathDiesWhenTheTopRowEntersANewClip) {
  GrowColumns columns = EmptyColumns(200);
  AddDiagonal(&columns, 20, 120, 61);  // columns 20..80 match 120..180; a clip starts at 50
  const auto candidates = Grow(columns, {0, 50}, Options(3, 20));
  const std::vector<PathCandidate> expected = {Candidate(20, 50, 120, 150),
                                               Candidate(50, 81, 150, 181)};
  EXPECT_EQ(candidates, expected) << Describe(candidates);
  // Without the clip boundary it is one path.
  const std::vector<PathCandidate> one = {Candidate(20, 81, 120, 181)};
  EXPECT_EQ(Grow(columns, {0}, Options(3, 20)), one);
}

TEST(PathGrower, AMatchedSegmentNeverSpansTwoClips) {
  GrowColumns columns = EmptyColumns(200);
  AddDiagonal(&columns, 0, 70, 60);  // match 70..129 crosses the clip start at 100
  const auto candidates = Grow(columns, {0, 100}, Options(3, 20));
  const std::vector<PathCandidate> expected = {Candidate(0, 30, 70, 100),
                                               Candidate(30, 60, 100, 130)};
  EXPECT_EQ(candidates, expected) << Describe(candidates);

  // A skip over the boundary (99 -> 101, within B = 3) is not allowed either.
  GrowColumns skip = EmptyColumns(200);
  AddPath(&skip, 0, {96, 97, 98, 99, 101, 102});
  const std::vector<PathCandidate> split = {Candidate(0, 4, 96, 100), Candidate(4, 6, 101, 103)};
  EXPECT_EQ(Grow(skip, {0, 100}, Options(3, 1)), split);
  const std::vector<PathCandidate> whole = {Candidate(0, 6, 96, 103)};
  EXPECT_EQ(Grow(skip, {0}, Options(3, 1)), whole);
}

// A path whose matched frames overlap its own top row (same clip, an offset beyond the
// exclusion radius, e.g. a repeated step cycle) is a valid candidate.
TEST(PathGrower, KeepsAPathThatOverlapsItsTopRow) {
  GrowColumns columns = EmptyColumns(200);
  AddDiagonal(&columns, 0, 40, 100);  // top [0, 100), match [40, 140)
  const std::vector<PathCandidate> expected = {Candidate(0, 100, 40, 140)};
  EXPECT_EQ(Grow(columns, {0}, Options(5, 60)), expected);
}

TEST(PathGrower, SameCandidatesOnEveryRunAndSortedOutput) {
  const GrowColumns columns = RandomColumns(500, 11, 30, 3, 2);
  const auto first = Grow(columns, {0, 170, 333}, Options(3, 5));
  const auto second = Grow(columns, {0, 170, 333}, Options(3, 5));
  EXPECT_EQ(first, second);
  ASSERT_GT(first.size(), 5u);
  std::vector<PathCandidate> sorted = first;
  SortCandidates(&sorted);
  EXPECT_EQ(sorted, first);
  for (const PathCandidate& candidate : first) {
    EXPECT_GE(candidate.top_length(), 5u);
    EXPECT_GE(candidate.match_length(), 5u);
  }
}

TEST(PathGrower, CountsTreesDeathsAndEntries) {
  GrowColumns columns = EmptyColumns(20);
  for (uint64_t frame : {10, 11}) AddNode(&columns, 0, frame);
  for (uint64_t frame : {11, 12, 13}) AddNode(&columns, 1, frame);
  auto grower = PathGrower::Create(20, {0}, Options(3, 1));
  ASSERT_TRUE(grower.ok());
  for (const auto& column : columns) {
    ASSERT_TRUE((*grower)->AddColumn(column.data(), column.size()).ok());
  }
  ASSERT_TRUE((*grower)->Finish().ok());
  const GrowStats& stats = (*grower)->stats();
  EXPECT_EQ(stats.columns, 20u);
  EXPECT_EQ(stats.entries, 5u);
  EXPECT_EQ(stats.trees, 2u);
  EXPECT_EQ(stats.dead_paths, 3u);
  EXPECT_EQ(stats.candidates, 3u);
  EXPECT_EQ(stats.max_column_nodes, 3u);
  EXPECT_GE((*grower)->memory_bytes(), 20 * sizeof(uint32_t));
}

TEST(PathGrower, RejectsBadOptionsClipsAndColumns) {
  EXPECT_TRUE(PathGrower::Create(10, {0}, Options(0, 60)).status().IsInvalidArgument());
  EXPECT_TRUE(
      PathGrower::Create(10, {0}, Options(kMaxBranch + 1, 60)).status().IsInvalidArgument());
  EXPECT_TRUE(PathGrower::Create(10, {0}, Options(3, 0)).status().IsInvalidArgument());
  EXPECT_TRUE(PathGrower::Create(10, {1}, Options(3, 1)).status().IsInvalidArgument());
  EXPECT_TRUE(PathGrower::Create(10, {0, 5, 5}, Options(3, 1)).status().IsInvalidArgument());
  EXPECT_TRUE(PathGrower::Create(10, {0, 10}, Options(3, 1)).status().IsInvalidArgument());
  EXPECT_TRUE(
      PathGrower::Create((uint64_t{1} << 32) + 1, {0}, Options(3, 1)).status().IsInvalidArgument());
  ASSERT_TRUE(PathGrower::Create(10, {}, Options(3, 1)).ok());  // no clips: one clip

  auto grower = PathGrower::Create(10, {0}, Options(3, 1));
  ASSERT_TRUE(grower.ok());
  const Neighbour unsorted[] = {{5, 0}, {4, 0}};
  EXPECT_TRUE((*grower)->AddColumn(unsorted, 2).IsInvalidArgument());
  const Neighbour duplicate[] = {{4, 0}, {4, 0}};
  EXPECT_TRUE((*grower)->AddColumn(duplicate, 2).IsInvalidArgument());
  const Neighbour outside[] = {{10, 0}};
  EXPECT_TRUE((*grower)->AddColumn(outside, 1).IsInvalidArgument());
  EXPECT_EQ((*grower)->next_column(), 0u);                        // unchanged
  EXPECT_TRUE((*grower)->Finish().status().IsInvalidArgument());  // before the last column
  for (int column = 0; column < 10; ++column) ASSERT_TRUE((*grower)->AddColumn(nullptr, 0).ok());
  EXPECT_TRUE((*grower)->AddColumn(nullptr, 0).IsInvalidArgument());  // one too many
  auto none = (*grower)->Finish();
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

TEST(GrowPaths, ReportsProgressAndClipsAgainstTheTrellis) {
  TempDir dir;
  GrowColumns columns = EmptyColumns(100);
  AddDiagonal(&columns, 0, 30, 70);
  ASSERT_TRUE(WriteColumns(dir.File("t.mtr"), columns, 32).ok());
  auto reader = TrellisFileReader::Open(dir.File("t.mtr"));
  ASSERT_TRUE(reader.ok());
  std::vector<std::pair<uint64_t, uint64_t>> calls;
  GrowStats stats;
  auto candidates = GrowPaths(
      **reader, {0}, Options(3, 60),
      [&](uint64_t done, uint64_t total) {
        calls.push_back({done, total});
      },
      &stats);
  ASSERT_TRUE(candidates.ok());
  EXPECT_EQ(*candidates, std::vector<PathCandidate>{Candidate(0, 70, 30, 100)});
  const std::vector<std::pair<uint64_t, uint64_t>> expected_calls = {
      {0, 100}, {32, 100}, {64, 100}, {96, 100}, {100, 100}};
  EXPECT_EQ(calls, expected_calls);
  EXPECT_EQ(stats.entries, 70u);
  EXPECT_GE(stats.memory_bytes, 100 * sizeof(uint32_t));
  // Clip starts beyond the trellis's columns: InvalidArgument naming the trellis.
  auto bad = GrowPaths(**reader, {0, 100}, Options(3, 60));
  EXPECT_TRUE(bad.status().IsInvalidArgument());
  EXPECT_NE(bad.status().message().find("t.mtr"), std::string::npos) << bad.status().ToString();
}

// GrowPaths gives each block's mapped pages back once consumed: after a run the reader's
// mapping is not resident (the grower's memory is its O(N) array, not the trellis file), and the
// candidates are those of the in-memory grower.
TEST(GrowPaths, ReleasesTheBlocksItHasGrown) {
  TempDir dir;
  const GrowColumns columns = RandomColumns(20000, 5, 40, 200, 2);
  const std::vector<uint64_t> clips = {0, 7000, 13000};
  ASSERT_TRUE(WriteColumns(dir.File("t.mtr"), columns, 256).ok());
  auto reader = TrellisFileReader::Open(dir.File("t.mtr"));
  ASSERT_TRUE(reader.ok());
  ASSERT_GT((*reader)->file_bytes(), 1u << 20);
  auto candidates = GrowPaths(**reader, clips, Options(5, 60, /*all_branches=*/false));
  ASSERT_TRUE(candidates.ok()) << candidates.status().ToString();
  auto in_memory = GrowInMemory(columns, clips, Options(5, 60, /*all_branches=*/false));
  ASSERT_TRUE(in_memory.ok());
  EXPECT_EQ(*candidates, *in_memory);
  EXPECT_FALSE(candidates->empty());
  const int64_t resident = MappedResidentBytes(dir.File("t.mtr"));
  if (resident < 0) GTEST_SKIP() << "no /proc/self/smaps";
  EXPECT_LT(resident, static_cast<int64_t>((*reader)->file_bytes() / 10));
}

}  // namespace
}  // namespace motif::testing
