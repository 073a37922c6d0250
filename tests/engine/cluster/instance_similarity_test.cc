#include "engine/cluster/instance_similarity.h"

#include <algorithm>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "tests/engine/cluster/cluster_test_util.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::Columns;

std::unique_ptr<TrellisFileReader> OpenTrellis(const std::string& path) {
  auto reader = TrellisFileReader::Open(path);
  EXPECT_TRUE(reader.ok()) << reader.status().ToString();
  return std::move(reader).value();
}

// Every edge as (a, b, weight), a < b.
std::vector<std::tuple<uint32_t, uint32_t, double>> EdgesOf(const SimilarityGraph& graph) {
  std::vector<std::tuple<uint32_t, uint32_t, double>> edges;
  for (uint32_t node = 0; node < graph.node_count(); ++node) {
    for (size_t idx = 0; idx < graph.Targets(node).size(); ++idx) {
      if (node < graph.Targets(node)[idx]) {
        edges.emplace_back(node, graph.Targets(node)[idx], graph.Weights(node)[idx]);
      }
    }
  }
  return edges;
}

TEST(InstanceSimilarityTest, CountsSharedFramesAndNormalisesByTheShorter) {
  testing::TempDir dir;
  Columns columns(40);
  // a = [0, 10), b = [20, 30): columns 0..4 of a see frame 25 of b (5 frames of a), columns 20
  // and 21 of b see frames 3 and 4 of a (2 frames of b). c = [32, 36) sees nothing.
  for (uint64_t column = 0; column < 5; ++column) columns[column] = {{25, 0.5f}};
  columns[20] = {{3, 0.5f}, {4, 0.5f}};
  columns[21] = {{4, 0.5f}};
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"), columns, 8).ok());
  auto trellis = OpenTrellis(dir.File("t.mtr"));
  const std::vector<MotifInstance> instances = {{0, 10}, {20, 30}, {32, 36}};

  SimilarityOptions options;
  SimilarityStats stats;
  auto graph = BuildSimilarityGraph(*trellis, instances, {}, options, &stats);
  ASSERT_TRUE(graph.ok()) << graph.status().ToString();
  // max(5, 2) / min(10, 10) = 0.5.
  EXPECT_EQ(EdgesOf(*graph), (std::vector<std::tuple<uint32_t, uint32_t, double>>{{0, 1, 0.5}}));
  EXPECT_EQ(stats.columns_read, 24u);
  EXPECT_EQ(stats.directed_pairs, 2u);

  // Above the threshold the pair is dropped, unless a path links it.
  options.min_similarity = 0.6;
  graph = BuildSimilarityGraph(*trellis, instances, {}, options);
  ASSERT_TRUE(graph.ok());
  EXPECT_EQ(graph->edge_count(), 0u);
  options.link_weight = 2.0;
  graph = BuildSimilarityGraph(*trellis, instances, {{1, 2}}, options);
  ASSERT_TRUE(graph.ok());
  EXPECT_EQ(EdgesOf(*graph), (std::vector<std::tuple<uint32_t, uint32_t, double>>{{1, 2, 2.0}}));

  // A linked similar pair gets both.
  options.min_similarity = 0.1;
  options.link_weight = 1.0;
  graph = BuildSimilarityGraph(*trellis, instances, {{0, 1}}, options);
  ASSERT_TRUE(graph.ok());
  EXPECT_EQ(EdgesOf(*graph), (std::vector<std::tuple<uint32_t, uint32_t, double>>{{0, 1, 1.5}}));
}

TEST(InstanceSimilarityTest, PlantedOccurrencesAreSimilarAndNoiseIsDropped) {
  testing::TempDir dir;
  const std::vector<testing::PlantedMotif> motifs = {{100, {100, 400, 900}}, {60, {250, 700}}};
  // One random neighbour a column: about 1 chance hit per 60 columns, far below 10 %.
  const Columns columns = testing::MakePlantedColumns(6000, motifs, 1, 9);
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"), columns).ok());
  auto trellis = OpenTrellis(dir.File("t.mtr"));
  // By start: 0 [100,200) A, 1 [250,310) B, 2 [400,500) A, 3 [700,760) B, 4 [900,1000) A.
  const std::vector<MotifInstance> instances = {
      {100, 200}, {250, 310}, {400, 500}, {700, 760}, {900, 1000}};
  SimilarityOptions options;
  options.link_weight = 0;
  auto graph = BuildSimilarityGraph(*trellis, instances, {}, options);
  ASSERT_TRUE(graph.ok());
  EXPECT_EQ(EdgesOf(*graph), (std::vector<std::tuple<uint32_t, uint32_t, double>>{
                                 {0, 2, 1.0}, {0, 4, 1.0}, {1, 3, 1.0}, {2, 4, 1.0}}));
}

TEST(InstanceSimilarityTest, SameGraphForAnyThreadCountAndBlockSize) {
  testing::TempDir dir;
  std::vector<testing::PlantedMotif> motifs;
  for (uint64_t motif = 0; motif < 6; ++motif) {
    motifs.push_back({80 + 10 * motif, {motif * 200, 1500 + motif * 200, 3000 + motif * 200}});
  }
  const Columns columns = testing::MakePlantedColumns(4500, motifs, 12, 4);
  ASSERT_TRUE(testing::WriteColumns(dir.File("a.mtr"), columns, 64).ok());
  ASSERT_TRUE(testing::WriteColumns(dir.File("b.mtr"), columns, 1000).ok());
  std::vector<MotifInstance> instances;
  for (uint64_t start = 0; start + 150 <= 4500; start += 75)
    instances.push_back({start, start + 150});
  std::vector<std::vector<std::tuple<uint32_t, uint32_t, double>>> results;
  for (const char* name : {"a.mtr", "b.mtr"}) {
    auto trellis = OpenTrellis(dir.File(name));
    for (int threads : {1, 2}) {
      tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
      SimilarityOptions options;
      options.threads = threads;
      auto graph = BuildSimilarityGraph(*trellis, instances, {{0, 5}}, options);
      ASSERT_TRUE(graph.ok());
      results.push_back(EdgesOf(*graph));
    }
  }
  EXPECT_FALSE(results[0].empty());
  for (size_t idx = 1; idx < results.size(); ++idx) EXPECT_EQ(results[idx], results[0]) << idx;
}

// Instances over the whole archive make the similarity read every block: the reader's mapping
// must not stay resident afterwards (at 10^6 re-sequenced frames it held the 500 MB trellis
// file, most of `mine`'s peak), and the graph is the one read with the pages kept.
TEST(InstanceSimilarityTest, ReleasesTheBlocksItHasRead) {
  testing::TempDir dir;
  std::vector<testing::PlantedMotif> motifs;
  for (uint64_t motif = 0; motif < 20; ++motif) {
    motifs.push_back({100, {motif * 1000, 20000 + motif * 1000, 40000 + motif * 1000}});
  }
  const Columns columns = testing::MakePlantedColumns(60000, motifs, 10, 3);
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"), columns, 1024).ok());
  auto trellis = OpenTrellis(dir.File("t.mtr"));
  ASSERT_GT(trellis->file_bytes(), 1u << 20);
  std::vector<MotifInstance> instances;
  for (const testing::PlantedMotif& motif : motifs) {
    for (uint64_t start : motif.starts) instances.push_back({start, start + motif.length});
  }
  std::sort(instances.begin(), instances.end(),
            [](const MotifInstance& a, const MotifInstance& b) { return a.start < b.start; });
  SimilarityStats stats;
  auto graph = BuildSimilarityGraph(*trellis, instances, {}, SimilarityOptions(), &stats);
  ASSERT_TRUE(graph.ok()) << graph.status().ToString();
  // Every block up to the last instance's end (59,100) holds an instance: the gaps between
  // them are shorter than a block. The archive's last block (from 59,392) holds none.
  EXPECT_EQ(stats.blocks_decoded, (59100 + 1023) / 1024);
  EXPECT_EQ(trellis->block_count(), stats.blocks_decoded + 1);
  // Each motif's 3 occurrences are similar to each other: 3 edges a motif.
  EXPECT_EQ(graph->edge_count(), 3 * motifs.size());
  const int64_t resident = testing::MappedResidentBytes(dir.File("t.mtr"));
  if (resident < 0) GTEST_SKIP() << "no /proc/self/smaps";
  EXPECT_LT(resident, static_cast<int64_t>(trellis->file_bytes() / 10));
}

TEST(InstanceSimilarityTest, RejectsInstancesOutsideTheTrellisAndBadLinks) {
  testing::TempDir dir;
  ASSERT_TRUE(testing::WriteColumns(dir.File("t.mtr"), Columns(50)).ok());
  auto trellis = OpenTrellis(dir.File("t.mtr"));
  EXPECT_TRUE(BuildSimilarityGraph(*trellis, {{40, 60}}, {}, {}).status().IsInvalidArgument());
  EXPECT_TRUE(BuildSimilarityGraph(*trellis, {{10, 10}}, {}, {}).status().IsInvalidArgument());
  EXPECT_TRUE(
      BuildSimilarityGraph(*trellis, {{20, 30}, {0, 10}}, {}, {}).status().IsInvalidArgument());
  EXPECT_TRUE(BuildSimilarityGraph(*trellis, {{0, 10}}, {{0, 3}}, {}).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
