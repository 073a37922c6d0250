#include "engine/cluster/motif_clusterer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/cluster/planted_motif_score.h"
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
  const std::vector<MotifInstance> instances = {{0, 10}, {20, 30}, {40, 100}, {200, 260},
                                                {300, 310}, {400, 500}};
  std::vector<Motif> motifs = RankMotifs({{0, 1}, {3, 2}, {4}, {5}}, instances);
  ASSERT_EQ(motifs.size(), 2u);
  EXPECT_EQ(motifs[0].instances, (std::vector<uint32_t>{2, 3}));
  EXPECT_EQ(motifs[0].total_frames, 120u);
  EXPECT_DOUBLE_EQ(motifs[0].mean_length(), 60.0);
  EXPECT_EQ(motifs[1].instances, (std::vector<uint32_t>{0, 1}));
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
