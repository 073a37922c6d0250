#include "engine/distance/exact_search.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "engine/distance/epsilon_estimator.h"
#include "tests/engine/distance/distance_test_util.h"

namespace motif {
namespace {

using Columns = std::vector<std::vector<Neighbour>>;

// The trellis columns by definition: every pair through the scalar PoseDistance and
// NeighbourRules::Excluded, the k_max nearest (distance, then frame), sorted by frame.
Columns DirectDoubleLoop(const PoseFeatures& features, const NeighbourRules& rules,
                         uint64_t first_column, uint64_t count) {
  Columns columns(count);
  for (uint64_t t = first_column; t < first_column + count; ++t) {
    std::vector<Neighbour> within;
    for (uint64_t j = 0; j < features.frame_count(); ++j) {
      if (rules.Excluded(t, j, features.ClipOf(t), features.ClipOf(j))) continue;
      const float distance = PoseDistance(features, t, j);
      if (distance <= rules.eps) within.push_back(Neighbour{static_cast<uint32_t>(j), distance});
    }
    std::sort(within.begin(), within.end(), [](const Neighbour& a, const Neighbour& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
    });
    if (within.size() > rules.k_max) within.resize(rules.k_max);
    std::sort(within.begin(), within.end(),
              [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
    columns[t - first_column] = std::move(within);
  }
  return columns;
}

Columns Search(const PoseFeatures& features, const NeighbourRules& rules, uint64_t first_column,
               uint64_t count, ExactSearchOptions options = {}, SearchStats* stats = nullptr) {
  const ExactSearch search(features, rules, options);
  Columns columns;
  SearchStats local;
  const Status status = search.SearchColumns(first_column, count, &columns, stats ? stats : &local);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return columns;
}

// One synthetic archive (~4000 frames, clips of 5-12 s) shared by the read-only tests.
const testing::ArchiveRows& SharedArchive() {
  static const auto* archive = new testing::ArchiveRows(testing::SynthArchive(4000, 31));
  return *archive;
}

NeighbourRules RulesFor(const PoseFeatures& features, float eps, uint32_t k_max = 100000) {
  NeighbourRules rules;
  rules.eps = eps;
  rules.k_max = k_max;
  rules.exclusion_frames = 30;
  rules.clip_first_frames = features.clip_first_frames();
  return rules;
}

TEST(ExactSearch, MatchesADirectDoubleLoop) {
  const PoseFeatures features = SharedArchive().Features();
  ASSERT_GE(features.clip_first_frames().size(), 4u);
  EpsilonEstimator estimator(features, RulesFor(features, 0));
  Result<EpsilonEstimate> estimate = estimator.Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  const NeighbourRules rules = RulesFor(features, estimate->eps);
  // Every column of two stretches: the archive's start and a clip boundary.
  const uint64_t boundary = features.clip_first_frames()[2];
  for (uint64_t first : {uint64_t{0}, boundary - 150}) {
    const Columns expected = DirectDoubleLoop(features, rules, first, 300);
    const Columns actual = Search(features, rules, first, 300);
    ASSERT_EQ(actual.size(), expected.size());
    uint64_t neighbours = 0;
    for (size_t column = 0; column < expected.size(); ++column) {
      ASSERT_EQ(actual[column], expected[column]) << "column " << first + column;
      neighbours += expected[column].size();
    }
    EXPECT_GT(neighbours, 300u) << "the test needs columns with neighbours";
  }
}

TEST(ExactSearch, MatchesADirectDoubleLoopOnHandMadeRows) {
  // Six one-joint frames in two clips (0-3, 4-5), rotations about X by the given angles:
  // D = 2 sin(angle between / 4) for one joint of weight 1, so eps = 0.2 reaches 22.9 degrees.
  // 350 degrees is -10 degrees with the quaternion's sign flipped.
  const double angles_degrees[] = {0, 10, 20, 350, 12, 0};
  std::vector<float> rows;
  for (double degrees : angles_degrees) {
    const double half = DegreesToRadians(degrees) / 2;
    rows.insert(rows.end(), {static_cast<float>(std::cos(half)), static_cast<float>(std::sin(half)),
                             0.0f, 0.0f, 0, 0, 0, 0});
  }
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 6, 1, {1.0f}, {0, 4});
  NeighbourRules rules = RulesFor(features, 0.2f);
  rules.exclusion_frames = 2;
  const Columns columns = Search(features, rules, 0, 6);
  EXPECT_EQ(columns, DirectDoubleLoop(features, rules, 0, 6));
  auto frames = [&](uint64_t column) {
    std::vector<uint32_t> result;
    for (const Neighbour& neighbour : columns[column]) result.push_back(neighbour.frame);
    return result;
  };
  EXPECT_EQ(frames(0), (std::vector<uint32_t>{2, 3, 4, 5}));  // 1: same clip, 1 frame away
  EXPECT_EQ(frames(1), (std::vector<uint32_t>{3, 4, 5}));     // 3: 20 degrees (sign-flipped)
  EXPECT_EQ(frames(2), (std::vector<uint32_t>{0, 4, 5}));     // 3: 30 degrees
  EXPECT_EQ(frames(3), (std::vector<uint32_t>{0, 1, 4, 5}));
  EXPECT_EQ(frames(4), (std::vector<uint32_t>{0, 1, 2, 3}));  // 5: same clip, 1 frame away
  EXPECT_NEAR(columns[0].back().distance, 0.0f, 1e-6);
  EXPECT_NEAR(columns[0][0].distance, 2 * std::sin(DegreesToRadians(20) / 4), 1e-4);
}

TEST(ExactSearch, AFrameIsNeverItsOwnNeighbourNorNearItInItsClip) {
  const PoseFeatures features = SharedArchive().Features();
  // eps so large that everything else is a neighbour.
  const NeighbourRules rules = RulesFor(features, 1000.0f);
  const uint64_t first = features.clip_first_frames()[1] - 40;
  const Columns columns = Search(features, rules, first, 80);
  for (uint64_t column = 0; column < columns.size(); ++column) {
    const uint64_t t = first + column;
    uint64_t excluded = 0;
    for (uint64_t j = 0; j < features.frame_count(); ++j) {
      excluded += rules.Excluded(t, j, features.ClipOf(t), features.ClipOf(j));
    }
    EXPECT_EQ(columns[column].size(), features.frame_count() - excluded) << t;
    for (const Neighbour& neighbour : columns[column]) {
      ASSERT_NE(neighbour.frame, t);
      if (features.ClipOf(neighbour.frame) == features.ClipOf(t)) {
        const uint64_t gap = neighbour.frame > t ? neighbour.frame - t : t - neighbour.frame;
        ASSERT_GE(gap, 30u) << t << " " << neighbour.frame;
      }
    }
  }
}

TEST(ExactSearch, OtherClipsAreNeighboursAtAnyFrameDistance) {
  // Four identical frames: clips [0, 2) and [2, 4). Frame 1's neighbour 2 is one frame away,
  // but in another clip.
  std::vector<float> rows;
  for (int frame_idx = 0; frame_idx < 4; ++frame_idx)
    rows.insert(rows.end(), {1, 0, 0, 0, 0, 0, 0, 0});
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 4, 1, {1.0f}, {0, 2});
  const NeighbourRules rules = RulesFor(features, 0.0f);
  const Columns columns = Search(features, rules, 0, 4);
  EXPECT_EQ(columns[1], (std::vector<Neighbour>{{2, 0.0f}, {3, 0.0f}}));
  EXPECT_EQ(columns[2], (std::vector<Neighbour>{{0, 0.0f}, {1, 0.0f}}));
  // Without an exclusion radius only the frame itself is excluded.
  NeighbourRules no_radius = rules;
  no_radius.exclusion_frames = 0;
  EXPECT_EQ(Search(features, no_radius, 1, 1)[0],
            (std::vector<Neighbour>{{0, 0.0f}, {2, 0.0f}, {3, 0.0f}}));
}

TEST(ExactSearch, KMaxKeepsTheNearestSortedByFrame) {
  const PoseFeatures features = SharedArchive().Features();
  const NeighbourRules all = RulesFor(features, 3.0f);
  const NeighbourRules capped = RulesFor(features, 3.0f, 16);
  SearchStats stats;
  const Columns full = Search(features, all, 500, 64);
  const Columns kept = Search(features, capped, 500, 64, {}, &stats);
  uint64_t capped_columns = 0;
  for (size_t column = 0; column < full.size(); ++column) {
    std::vector<Neighbour> nearest = full[column];
    std::sort(nearest.begin(), nearest.end(), [](const Neighbour& a, const Neighbour& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
    });
    capped_columns += nearest.size() > 16;
    if (nearest.size() > 16) nearest.resize(16);
    std::sort(nearest.begin(), nearest.end(),
              [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
    EXPECT_EQ(kept[column], nearest) << "column " << 500 + column;
  }
  EXPECT_GT(capped_columns, 32u) << "the test needs capped columns";
  EXPECT_EQ(stats.capped_columns, capped_columns);
  EXPECT_EQ(stats.columns, 64u);
  EXPECT_EQ(stats.distance_evaluations, 64u * features.frame_count());
  uint64_t neighbours = 0;
  for (const auto& column : kept) neighbours += column.size();
  EXPECT_EQ(stats.neighbours, neighbours);
}

TEST(ExactSearch, KMaxTiesKeepTheLowerFrames) {
  // Ten identical frames in ten clips: every other frame is at distance 0.
  std::vector<float> rows;
  std::vector<uint64_t> clips;
  for (uint64_t frame_idx = 0; frame_idx < 10; ++frame_idx) {
    rows.insert(rows.end(), {0.5f, 0.5f, 0.5f, 0.5f, 0, 0, 0, 0});
    clips.push_back(frame_idx);
  }
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 10, 1, {1.0f}, clips);
  const Columns columns = Search(features, RulesFor(features, 0.5f, 3), 0, 10);
  EXPECT_EQ(columns[0], (std::vector<Neighbour>{{1, 0.0f}, {2, 0.0f}, {3, 0.0f}}));
  EXPECT_EQ(columns[2], (std::vector<Neighbour>{{0, 0.0f}, {1, 0.0f}, {3, 0.0f}}));
  EXPECT_EQ(columns[9], (std::vector<Neighbour>{{0, 0.0f}, {1, 0.0f}, {2, 0.0f}}));
}

TEST(ExactSearch, SameColumnsForAnyThreadCountAndBlockSizes) {
  const PoseFeatures features = SharedArchive().Features();
  const NeighbourRules rules = RulesFor(features, 1.2f, 40);
  ExactSearchOptions one_thread;
  one_thread.threads = 1;
  SearchStats stats_one;
  const Columns expected = Search(features, rules, 100, 700, one_thread, &stats_one);
  for (ExactSearchOptions options : {ExactSearchOptions{2, 64, 1024}, ExactSearchOptions{2, 7, 33},
                                     ExactSearchOptions{2, 1000, 5000}}) {
    SearchStats stats;
    EXPECT_EQ(Search(features, rules, 100, 700, options, &stats), expected)
        << options.query_block_frames << " " << options.candidate_block_frames;
    EXPECT_EQ(stats.neighbours, stats_one.neighbours);
    EXPECT_EQ(stats.capped_columns, stats_one.capped_columns);
  }
}

TEST(ExactSearch, PruningLargeColumnsKeepsTheSameNearest) {
  // eps covering everything, k_max small: columns are pruned as they grow (> 1024 entries).
  const PoseFeatures features = SharedArchive().Features();
  const NeighbourRules rules = RulesFor(features, 1000.0f, 5);
  EXPECT_EQ(Search(features, rules, 2000, 20), DirectDoubleLoop(features, rules, 2000, 20));
}

TEST(ExactSearch, RejectsColumnsOutsideTheArchiveAndABadEps) {
  const std::vector<float> rows = testing::RandomRows(50, 1, 3);
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 50, 1, {1.0f}, {0});
  Columns columns;
  SearchStats stats;
  EXPECT_TRUE(ExactSearch(features, RulesFor(features, 1.0f))
                  .SearchColumns(40, 11, &columns, &stats)
                  .IsInvalidArgument());
  EXPECT_TRUE(ExactSearch(features, RulesFor(features, -1.0f))
                  .SearchColumns(0, 1, &columns, &stats)
                  .IsInvalidArgument());
  NeighbourRules bad_clips = RulesFor(features, 1.0f);
  bad_clips.clip_first_frames = {5, 2};
  EXPECT_TRUE(
      ExactSearch(features, bad_clips).SearchColumns(0, 1, &columns, &stats).IsInvalidArgument());
  EXPECT_EQ(stats.columns, 0u);
  ASSERT_TRUE(
      ExactSearch(features, RulesFor(features, 1.0f)).SearchColumns(50, 0, &columns, &stats).ok());
  // Clips default to the archive's.
  NeighbourRules no_clips = RulesFor(features, 1.0f);
  no_clips.clip_first_frames.clear();
  EXPECT_EQ(ExactSearch(features, no_clips).rules().clip_first_frames,
            features.clip_first_frames());
}

TEST(ExactSearch, ExclusionRangeAgreesWithNeighbourRules) {
  const std::vector<uint64_t> clips = {0, 5, 5, 6, 40, 41};
  const uint64_t frame_count = 100;
  for (uint32_t radius : {0u, 1u, 2u, 7u, 30u, 200u}) {
    NeighbourRules rules;
    rules.exclusion_frames = radius;
    rules.clip_first_frames = clips;
    auto clip_of = [&](uint64_t frame) {
      return static_cast<uint32_t>(std::upper_bound(clips.begin(), clips.end(), frame) -
                                   clips.begin() - 1);
    };
    for (uint64_t t = 0; t < frame_count; ++t) {
      const ExclusionRange range = ExclusionRangeOf(rules, t, frame_count);
      for (uint64_t j = 0; j < frame_count; ++j) {
        ASSERT_EQ(range.Contains(j), rules.Excluded(t, j, clip_of(t), clip_of(j)))
            << "radius " << radius << " t " << t << " j " << j;
      }
    }
  }
}

}  // namespace
}  // namespace motif
