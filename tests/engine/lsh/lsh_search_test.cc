// LshSearch against the exact eps-neighbour columns (a direct double loop with the scalar
// PoseDistance): recall after the k_max cap on a synthetic archive and on the real CMU takes,
// the trellis rules, determinism across thread counts, heavy buckets and quaternion signs.
#include "engine/lsh/lsh_search.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <memory>

#include "engine/lsh/lsh_tuning.h"
#include "tests/engine/lsh/lsh_test_util.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

using testing::ExactColumn;
using testing::Recall;
using testing::RecallStats;

std::unique_ptr<LshSearch> CreateSearch(const PoseFeatures& features, const NeighbourRules& rules,
                                        const LshOptions& options = LshOptions()) {
  auto search = LshSearch::Create(features, rules, options);
  EXPECT_TRUE(search.ok()) << search.status().ToString();
  return search.ok() ? std::move(*search) : nullptr;
}

// One search per set of options, in order (null, with a failure, where creation fails).
std::vector<std::unique_ptr<LshSearch>> CreateSearches(const PoseFeatures& features,
                                                       const NeighbourRules& rules,
                                                       const std::vector<LshOptions>& options) {
  std::vector<std::unique_ptr<LshSearch>> searches;
  for (const LshOptions& one : options) searches.push_back(CreateSearch(features, rules, one));
  return searches;
}

std::vector<Neighbour> Column(const LshSearch& search, uint64_t column, SearchStats* stats,
                              LshQueryStats* lsh_stats = nullptr) {
  std::vector<std::vector<Neighbour>> columns;
  const Status status = search.SearchColumns(column, 1, &columns, stats, lsh_stats);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return columns.empty() ? std::vector<Neighbour>() : columns[0];
}

// The exact columns [first, first + count) (the direct double loop).
std::vector<std::vector<Neighbour>> ExactBlock(const PoseFeatures& features,
                                               const NeighbourRules& rules, uint64_t first,
                                               uint64_t count) {
  std::vector<std::vector<Neighbour>> exact;
  for (uint64_t column = first; column < first + count; ++column) {
    exact.push_back(ExactColumn(features, rules, column));
  }
  return exact;
}

// Recall over `count` sampled columns, and the work the search did for them.
struct Measured {
  RecallStats recall;
  SearchStats stats;
  double exact_neighbours_per_column = 0;
};

// The LSH columns come from one search of the whole archive (a column is computed with its whole
// chain anyway), so the work counted is that of every column.
Measured MeasureRecall(const LshSearch& search, const PoseFeatures& features,
                       const NeighbourRules& rules, uint32_t count, uint64_t seed) {
  Measured measured;
  const std::vector<uint64_t> columns = testing::SampleColumns(features.frame_count(), count, seed);
  std::vector<std::vector<Neighbour>> all;
  const Status status = search.SearchColumns(0, features.frame_count(), &all, &measured.stats);
  EXPECT_TRUE(status.ok()) << status.ToString();
  std::vector<std::vector<Neighbour>> exact;
  std::vector<std::vector<Neighbour>> approximate;
  for (uint64_t column : columns) {
    exact.push_back(ExactColumn(features, rules, column));
    approximate.push_back(all[column]);
    measured.exact_neighbours_per_column += exact.back().size();
  }
  measured.exact_neighbours_per_column /= columns.size();
  measured.recall = Recall(exact, approximate);
  return measured;
}

void Report(const char* what, const Measured& measured, const LshSearch& search) {
  std::printf(
      "%s: recall %.4f (per-column mean %.4f, worst %.3f), exact neighbours/column %.1f, "
      "distance evaluations/column %.0f\n  %s\n",
      what, measured.recall.pooled(), measured.recall.column_mean, measured.recall.worst_column,
      measured.exact_neighbours_per_column,
      static_cast<double>(measured.stats.distance_evaluations) / measured.stats.columns,
      search.DescribeParams().c_str());
}

class LshSearchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(30000, 7));
    rules_ = new NeighbourRules(testing::RulesWithEstimatedEps(*features_));
  }
  static void TearDownTestSuite() {
    delete features_;
    delete rules_;
    features_ = nullptr;
    rules_ = nullptr;
  }
  static PoseFeatures* features_;
  static NeighbourRules* rules_;
};

PoseFeatures* LshSearchTest::features_ = nullptr;
NeighbourRules* LshSearchTest::rules_ = nullptr;

TEST_F(LshSearchTest, RecallOnSyntheticArchive) {
  auto search = CreateSearch(*features_, *rules_);
  ASSERT_NE(search, nullptr);
  const Measured measured = MeasureRecall(*search, *features_, *rules_, 300, 5);
  Report("synthetic 30k", measured, *search);
  RecordProperty("recall", std::to_string(measured.recall.pooled()));
  EXPECT_GE(measured.recall.pooled(), 0.95);
  EXPECT_GE(measured.recall.column_mean, 0.95);
  EXPECT_GT(measured.exact_neighbours_per_column, 50) << "eps too small for a meaningful test";
  // Sub-quadratic: far fewer distance evaluations than frames per column.
  EXPECT_LT(measured.stats.distance_evaluations,
            measured.stats.columns * features_->frame_count() / 5);
}

// Ranking the gathered entries by position code: at least the recall of the sort-value scan
// with the same verification budget, on the same columns.
TEST_F(LshSearchTest, RankingByPositionCodeKeepsRecallWithHalfTheBudget) {
  LshOptions by_code;
  by_code.ranking = LshRanking::kPositionCode;
  by_code.max_candidates = 2048;
  LshOptions by_sort = by_code;
  by_sort.ranking = LshRanking::kSortValue;
  auto code_search = CreateSearch(*features_, *rules_, by_code);
  auto sort_search = CreateSearch(*features_, *rules_, by_sort);
  ASSERT_NE(code_search, nullptr);
  ASSERT_NE(sort_search, nullptr);
  EXPECT_FALSE(code_search->index().table(0).codes.empty());
  EXPECT_TRUE(sort_search->index().table(0).codes.empty()) << "codes only when they are used";
  const Measured code = MeasureRecall(*code_search, *features_, *rules_, 200, 5);
  const Measured sort = MeasureRecall(*sort_search, *features_, *rules_, 200, 5);
  Report("synthetic 30k, ranked by code, budget 2048", code, *code_search);
  Report("synthetic 30k, sort-value scan, budget 2048", sort, *sort_search);
  EXPECT_GE(code.recall.pooled(), 0.95);
  EXPECT_GE(code.recall.pooled(), sort.recall.pooled() - 0.005);
  EXPECT_LE(code.stats.distance_evaluations, code.stats.columns * 2048);
  // Deterministic across thread counts too.
  LshOptions two = by_code;
  two.threads = 2;
  two.shard_frames = 7000;
  by_code.threads = 1;
  auto one_thread = CreateSearch(*features_, *rules_, by_code);
  auto two_threads = CreateSearch(*features_, *rules_, two);
  ASSERT_NE(one_thread, nullptr);
  ASSERT_NE(two_threads, nullptr);
  std::vector<std::vector<Neighbour>> a;
  std::vector<std::vector<Neighbour>> b;
  SearchStats stats_a;
  SearchStats stats_b;
  ASSERT_TRUE(one_thread->SearchColumns(2000, 1000, &a, &stats_a).ok());
  ASSERT_TRUE(two_threads->SearchColumns(2000, 1000, &b, &stats_b).ok());
  EXPECT_EQ(a, b);
  EXPECT_EQ(stats_a.distance_evaluations, stats_b.distance_evaluations);
}

TEST(LshSearchRealTakes, RecallOnRealCmuTakes) {
  MOTIF_REQUIRE_MOCAP_DATA();
  auto features = testing::RealTakeFeatures(::motif::testing::MocapDir() + "/bvh");
  ASSERT_TRUE(features.ok()) << features.status().ToString();
  EXPECT_GT(features->frame_count(), 30000u);
  const NeighbourRules rules = testing::RulesWithEstimatedEps(*features);
  // mu - 2 sigma on these takes is 1.02: docs/design/algorithm.md section 6.2, measured by
  // EpsilonEstimator.ReproducesTheMeasuredFiguresOnTheRealTakes.
  EXPECT_NEAR(rules.eps, 1.02, 0.1) << "eps = mu - 2 sigma, docs/design/algorithm.md 6.2";
  auto search = CreateSearch(*features, rules);
  ASSERT_NE(search, nullptr);
  const Measured measured = MeasureRecall(*search, *features, rules, 300, 9);
  Report("real CMU BVH takes", measured, *search);
  RecordProperty("recall", std::to_string(measured.recall.pooled()));
  EXPECT_GE(measured.recall.pooled(), 0.95);
  EXPECT_GE(measured.recall.column_mean, 0.95);
}

TEST_F(LshSearchTest, ColumnsFollowTheTrellisRules) {
  NeighbourRules rules = *rules_;
  rules.exclusion_frames = 45;
  auto search = CreateSearch(*features_, rules);
  ASSERT_NE(search, nullptr);
  // A range across the first clip boundary, plus the archive's last frames.
  const uint64_t boundary = features_->clip_first_frames().at(1);
  for (const auto& [first, count] :
       {std::pair<uint64_t, uint64_t>{boundary - 300, 600},
        std::pair<uint64_t, uint64_t>{features_->frame_count() - 200, 200}}) {
    std::vector<std::vector<Neighbour>> columns;
    SearchStats stats;
    ASSERT_TRUE(search->SearchColumns(first, count, &columns, &stats).ok());
    EXPECT_EQ(stats.columns, count);
    uint64_t total = 0;
    for (uint64_t offset = 0; offset < count; ++offset) {
      const uint64_t column = first + offset;
      const std::vector<Neighbour>& neighbours = columns[offset];
      ASSERT_LE(neighbours.size(), rules.k_max);
      total += neighbours.size();
      for (size_t idx = 0; idx < neighbours.size(); ++idx) {
        const Neighbour& neighbour = neighbours[idx];
        ASSERT_NE(neighbour.frame, column) << "a frame is never its own neighbour";
        ASSERT_FALSE(rules.Excluded(column, neighbour.frame, features_->ClipOf(column),
                                    features_->ClipOf(neighbour.frame)))
            << column << " -> " << neighbour.frame;
        ASSERT_LE(neighbour.distance, rules.eps);
        const float exact = PoseDistance(*features_, column, neighbour.frame);
        ASSERT_EQ(std::memcmp(&exact, &neighbour.distance, sizeof(float)), 0)
            << "every candidate is verified with the exact D";
        if (idx > 0) {
          ASSERT_LT(neighbours[idx - 1].frame, neighbour.frame) << "sorted, unique";
        }
      }
    }
    EXPECT_EQ(stats.neighbours, total);
    EXPECT_GT(total, 0u);
  }
}

TEST_F(LshSearchTest, KeepsAtMostKMaxNearest) {
  NeighbourRules rules = *rules_;
  rules.k_max = 12;
  auto search = CreateSearch(*features_, rules);
  ASSERT_NE(search, nullptr);
  const Measured measured = MeasureRecall(*search, *features_, rules, 150, 13);
  Report("k_max 12", measured, *search);
  EXPECT_GE(measured.recall.pooled(), 0.95);
  EXPECT_GT(measured.stats.capped_columns, measured.stats.columns / 2);
  const std::vector<uint64_t> columns = testing::SampleColumns(features_->frame_count(), 50, 3);
  for (uint64_t column : columns) {
    SearchStats stats;
    EXPECT_LE(Column(*search, column, &stats).size(), 12u);
  }
}

// On an archive of its own, a third the size of the suite's, because ThreadSanitizer runs this
// test (docs/reliability.md, "Build and test time"): 2 shards of 5,000 frames against 1.
TEST(LshSearchThreads, SameColumnsForOneAndTwoThreads) {
  const PoseFeatures features = testing::SyntheticFeatures(10000, 7);
  const NeighbourRules rules = testing::RulesWithEstimatedEps(features);
  LshOptions one;
  one.threads = 1;
  one.shard_frames = 5000;
  LshOptions two = one;
  two.threads = 2;
  two.shard_frames = 1 << 16;
  auto serial = CreateSearch(features, rules, one);
  auto parallel = CreateSearch(features, rules, two);
  ASSERT_NE(serial, nullptr);
  ASSERT_NE(parallel, nullptr);
  EXPECT_EQ(serial->options().bucket_width, parallel->options().bucket_width);
  for (uint32_t table_idx = 0; table_idx < serial->index().table_count(); ++table_idx) {
    EXPECT_EQ(serial->index().table(table_idx).frames, parallel->index().table(table_idx).frames);
    EXPECT_EQ(serial->index().table(table_idx).keys, parallel->index().table(table_idx).keys);
  }
  std::vector<std::vector<Neighbour>> a;
  std::vector<std::vector<Neighbour>> b;
  SearchStats stats_a;
  SearchStats stats_b;
  ASSERT_TRUE(serial->SearchColumns(1000, 1500, &a, &stats_a).ok());
  ASSERT_TRUE(parallel->SearchColumns(1000, 1500, &b, &stats_b).ok());
  EXPECT_EQ(a, b);
  EXPECT_EQ(stats_a.distance_evaluations, stats_b.distance_evaluations);
  EXPECT_EQ(stats_a.neighbours, stats_b.neighbours);
  EXPECT_EQ(stats_a.capped_columns, stats_b.capped_columns);
  // Another seed draws other functions.
  LshOptions reseeded = two;
  reseeded.seed = 12345;
  auto other = CreateSearch(features, rules, reseeded);
  ASSERT_NE(other, nullptr);
  EXPECT_NE(other->index().table(0).keys, parallel->index().table(0).keys);
  EXPECT_NE(serial->DescribeParams(), other->DescribeParams());
}

// Chained columns depend on their predecessors in an aligned chain: a column must come out the
// same whether a range starts at it, inside its chain or before it.
TEST_F(LshSearchTest, ChainedColumnsDoNotDependOnTheRangeThatAskedForThem) {
  LshOptions options;
  options.chain_columns = 64;
  options.threads = 2;
  auto search = CreateSearch(*features_, *rules_, options);
  ASSERT_NE(search, nullptr);
  std::vector<std::vector<Neighbour>> whole;
  SearchStats whole_stats;
  ASSERT_TRUE(search->SearchColumns(1000, 700, &whole, &whole_stats).ok());
  EXPECT_EQ(whole_stats.columns, 700u);
  // Split at 1037 (inside the chain [1024, 1088)) and at 1100.
  std::vector<std::vector<Neighbour>> part;
  std::vector<std::vector<Neighbour>> pieces;
  for (auto [first, count] : {std::pair<uint64_t, uint64_t>{1000, 37}, {1037, 63}, {1100, 600}}) {
    SearchStats stats;
    ASSERT_TRUE(search->SearchColumns(first, count, &part, &stats).ok());
    EXPECT_EQ(stats.columns, count);
    pieces.insert(pieces.end(), part.begin(), part.begin() + static_cast<ptrdiff_t>(count));
  }
  EXPECT_EQ(pieces, whole);
  for (uint64_t column : {1000u, 1024u, 1025u, 1087u, 1500u, 1699u}) {
    SearchStats stats;
    EXPECT_EQ(Column(*search, column, &stats), whole[column - 1000]) << "column " << column;
    EXPECT_EQ(stats.columns, 1u);
  }
}

// Chaining seeds each column with its predecessor's neighbours advanced by 0..2 frames: on the
// same columns and with the same probed-bucket budget, it finds at least as many of the exact
// neighbours, and with half of that budget for the probes it still keeps recall >= 0.95.
TEST_F(LshSearchTest, ChainingSeedsColumnsWithTheirPredecessorsNeighbours) {
  LshOptions alone;
  alone.chain_columns = 0;
  alone.max_candidates = 512;  // tight, so that the seeds' contribution shows
  alone.probes_per_table = 8;
  LshOptions chained = alone;
  chained.chain_columns = 64;
  chained.chained_max_candidates = 512;
  LshOptions cheap = chained;
  cheap.chained_max_candidates = 256;
  const auto searches = CreateSearches(*features_, *rules_, {alone, chained, cheap});
  for (const auto& search : searches) ASSERT_NE(search, nullptr);
  const LshSearch& search_alone = *searches[0];
  const LshSearch& search_chained = *searches[1];
  const LshSearch& search_cheap = *searches[2];
  // A block of consecutive columns: where chaining acts.
  const uint64_t first = 12800;
  const uint64_t count = 256;
  const std::vector<std::vector<Neighbour>> exact = ExactBlock(*features_, *rules_, first, count);
  auto measure = [&](const LshSearch& search, const char* what) {
    std::vector<std::vector<Neighbour>> columns;
    SearchStats stats;
    LshQueryStats lsh_stats;
    EXPECT_TRUE(search.SearchColumns(first, count, &columns, &stats, &lsh_stats).ok());
    const RecallStats recall = Recall(exact, columns);
    std::printf("%s: recall %.4f, evaluations/column %.0f (seeds %.0f)\n", what, recall.pooled(),
                static_cast<double>(stats.distance_evaluations) / count,
                static_cast<double>(lsh_stats.seed_evaluations) / count);
    return std::make_pair(recall.pooled(), lsh_stats);
  };
  const auto [recall_alone, stats_alone] = measure(search_alone, "alone, 512");
  const auto [recall_chained, stats_chained] = measure(search_chained, "chained, 512");
  const auto [recall_cheap, stats_cheap] = measure(search_cheap, "chained, 256");
  EXPECT_EQ(stats_alone.seed_evaluations, 0u);
  EXPECT_GT(stats_chained.seed_evaluations, 0u);
  EXPECT_GE(recall_chained, recall_alone);
  EXPECT_GE(recall_chained, 0.97);
  EXPECT_GE(recall_cheap, 0.95);
  // The cheap chain examines fewer bucket entries than the unchained search.
  EXPECT_LT(stats_cheap.entries_examined, stats_alone.entries_examined);
}

// chain_probe_every: only columns 0, S, 2S, ... of a chain probe the buckets; the others keep
// their seeds and what the sweeps carry over. Against every column probing with a quarter of
// the budget (the same probing evaluations per chain), far fewer buckets are opened (each is a
// directory lookup, a binary search and a cache miss), and the columns lose no recall: adjacent
// columns would have probed nearly the same buckets, and one deeper search finds more new
// paths.
TEST_F(LshSearchTest, ChainProbeEveryProbesEveryNthColumnAndTheSweepsCarryTheRest) {
  LshOptions every;
  every.chain_columns = 64;
  every.chain_probe_every = 1;
  every.max_candidates = 512;
  every.chained_max_candidates = 128;
  LshOptions fourth = every;
  fourth.chain_probe_every = 4;
  fourth.chained_max_candidates = 512;
  const auto searches = CreateSearches(*features_, *rules_, {every, fourth});
  for (const auto& search : searches) ASSERT_NE(search, nullptr);
  const uint64_t first = 12800;  // a multiple of 64: whole chains
  const uint64_t count = 256;
  const std::vector<std::vector<Neighbour>> exact = ExactBlock(*features_, *rules_, first, count);
  auto run = [&](const LshSearch& search, const char* what) {
    std::vector<std::vector<Neighbour>> columns;
    SearchStats stats;
    LshQueryStats lsh_stats;
    EXPECT_TRUE(search.SearchColumns(first, count, &columns, &stats, &lsh_stats).ok());
    const double recall = Recall(exact, columns).pooled();
    std::printf("%s: recall %.4f, buckets opened/column %.1f, evaluations/column %.0f\n", what,
                recall, static_cast<double>(lsh_stats.probes) / count,
                static_cast<double>(stats.distance_evaluations) / count);
    return std::make_pair(recall, lsh_stats);
  };
  const auto [recall_every, stats_every] = run(*searches[0], "every column, 128");
  const auto [recall_fourth, stats_fourth] = run(*searches[1], "every 4th column, 512");
  EXPECT_LT(stats_fourth.probes * 3, stats_every.probes * 2);
  EXPECT_GE(recall_fourth, recall_every - 0.005);
  EXPECT_GE(recall_fourth, 0.95);

  // A column that does not probe depends on its chain only: searching it alone (its chain is
  // computed whole) gives the same column as the block did.
  std::vector<std::vector<Neighbour>> block;
  SearchStats ignored;
  ASSERT_TRUE(searches[1]->SearchColumns(first, count, &block, &ignored).ok());
  for (uint64_t offset : {1u, 2u, 3u, 4u, 5u, 130u}) {
    EXPECT_EQ(Column(*searches[1], first + offset, &ignored), block[offset]) << offset;
  }
}

// Chain sweeps: after a chain's columns are found, a backward sweep lets every column verify its
// successor's neighbours moved back by 0..chain_advance frames, so a path found late in a chain
// reaches its earlier columns. After one backward sweep each column is closed under that move
// (every such frame within eps is in it, or the column is full of nearer ones), and with a tight
// budget the sweeps find more of the exact neighbours on the same columns.
TEST_F(LshSearchTest, ChainSweepsCarryPathsFoundLateToTheWholeChain) {
  LshOptions none;
  none.chain_columns = 64;
  none.chain_sweeps = 0;
  none.max_candidates = 512;  // tight, so that what the sweeps add shows
  none.chained_max_candidates = 256;
  LshOptions backward = none;
  backward.chain_sweeps = 1;
  LshOptions both = none;
  both.chain_sweeps = 4;
  const auto searches = CreateSearches(*features_, *rules_, {none, backward, both});
  for (const auto& search : searches) ASSERT_NE(search, nullptr);
  const uint64_t first = 12800;  // a multiple of 64: whole chains
  const uint64_t count = 256;
  const std::vector<std::vector<Neighbour>> exact = ExactBlock(*features_, *rules_, first, count);
  auto run = [&](const LshSearch& search, std::vector<std::vector<Neighbour>>* columns) {
    SearchStats stats;
    LshQueryStats lsh_stats;
    EXPECT_TRUE(search.SearchColumns(first, count, columns, &stats, &lsh_stats).ok());
    EXPECT_EQ(stats.columns, count);
    return lsh_stats;
  };
  std::vector<std::vector<Neighbour>> columns_none, columns_backward, columns_both;
  const LshQueryStats stats_none = run(*searches[0], &columns_none);
  const LshQueryStats stats_backward = run(*searches[1], &columns_backward);
  const LshQueryStats stats_both = run(*searches[2], &columns_both);
  EXPECT_EQ(stats_none.sweep_evaluations, 0u);
  EXPECT_GT(stats_backward.sweep_evaluations, 0u);
  EXPECT_GT(stats_both.sweep_evaluations, stats_backward.sweep_evaluations);
  const double recall_none = Recall(exact, columns_none).pooled();
  const double recall_backward = Recall(exact, columns_backward).pooled();
  const double recall_both = Recall(exact, columns_both).pooled();
  std::printf("sweeps 0: recall %.4f; 1 (backward): %.4f; 4: %.4f\n", recall_none, recall_backward,
              recall_both);
  EXPECT_GT(recall_backward, recall_none + 0.01);
  EXPECT_GE(recall_both, recall_backward);

  // Closure under the backward move, checked with the exact D on every column but a chain's last.
  const NeighbourRules& rules = *rules_;
  auto nearer = [](const Neighbour& a, const Neighbour& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
  };
  uint64_t checked = 0;
  for (uint64_t offset = 0; offset + 1 < count; ++offset) {
    const uint64_t column = first + offset;
    if ((column + 1) % 64 == 0) continue;  // a chain's last column has no successor in it
    const std::vector<Neighbour>& own = columns_backward[offset];
    Neighbour farthest{0, 0};
    for (const Neighbour& neighbour : own) {
      if (nearer(farthest, neighbour)) farthest = neighbour;
    }
    for (const Neighbour& next : columns_backward[offset + 1]) {
      for (uint32_t shift = 0; shift <= backward.chain_advance && shift <= next.frame; ++shift) {
        const uint32_t frame = next.frame - shift;
        if (rules.Excluded(column, frame, features_->ClipOf(column), features_->ClipOf(frame))) {
          continue;
        }
        const Neighbour candidate{frame, PoseDistance(*features_, column, frame)};
        if (candidate.distance > rules.eps) continue;
        const bool held = std::any_of(own.begin(), own.end(),
                                      [&](const Neighbour& n) { return n.frame == frame; });
        ASSERT_TRUE(held || (own.size() == rules.k_max && !nearer(candidate, farthest)))
            << "column " << column << " misses " << frame << " at " << candidate.distance;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, count * 100);
}

// Heavy buckets: a static pose held for thousands of frames (the T-pose a take starts with)
// lands in one bucket of every table. The work per column must stay within the caps, the
// static frames' columns must still be exact (distance 0, lowest frames first), and the other
// columns must not slow down.
void CheckHeavyBucket(LshRanking ranking) {
  const uint64_t motion_frames = 12000;
  const uint64_t static_frames = 6000;
  SynthOptions options;
  options.frames = motion_frames;
  options.seed = 31;
  options.motifs = 2;
  auto synthesizer = MotionSynthesizer::Create(options);
  ASSERT_TRUE(synthesizer.ok());
  std::vector<ClipFrames> clips;
  ASSERT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) {
                    clips.push_back(clip);
                    return Status::Ok();
                  })
                  .ok());
  const Skeleton& skeleton = (*synthesizer)->skeleton();
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  // Two takes that start with a long T-pose (identity rotations) and one that is only T-pose.
  ClipFrames t_pose;
  t_pose.rows.assign(static_frames / 2 * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < static_frames / 2; ++frame_idx) {
    for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
      t_pose.rows[frame_idx * layout.stride() + 4 * joint_idx] = 1.0f;
    }
  }
  std::vector<ClipFrames> with_static;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    ClipFrames clip = clips[clip_idx];
    if (clip_idx < 2) {
      const size_t static_rows = static_frames / 4 * layout.stride();
      clip.rows.insert(clip.rows.begin(), t_pose.rows.begin(), t_pose.rows.begin() + static_rows);
    }
    with_static.push_back(std::move(clip));
    if (clip_idx == 0) with_static.push_back(t_pose);
  }
  const PoseFeatures plain = testing::FeaturesFromClips(skeleton, clips);
  const PoseFeatures features = testing::FeaturesFromClips(skeleton, with_static);
  ASSERT_EQ(features.frame_count(), motion_frames + static_frames);
  NeighbourRules rules = testing::RulesWithEstimatedEps(plain);
  rules.clip_first_frames.clear();
  LshOptions lsh_options;
  lsh_options.max_candidates = 2048;
  lsh_options.max_bucket_scan = 1024;
  lsh_options.ranking = ranking;
  auto search = CreateSearch(features, rules, lsh_options);
  NeighbourRules plain_rules = rules;
  auto plain_search = CreateSearch(plain, plain_rules, lsh_options);
  ASSERT_NE(search, nullptr);
  ASSERT_NE(plain_search, nullptr);
  LshBucketStats largest;
  for (uint32_t table_idx = 0; table_idx < search->index().table_count(); ++table_idx) {
    const LshBucketStats stats = search->index().BucketStats(table_idx);
    if (stats.largest_bucket > largest.largest_bucket) largest = stats;
  }
  EXPECT_GE(largest.largest_bucket, static_frames) << "the static frames share one bucket";

  // The static frames' columns: all of the static frames are at distance 0; the exact column is
  // the k_max lowest of them outside the exclusion radius.
  const uint64_t first_clip_frames = clips[0].rows.size() / layout.stride() + static_frames / 4;
  const std::vector<uint64_t> static_columns = {0, 17, first_clip_frames + 5,
                                                first_clip_frames + 1500, first_clip_frames + 2999};
  SearchStats static_stats;
  LshQueryStats static_lsh;
  for (uint64_t column : static_columns) {
    const std::vector<Neighbour> found = Column(*search, column, &static_stats, &static_lsh);
    const std::vector<Neighbour> exact = ExactColumn(features, rules, column);
    ASSERT_EQ(exact.size(), rules.k_max);
    EXPECT_EQ(exact.back().distance, 0.0f);
    EXPECT_EQ(found, exact) << "column " << column;
  }
  EXPECT_LE(static_stats.distance_evaluations, static_columns.size() * lsh_options.max_candidates);
  // Entries read per column: at most max_bucket_scan per probed bucket, with every extension
  // stage (4x the probes each).
  uint64_t probes_per_column = search->options().probes_per_table;
  for (uint32_t stage = 0; stage < search->options().extension_stages; ++stage) {
    probes_per_column *= 4;
  }
  EXPECT_LE(static_lsh.entries_examined, static_columns.size() * search->index().table_count() *
                                             probes_per_column * lsh_options.max_bucket_scan);

  // Every column within the budget, and the moving frames' columns cost about what they cost
  // without the static frames.
  std::vector<std::vector<Neighbour>> columns;
  SearchStats all_stats;
  LshQueryStats all_lsh;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(
      search->SearchColumns(0, features.frame_count(), &columns, &all_stats, &all_lsh).ok());
  const double heavy_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const std::vector<Neighbour>& column : columns) ASSERT_LE(column.size(), rules.k_max);
  SearchStats plain_stats;
  std::vector<std::vector<Neighbour>> plain_columns;
  const auto plain_start = std::chrono::steady_clock::now();
  ASSERT_TRUE(
      plain_search->SearchColumns(0, plain.frame_count(), &plain_columns, &plain_stats).ok());
  const double plain_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - plain_start).count();
  const double heavy_per_column =
      static_cast<double>(all_stats.distance_evaluations) / all_stats.columns;
  const double plain_per_column =
      static_cast<double>(plain_stats.distance_evaluations) / plain_stats.columns;
  std::printf(
      "heavy bucket: largest bucket %llu entries; static columns: %.0f evaluations, %.0f entries "
      "read per column; all columns: %.0f evaluations (%.0f without the static frames), "
      "%.1f us per column (%.1f without)\n",
      static_cast<unsigned long long>(largest.largest_bucket),
      static_cast<double>(static_stats.distance_evaluations) / static_columns.size(),
      static_cast<double>(static_lsh.entries_examined) / static_columns.size(), heavy_per_column,
      plain_per_column, 1e6 * heavy_seconds / features.frame_count(),
      1e6 * plain_seconds / plain.frame_count());
  EXPECT_LE(all_stats.distance_evaluations, all_stats.columns * lsh_options.max_candidates);
  EXPECT_LE(heavy_per_column, 1.5 * plain_per_column + 64);
}

TEST(LshSearchHeavyBucket, StaticPoseRepeatedThousandsOfTimes) {
  CheckHeavyBucket(LshRanking::kSortValue);
}

TEST(LshSearchHeavyBucket, StaticPoseRepeatedThousandsOfTimesRankedByCode) {
  CheckHeavyBucket(LshRanking::kPositionCode);
}

TEST_F(LshSearchTest, QuaternionSignFlipGivesTheSameColumns) {
  // Rebuild the archive's rows from the features (dequantised), flip joints of a few frames.
  const uint32_t joints = features_->weighted_joint_count();
  const uint64_t frames = features_->frame_count();
  const FrameLayout layout{joints};
  std::vector<float> rows(frames * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < frames; ++frame_idx) {
    for (uint32_t value_idx = 0; value_idx < 4 * joints; ++value_idx) {
      rows[frame_idx * layout.stride() + value_idx] =
          features_->frame(frame_idx)[value_idx] / PoseFeatures::kQuantScale;
    }
  }
  std::vector<float> flipped = rows;
  const std::vector<uint64_t> flipped_frames = {10, 5000, 5001, 12345, 29999};
  for (uint64_t frame_idx : flipped_frames) {
    for (uint32_t joint_idx : {0u, 3u, 7u}) {
      for (int component = 0; component < 4; ++component) {
        float& value = flipped[frame_idx * layout.stride() + 4 * joint_idx + component];
        value = -value;
      }
    }
  }
  const PoseFeatures original = PoseFeatures::FromRows(
      rows.data(), frames, joints, features_->weights(), features_->clip_first_frames());
  const PoseFeatures sign_flipped = PoseFeatures::FromRows(
      flipped.data(), frames, joints, features_->weights(), features_->clip_first_frames());
  NeighbourRules rules = *rules_;
  auto search = CreateSearch(original, rules);
  auto flipped_search = CreateSearch(sign_flipped, rules);
  ASSERT_NE(search, nullptr);
  ASSERT_NE(flipped_search, nullptr);
  // The flipped frames' own columns, and columns that have a flipped frame as a neighbour.
  std::vector<uint64_t> columns = flipped_frames;
  SearchStats stats;
  for (uint64_t column : flipped_frames) {
    for (const Neighbour& neighbour : Column(*search, column, &stats)) {
      if (columns.size() < 40) columns.push_back(neighbour.frame);
    }
  }
  bool some_neighbour_was_flipped = false;
  for (uint64_t column : columns) {
    const std::vector<Neighbour> a = Column(*search, column, &stats);
    const std::vector<Neighbour> b = Column(*flipped_search, column, &stats);
    EXPECT_EQ(a, b) << "column " << column;
    for (const Neighbour& neighbour : b) {
      for (uint64_t frame_idx : flipped_frames) {
        some_neighbour_was_flipped |= neighbour.frame == frame_idx;
      }
    }
  }
  EXPECT_TRUE(some_neighbour_was_flipped);
}

TEST_F(LshSearchTest, ProbesStartWithTheQuerysOwnBucketsNearestFirst) {
  auto search = CreateSearch(*features_, *rules_);
  ASSERT_NE(search, nullptr);
  const auto sequence = search->ProbeSequence(777);
  const uint32_t tables = search->index().table_count();
  ASSERT_EQ(sequence.size(), tables * search->options().probes_per_table);
  for (uint32_t idx = 0; idx < tables; ++idx) {
    EXPECT_EQ(sequence[idx].lower_bound, 0.0f);
    EXPECT_EQ(sequence[idx].table_idx, idx);
  }
  for (size_t idx = 1; idx < sequence.size(); ++idx) {
    EXPECT_LE(sequence[idx - 1].lower_bound, sequence[idx].lower_bound);
  }
  // The column's frame is in its own bucket of every table.
  for (uint32_t idx = 0; idx < tables; ++idx) {
    const auto [begin, end] = search->index().FindBucket(idx, sequence[idx].key);
    const auto& frames = search->index().table(idx).frames;
    EXPECT_NE(std::find(frames.begin() + begin, frames.begin() + end, 777u), frames.begin() + end);
  }
}

TEST_F(LshSearchTest, ChoosesParametersFromTheData) {
  EXPECT_EQ(DefaultHashesPerTable(40000), 13u);
  EXPECT_EQ(DefaultHashesPerTable(1u << 20), 16u);
  EXPECT_EQ(DefaultHashesPerTable(10000000), 18u);
  const LshOptions resolved = ResolveLshOptions(*features_, *rules_, LshOptions());
  EXPECT_EQ(resolved.hashes_per_table, DefaultHashesPerTable(features_->frame_count()));
  EXPECT_GT(resolved.bucket_width, 0.0f);
  EXPECT_EQ(ResolveLshOptions(*features_, *rules_, LshOptions()).bucket_width,
            resolved.bucket_width);
  const SearchScale scale = EstimateSearchScale(*features_, *rules_, LshOptions());
  EXPECT_GT(scale.neighbour_pairs, 1000u);
  EXPECT_LE(scale.radius, rules_->eps);
  EXPECT_LE(scale.neighbour_l2, rules_->eps) << "|e_i - e_j| <= D";
  LshOptions fixed;
  fixed.hashes_per_table = 9;
  fixed.bucket_width = 0.2f;
  const LshOptions kept = ResolveLshOptions(*features_, *rules_, fixed);
  EXPECT_EQ(kept.hashes_per_table, 9u);
  EXPECT_EQ(kept.bucket_width, 0.2f);
  auto search = CreateSearch(*features_, *rules_, fixed);
  ASSERT_NE(search, nullptr);
  EXPECT_NE(search->DescribeParams().find("hashes=9 width=0.2 "), std::string::npos)
      << search->DescribeParams();
}

TEST_F(LshSearchTest, RejectsInvalidOptions) {
  auto expect_invalid = [&](NeighbourRules rules, LshOptions options, const char* what) {
    auto search = LshSearch::Create(*features_, rules, options);
    ASSERT_FALSE(search.ok()) << what;
    EXPECT_TRUE(search.status().IsInvalidArgument()) << what << ": " << search.status().ToString();
  };
  LshOptions options;
  NeighbourRules rules = *rules_;
  rules.eps = 0;
  expect_invalid(rules, options, "eps 0");
  rules = *rules_;
  rules.k_max = 0;
  expect_invalid(rules, options, "k_max 0");
  rules = *rules_;
  rules.clip_first_frames = {0, 5};
  expect_invalid(rules, options, "other clip layout");
  options.tables = 0;
  expect_invalid(*rules_, options, "no tables");
  options = LshOptions();
  options.hashes_per_table = 40;
  expect_invalid(*rules_, options, "too many hashes");
  options = LshOptions();
  options.probes_per_table = 0;
  expect_invalid(*rules_, options, "no probes");
  options = LshOptions();
  options.max_candidates = 0;
  expect_invalid(*rules_, options, "no budget");
  options = LshOptions();
  options.bucket_width = -1;
  expect_invalid(*rules_, options, "negative width");
  options = LshOptions();
  options.chain_probe_every = 0;
  expect_invalid(*rules_, options, "no probing column");

  auto search = CreateSearch(*features_, *rules_);
  ASSERT_NE(search, nullptr);
  std::vector<std::vector<Neighbour>> columns;
  SearchStats stats;
  const Status status = search->SearchColumns(features_->frame_count() - 5, 10, &columns, &stats);
  EXPECT_TRUE(status.IsInvalidArgument()) << status.ToString();
}

}  // namespace
}  // namespace motif
