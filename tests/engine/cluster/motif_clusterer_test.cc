#include "engine/cluster/motif_clusterer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/evaluation/planted_motif_score.h"
#include "tests/engine/cluster/cluster_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// Three motifs: A 100 frames x 4 (score 400), B 80 x 3 (240), C 60 x 2 (120), interleaved.
const std::vector<testing::PlantedMotif> kMotifs = {
    {100, {200, 1400, 2600, 3800}},
    {80, {600, 2000, 3200}},
    {60, {1000, 4400}},
};

std::vector<MotifInstance> InstancesOf(const ClusterResult& result, const Motif& motif) {
  std::vector<MotifInstance> instances;
  for (uint32_t id : motif.instances) instances.push_back(result.instances[id]);
  return instances;
}

TEST(RankMotifsTest, MostFramesFirstAndSingletonsDropped) {
  const std::vector<MotifInstance> instances = {{0, 10},    {20, 30},   {40, 100},
                                                {200, 260}, {300, 310}, {400, 500}};
  std::vector<Motif> motifs = RankMotifs({{0, 1}, {3, 2}, {4}, {5}}, instances);
  ASSERT_EQ(motifs.size(), 2u);
  EXPECT_EQ(motifs[0].instances, (std::vector<uint32_t>{2, 3}));
  EXPECT_EQ(motifs[0].total_frames, 120u);
  EXPECT_DOUBLE_EQ(motifs[0].mean_length(), 60.0);
  EXPECT_EQ(motifs[1].instances, (std::vector<uint32_t>{0, 1}));
}

TEST(RankMotifsTest, RanksByTheFramesExplainedBeyondTheFirstInstance) {
  // Five 100-frame repetitions ((5 - 1) x 100 = 400) come before two 300-frame ones (300),
  // which come before two 240-frame ones (240), though the five cover 500 frames and the two
  // pairs 600 and 480.
  const std::vector<MotifInstance> instances = {{0, 100},     {200, 300},   {400, 500},
                                                {600, 700},   {800, 900},   {1000, 1240},
                                                {1300, 1540}, {2000, 2300}, {2500, 2800}};
  std::vector<Motif> motifs = RankMotifs({{5, 6}, {7, 8}, {0, 1, 2, 3, 4}}, instances);
  ASSERT_EQ(motifs.size(), 3u);
  EXPECT_EQ(motifs[0].instances.size(), 5u);
  EXPECT_DOUBLE_EQ(motifs[0].score(), 400.0);
  EXPECT_EQ(motifs[1].instances, (std::vector<uint32_t>{7, 8}));
  EXPECT_EQ(motifs[2].instances, (std::vector<uint32_t>{5, 6}));
}

TEST(RankMotifsTest, NoTwoInstancesOfAMotifOverlapByMoreThanAQuarter) {
  // [0, 100) and [30, 130) share 70 frames: near-copies; [90, 190) shares 10 with [0, 100).
  // Of the near-copies the one closer to the typical length (100) stays: [0, 100) (ties go to
  // the earlier) and the 100-frame [30, 130) is left out.
  const std::vector<MotifInstance> instances = {{0, 100}, {30, 130}, {90, 190}, {500, 600}};
  std::vector<Motif> motifs = RankMotifs({{0, 1, 2, 3}}, instances);
  ASSERT_EQ(motifs.size(), 1u);
  EXPECT_EQ(motifs[0].instances, (std::vector<uint32_t>{0, 2, 3}));
}

TEST(RankMotifsTest, AMotifWhoseInstancesLieInsideABetterMotifsIsDropped) {
  // Motif A: three 300-frame instances. Motif B: the first 80 frames of each of A's instances.
  // Motif C: two 80-frame instances, one inside A, one elsewhere: it stays.
  const std::vector<MotifInstance> instances = {{0, 300},   {1000, 1300}, {2000, 2300},  // A
                                                {0, 80},    {1000, 1080}, {2010, 2090},  // B
                                                {100, 180}, {5000, 5080}};               // C
  std::vector<Motif> motifs = RankMotifs({{0, 1, 2}, {3, 4, 5}, {6, 7}}, instances);
  ASSERT_EQ(motifs.size(), 2u);
  EXPECT_EQ(motifs[0].instances, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(motifs[1].instances, (std::vector<uint32_t>{6, 7}));
}

// One group as the cut might leave it: four instances of a 400-frame motif (0-3), two 70-frame
// fragments linked only to them (4, 5), three 120-frame instances of a short motif linked to
// each other (6-8), and two 60-frame stretches linked only to each other (9, 10).
TEST(RankMotifsTest, SplitsAGroupByLengthAndDropsFragments) {
  const std::vector<MotifInstance> instances = {
      {0, 400},     {1000, 1380}, {2000, 2430}, {3000, 3410},  // the long motif
      {4000, 4070}, {4500, 4570},                              // fragments of it
      {5000, 5120}, {5500, 5610}, {6000, 6130},                // a short motif
      {7000, 7060}, {7500, 7560}};                             // a chance pair
  const std::vector<InstanceLink> links = {{0, 1}, {1, 2}, {2, 3}, {0, 4},  {2, 5},
                                           {6, 7}, {7, 8}, {0, 6}, {9, 10}, {3, 9}};
  const std::vector<std::vector<uint32_t>> groups = {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}};
  uint64_t dropped = 0;
  std::vector<Motif> motifs = RankMotifs(groups, instances, links, 3.0, &dropped);
  ASSERT_EQ(motifs.size(), 2u);
  EXPECT_EQ(motifs[0].instances, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(motifs[1].instances, (std::vector<uint32_t>{6, 7, 8}));
  EXPECT_EQ(dropped, 4u);  // 4, 5 alone; 9, 10 a pair

  // The typical length is length-weighted: six fragments outnumbering four instances do not
  // make the fragments typical.
  std::vector<MotifInstance> many = instances;
  many.push_back({8000, 8065});
  many.push_back({8500, 8570});
  uint64_t many_dropped = 0;
  std::vector<Motif> kept =
      RankMotifs({{0, 1, 2, 3, 4, 5, 11, 12}}, many, links, 3.0, &many_dropped);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].instances, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(many_dropped, 4u);

  // Within the ratio everything stays; a ratio of 0 keeps the group as cut.
  EXPECT_EQ(RankMotifs({{0, 1, 2, 3}}, instances, links, 3.0)[0].instances.size(), 4u);
  ASSERT_EQ(RankMotifs(groups, instances, links, 0.0).size(), 1u);
  EXPECT_EQ(RankMotifs(groups, instances, links, 0.0)[0].instances.size(), 11u);
}

TEST(MotifClustererTest, FindsPlantedMotifsRankedByImportance) {
  testing::TempDir dir;
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"),
                                    testing::MakePlantedColumns(5000, kMotifs, 1, 3), 256)
                  .ok());
  auto trellis = TrellisFileReader::Open(dir.File("t.mtr"));
  ASSERT_TRUE(trellis.ok());
  auto result = ClusterMotifs(testing::MakePlantedCandidates(kMotifs), **trellis, {});
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_EQ(result->motifs.size(), 3u);
  for (size_t motif = 0; motif < 3; ++motif) {
    std::vector<MotifInstance> expected;
    for (uint64_t start : kMotifs[motif].starts) {
      expected.push_back({start, start + kMotifs[motif].length});
    }
    EXPECT_EQ(InstancesOf(*result, result->motifs[motif]), expected) << motif;
  }
  EXPECT_EQ(result->motifs[0].total_frames, 400u);
  const ClusterReport& report = result->report;
  EXPECT_EQ(report.instance_stats.kept_paths, 12u + 6u + 2u);  // one per ordered pair
  EXPECT_EQ(report.instance_stats.instances, 9u);
  EXPECT_EQ(report.clustered_instances, 9u);
  EXPECT_EQ(report.covered_frames, 400u + 240u + 120u);
  EXPECT_EQ(report.cut_stats.components, 3u);

  // Scored against the truth: everything found, nothing else, grouped right.
  std::vector<PlantedInstance> planted;
  std::vector<FoundInstance> found;
  for (uint32_t motif = 0; motif < 3; ++motif) {
    for (uint64_t start : kMotifs[motif].starts) {
      planted.push_back({"clip", start, start + kMotifs[motif].length, 7 + motif});
    }
    for (const MotifInstance& instance : InstancesOf(*result, result->motifs[motif])) {
      found.push_back({"clip", instance.start, instance.end, motif});
    }
  }
  PlantedMotifScore score = ScorePlantedMotifs(found, planted);
  EXPECT_DOUBLE_EQ(score.recall, 1.0);
  EXPECT_DOUBLE_EQ(score.precision, 1.0);
  EXPECT_DOUBLE_EQ(score.adjusted_rand_index, 1.0);
}

TEST(MotifClustererTest, SameMotifsForAnyThreadCount) {
  testing::TempDir dir;
  std::vector<testing::PlantedMotif> motifs;
  for (uint64_t motif = 0; motif < 12; ++motif) {
    testing::PlantedMotif planted{60 + 5 * motif, {}};
    for (uint64_t copy = 0; copy < 3 + motif % 3; ++copy) {
      planted.starts.push_back(motif * 220 + copy * 3000);
    }
    motifs.push_back(planted);
  }
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"),
                                    testing::MakePlantedColumns(16000, motifs, 3, 5), 512)
                  .ok());
  auto trellis = TrellisFileReader::Open(dir.File("t.mtr"));
  ASSERT_TRUE(trellis.ok());
  std::vector<std::vector<std::vector<MotifInstance>>> runs;
  for (int threads : {1, 2}) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    ClusterOptions options;
    options.threads = threads;
    auto result = ClusterMotifs(testing::MakePlantedCandidates(motifs), **trellis, options);
    ASSERT_TRUE(result.ok());
    runs.emplace_back();
    for (const Motif& motif : result->motifs) runs.back().push_back(InstancesOf(*result, motif));
  }
  EXPECT_EQ(runs[0].size(), 12u);
  EXPECT_EQ(runs[0], runs[1]);
}

TEST(MotifClustererTest, RejectsCandidatesOutsideTheTrellis) {
  testing::TempDir dir;
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"), testing::Columns(100)).ok());
  auto trellis = TrellisFileReader::Open(dir.File("t.mtr"));
  ASSERT_TRUE(trellis.ok());
  auto result = ClusterMotifs({{0, 50, 60, 120, 0, 60}}, **trellis, {});
  EXPECT_TRUE(result.status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
