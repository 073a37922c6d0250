#include "engine/cluster/instance_builder.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

namespace motif {
namespace {

PathCandidate Path(uint64_t top_start, uint64_t top_end, uint64_t match_start, uint64_t match_end,
                   uint64_t root_column, uint64_t root_frame) {
  return {top_start, top_end, match_start, match_end, root_column, root_frame};
}

TEST(KeepLongestPathPerRootTest, KeepsOnlyTheLongestBranchOfEachTree) {
  std::vector<PathCandidate> candidates = {
      Path(100, 180, 500, 580, 100, 500),  // root (100, 500): 80 frames
      Path(100, 220, 500, 620, 100, 500),  // root (100, 500): 120 frames, the longest
      Path(100, 200, 500, 601, 100, 500),  // root (100, 500): 100 frames
      Path(300, 400, 900, 1000, 300, 900),
  };
  std::vector<PathCandidate> kept = KeepLongestPathPerRoot(candidates);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], candidates[1]);
  EXPECT_EQ(kept[1], candidates[3]);
  // The choice does not depend on the input order, ties included.
  candidates.push_back(Path(100, 220, 510, 630, 100, 500));  // same lengths as the longest
  std::vector<PathCandidate> reversed(candidates.rbegin(), candidates.rend());
  EXPECT_EQ(KeepLongestPathPerRoot(candidates), KeepLongestPathPerRoot(reversed));
  EXPECT_EQ(KeepLongestPathPerRoot(candidates)[0].match_start, 500u);  // earliest wins the tie
}

TEST(OverlapsEnoughTest, ThreeQuartersOfTheLongerIsTheBoundary) {
  EXPECT_TRUE(OverlapsEnough({0, 100}, {25, 125}, 0.75));    // 75 of 100
  EXPECT_FALSE(OverlapsEnough({0, 100}, {26, 126}, 0.75));   // 74 of 100
  EXPECT_FALSE(OverlapsEnough({0, 400}, {300, 380}, 0.75));  // inside, but 80 of 400
  EXPECT_TRUE(OverlapsEnough({0, 100}, {0, 133}, 0.75));     // 100 of 133
  EXPECT_FALSE(OverlapsEnough({0, 100}, {0, 134}, 0.75));    // 100 of 134
  EXPECT_FALSE(OverlapsEnough({0, 100}, {100, 200}, 0.75));  // touching, no shared frame
}

TEST(BuildInstancesTest, TwoInstancesPerPathLinked) {
  InstanceSet set = BuildInstances({Path(0, 100, 1000, 1090, 0, 1000)});
  ASSERT_EQ(set.instances.size(), 2u);
  EXPECT_EQ(set.instances[0], (MotifInstance{0, 100}));
  EXPECT_EQ(set.instances[1], (MotifInstance{1000, 1090}));
  ASSERT_EQ(set.links.size(), 1u);
  EXPECT_EQ(set.links[0], (InstanceLink{0, 1}));
  EXPECT_EQ(set.stats.raw_instances, 2u);
}

TEST(BuildInstancesTest, MergesOverlapsOfThreeQuartersIntoTheUnionAndCarriesLinks) {
  InstanceSet set = BuildInstances({
      Path(0, 100, 1000, 1100, 0, 1000),
      Path(20, 120, 2000, 2100, 20, 2000),  // top overlaps the first top by 80 of 100: merged
      Path(500, 600, 3000, 3100, 500, 3000),
      Path(530, 630, 4000, 4100, 530, 4000),  // overlaps [500, 600) by 70 of 100: kept apart
  });
  ASSERT_EQ(set.instances.size(), 7u);
  EXPECT_EQ(set.instances[0], (MotifInstance{0, 120}));
  EXPECT_EQ(set.instances[1], (MotifInstance{500, 600}));
  EXPECT_EQ(set.instances[2], (MotifInstance{530, 630}));
  EXPECT_EQ(set.instances[3], (MotifInstance{1000, 1100}));
  EXPECT_EQ(set.instances[4], (MotifInstance{2000, 2100}));
  // [0, 120) carries both paths' links.
  EXPECT_EQ(set.links, (std::vector<InstanceLink>{{0, 3}, {0, 4}, {1, 5}, {2, 6}}));
  EXPECT_EQ(set.stats.instances, 7u);
  EXPECT_EQ(set.stats.links, 4u);
}

TEST(BuildInstancesTest, ChainedMergesTakeTheUnion) {
  // [0,100) ~ [20,120) ~ [40,140): the first and last overlap by only 60, but the chain joins them.
  InstanceSet set = BuildInstances({
      Path(0, 100, 1000, 1100, 0, 1000),
      Path(20, 120, 1020, 1120, 20, 1020),
      Path(40, 140, 1040, 1140, 40, 1040),
  });
  ASSERT_EQ(set.instances.size(), 2u);
  EXPECT_EQ(set.instances[0], (MotifInstance{0, 140}));
  EXPECT_EQ(set.instances[1], (MotifInstance{1000, 1140}));
  EXPECT_EQ(set.links, (std::vector<InstanceLink>{{0, 1}}));  // three paths, one distinct link
}

TEST(BuildInstancesTest, APeriodicPathIsCutIntoLinkedPeriods) {
  // A periodic motion: the matched segment is the top segment shifted by one period, 100 frames.
  // The span [0, 450) holds four whole periods; the partial fifth is left out.
  const PathCandidate path = Path(0, 350, 100, 450, 0, 100);
  EXPECT_EQ(PeriodicPieces(path, 0),
            (std::vector<MotifInstance>{{0, 100}, {100, 200}, {200, 300}, {300, 400}}));
  // With a least length of 150 frames a piece is two periods.
  EXPECT_EQ(PeriodicPieces(path, 150), (std::vector<MotifInstance>{{0, 200}, {200, 400}}));
  EXPECT_TRUE(PeriodicPieces(Path(0, 100, 100, 200, 0, 100), 0).empty());  // touching: no overlap
  InstanceSet set = BuildInstances({path});
  EXPECT_EQ(set.instances,
            (std::vector<MotifInstance>{{0, 100}, {100, 200}, {200, 300}, {300, 400}}));
  EXPECT_EQ(set.links, (std::vector<InstanceLink>{{0, 1}, {1, 2}, {2, 3}}));
  EXPECT_EQ(set.stats.periodic_paths, 1u);
  EXPECT_EQ(set.stats.self_links, 0u);
}

TEST(BuildInstancesTest, AHarmonicOfAPeriodicPathLinksItsPiecesKPiecesApart) {
  // Period 100 over [0, 450): pieces [0,100) ... [300,400). A path matching [20,150) with
  // [220,350) is the same motion two periods later: it links pieces 0-2 and 1-3 (each at least
  // half inside [20,150)) and adds no instance of its own.
  const PathCandidate periodic = Path(0, 350, 100, 450, 0, 100);
  const PathCandidate harmonic = Path(20, 150, 220, 350, 20, 220);
  InstanceSet set = BuildInstances({periodic, harmonic});
  EXPECT_EQ(set.instances,
            (std::vector<MotifInstance>{{0, 100}, {100, 200}, {200, 300}, {300, 400}}));
  EXPECT_EQ(set.links, (std::vector<InstanceLink>{{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}}));
  EXPECT_EQ(set.stats.harmonic_paths, 1u);
  EXPECT_EQ(set.stats.periodic_paths, 1u);

  // Two and a half periods later (off by more than a quarter period): a path of its own, whose
  // [270, 400) takes in the piece [300, 400) (3/4 of the longer shared).
  set = BuildInstances({periodic, Path(20, 150, 270, 400, 20, 270)});
  EXPECT_EQ(set.stats.harmonic_paths, 0u);
  EXPECT_EQ(set.instances,
            (std::vector<MotifInstance>{{0, 100}, {20, 150}, {100, 200}, {200, 300}, {270, 400}}));
  // A quarter of a segment outside the periodic span: a path of its own too.
  set = BuildInstances({periodic, Path(20, 150, 350, 480, 20, 350)});
  EXPECT_EQ(set.stats.harmonic_paths, 0u);

  // A period shorter than lambda (pieces of two periods) is no fundamental.
  InstanceOptions options;
  options.min_length = 150;
  set = BuildInstances({periodic, harmonic}, options);
  EXPECT_EQ(set.stats.harmonic_paths, 0u);
}

TEST(BuildInstancesTest, DeduplicatesRootsBeforeMerging) {
  InstanceSet set = BuildInstances({
      Path(0, 60, 1000, 1060, 0, 1000),
      Path(0, 200, 1000, 1200, 0, 1000),  // same tree, longer: the only one kept
  });
  EXPECT_EQ(set.stats.kept_paths, 1u);
  EXPECT_EQ(set.instances, (std::vector<MotifInstance>{{0, 200}, {1000, 1200}}));
}

// The sweep finds the same sets as comparing all pairs.
TEST(BuildInstancesTest, SweepMatchesAllPairsOnRandomPaths) {
  std::mt19937_64 random(5);
  for (int round = 0; round < 20; ++round) {
    std::vector<PathCandidate> candidates;
    for (int idx = 0; idx < 80; ++idx) {
      const uint64_t top = random() % 2000;
      const uint64_t match = random() % 2000;
      candidates.push_back(
          Path(top, top + 20 + random() % 100, match, match + 20 + random() % 100, top, match));
    }
    const InstanceSet set = BuildInstances(candidates);
    // Brute force: all pairs, transitive closure, unions.
    const std::vector<MotifInstance> raw =
        RawInstances(KeepLongestPathPerRoot(candidates), 0).instances;
    std::vector<size_t> label(raw.size());
    for (size_t idx = 0; idx < raw.size(); ++idx) label[idx] = idx;
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t a = 0; a < raw.size(); ++a) {
        for (size_t b = 0; b < raw.size(); ++b) {
          if (label[a] != label[b] && OverlapsEnough(raw[a], raw[b], 0.75)) {
            const size_t low = std::min(label[a], label[b]);
            label[a] = label[b] = low;
            changed = true;
          }
        }
      }
    }
    std::vector<MotifInstance> expected;
    for (size_t idx = 0; idx < raw.size(); ++idx) {
      if (label[idx] != idx) continue;
      MotifInstance merged = raw[idx];
      for (size_t other = 0; other < raw.size(); ++other) {
        if (label[other] != idx) continue;
        merged.start = std::min(merged.start, raw[other].start);
        merged.end = std::max(merged.end, raw[other].end);
      }
      expected.push_back(merged);
    }
    std::sort(expected.begin(), expected.end(), [](const MotifInstance& a, const MotifInstance& b) {
      return a.start != b.start ? a.start < b.start : a.end < b.end;
    });
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    EXPECT_EQ(set.instances, expected) << "round " << round;
  }
}

TEST(MovingSpanTest, StillHeadsAndTailsGoAndSoDoShortStretchesCutOffByAPause) {
  const std::vector<MotifInstance> pauses = {{0, 50}, {300, 340}, {400, 420}, {700, 800}};
  // No pause inside: unchanged.
  EXPECT_EQ(MovingSpan({100, 290}, pauses, 60), (MotifInstance{100, 290}));
  EXPECT_EQ(MovingSpan({50, 300}, pauses, 60), (MotifInstance{50, 300}));  // touching only
  // A still head, a still tail.
  EXPECT_EQ(MovingSpan({20, 200}, pauses, 60), (MotifInstance{50, 200}));
  EXPECT_EQ(MovingSpan({200, 330}, pauses, 60), (MotifInstance{200, 300}));
  // A pause inside stays: only the ends are trimmed.
  EXPECT_EQ(MovingSpan({100, 720}, pauses, 60), (MotifInstance{100, 700}));
  // A stretch shorter than lambda before the first pause (the end of the movement before) goes;
  // [340, 400) is 60 frames, long enough.
  EXPECT_EQ(MovingSpan({250, 600}, pauses, 60), (MotifInstance{340, 600}));
  EXPECT_EQ(MovingSpan({250, 600}, pauses, 61), (MotifInstance{420, 600}));
  // Nothing but pauses and short stretches: no movement.
  EXPECT_EQ(MovingSpan({290, 425}, pauses, 61), std::nullopt);
  EXPECT_EQ(MovingSpan({710, 790}, pauses, 1), std::nullopt);
  // No pauses at all.
  EXPECT_EQ(MovingSpan({710, 790}, {}, 60), (MotifInstance{710, 790}));
}

TEST(BuildInstancesTest, InstancesAreTrimmedToTheirMovementAndStillOnesDropWithTheirLinks) {
  InstanceOptions options;
  options.min_length = 60;
  options.pauses = {{180, 260}, {1000, 1200}};
  InstanceSet set = BuildInstances(
      {
          Path(100, 260, 500, 660, 100, 500),        // a still tail: [100, 180) and [500, 660)
          Path(1000, 1200, 1500, 1700, 1000, 1500),  // all still on top: both dropped
      },
      options);
  ASSERT_EQ(set.instances.size(), 3u);
  EXPECT_EQ(set.instances[0], (MotifInstance{100, 180}));
  EXPECT_EQ(set.instances[1], (MotifInstance{500, 660}));
  EXPECT_EQ(set.instances[2], (MotifInstance{1500, 1700}));  // alone: its link went
  ASSERT_EQ(set.links.size(), 1u);
  EXPECT_EQ(set.links[0], (InstanceLink{0, 1}));
  EXPECT_EQ(set.stats.trimmed_instances, 1u);
  EXPECT_EQ(set.stats.still_instances, 1u);
  EXPECT_EQ(set.stats.raw_instances, 3u);
}

}  // namespace
}  // namespace motif
