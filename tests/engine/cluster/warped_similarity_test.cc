// ReweightByWarpedDistance: edge weights from the time-warped distance of instances, with each
// instance scaled by its nearest non-overlapping repetition. On a small procedural archive
// with planted motifs (known occurrences).
#include "engine/cluster/warped_similarity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cluster/instance_rows.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

struct PlantedArchive {
  std::unique_ptr<FrameFileReader> reader;
  std::vector<MotifInstance> instances;  // the planted occurrences, global frames
  std::vector<uint32_t> motif_of;        // planted motif of each
};

PlantedArchive MakePlantedArchive(const testing::TempDir& dir) {
  SynthOptions options;
  options.frames = 24000;
  options.motifs = 3;
  options.seed = 3;
  options.threads = 1;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok());
  const std::string path = dir.File("planted.mfs");
  auto writer = FrameFileWriter::Create(path, (*synthesizer)->skeleton(), options.fps);
  EXPECT_TRUE(writer.ok());
  EXPECT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) { return (*writer)->AppendClip(clip); })
                  .ok());
  EXPECT_TRUE((*writer)->Commit().ok());
  auto reader = FrameFileReader::Open(path);
  EXPECT_TRUE(reader.ok());
  PlantedArchive archive;
  std::map<std::string, uint64_t> first_frame;
  for (const ClipInfo& clip : (*reader)->clips()) first_frame[clip.name] = clip.first_frame;
  for (const PlantedInstance& planted : (*synthesizer)->truth()) {
    const uint64_t offset = first_frame.at(planted.clip);
    archive.instances.push_back({offset + planted.start, offset + planted.end});
    archive.motif_of.push_back(planted.motif);
  }
  archive.reader = std::move(reader.value());
  return archive;
}

SimilarityGraph CompleteGraph(uint32_t nodes) {
  std::vector<WeightedEdge> edges;
  for (uint32_t a = 0; a < nodes; ++a) {
    for (uint32_t b = a + 1; b < nodes; ++b) edges.push_back({a, b, 1.0});
  }
  return SimilarityGraph::FromEdges(nodes, std::move(edges));
}

double Weight(const SimilarityGraph& graph, uint32_t a, uint32_t b) {
  for (size_t k = 0; k < graph.Targets(a).size(); ++k) {
    if (graph.Targets(a)[k] == b) return graph.Weights(a)[k];
  }
  return 0;
}

constexpr float kEps = 1.256f;

TEST(WarpedSimilarityTest, EveryInstanceWeighsMostWithARepetitionOfItsOwnMotif) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  ASSERT_GE(nodes, 6u);
  const SimilarityGraph graph = CompleteGraph(nodes);
  WarpedSimilarityStats stats;
  auto warped =
      ReweightByWarpedDistance(*archive.reader, archive.instances, graph, kEps, {}, &stats);
  ASSERT_TRUE(warped.ok()) << warped.status().ToString();
  EXPECT_EQ(stats.edges, graph.edge_count());
  EXPECT_EQ(warped->edge_count(), graph.edge_count() - stats.dropped_edges);
  EXPECT_GT(stats.mean_distance, 0);
  for (uint32_t a = 0; a < nodes; ++a) {
    uint32_t heaviest = a;
    for (uint32_t b = 0; b < nodes; ++b) {
      if (b != a && (heaviest == a || Weight(*warped, a, b) > Weight(*warped, a, heaviest))) {
        heaviest = b;
      }
    }
    EXPECT_EQ(archive.motif_of[heaviest], archive.motif_of[a]) << "instance " << a;
  }
}

TEST(WarpedSimilarityTest, TwoInstancesThatAreEachOthersNearestWeighExactlyOneOverE) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  WarpedSimilarityOptions local_only;
  local_only.floor_scale = 0;
  auto warped = ReweightByWarpedDistance(*archive.reader, archive.instances, CompleteGraph(nodes),
                                         kEps, local_only);
  ASSERT_TRUE(warped.ok());
  // With one scale per instance (its nearest), the heaviest edge of the whole graph joins two
  // instances that are each other's nearest: d^2 / (d · d) = 1.
  double heaviest = 0;
  for (uint32_t a = 0; a < nodes; ++a) {
    for (double weight : warped->Weights(a)) heaviest = std::max(heaviest, weight);
  }
  EXPECT_NEAR(heaviest, std::exp(-1.0), 1e-12);
}

TEST(WarpedSimilarityTest, AnOverlappingInstanceDoesNotSetTheScale) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  // Two occurrences of one motif, and the first shifted by two frames (nearly the same frames).
  uint32_t second = 1;
  while (archive.motif_of[second] != archive.motif_of[0]) ++second;
  const MotifInstance first = archive.instances[0];
  const std::vector<MotifInstance> instances = {
      first, archive.instances[second], {first.start + 2, first.end + 2}};
  WarpedSimilarityOptions local_only;
  local_only.floor_scale = 0;
  auto warped =
      ReweightByWarpedDistance(*archive.reader, instances, CompleteGraph(3), kEps, local_only);
  ASSERT_TRUE(warped.ok());
  // Were the shifted copy its scale, the first would weigh e^-1 to it and almost nothing to the
  // real repetition; scaled by the repetition, the shifted copy weighs near 1.
  EXPECT_GT(Weight(*warped, 0, 2), 0.9);
  EXPECT_LE(Weight(*warped, 0, 1), std::exp(-1.0) + 1e-12);
  EXPECT_GT(Weight(*warped, 0, 1), 0.1);
}

TEST(WarpedSimilarityTest, NoScaleIsBelowTheFloor) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  auto lightest = [&](double floor_scale) {
    WarpedSimilarityOptions options;
    options.floor_scale = floor_scale;
    options.max_scales = std::numeric_limits<double>::infinity();  // every pair keeps its edge
    auto warped = ReweightByWarpedDistance(*archive.reader, archive.instances, CompleteGraph(nodes),
                                           kEps, options);
    EXPECT_TRUE(warped.ok());
    double least = 1;
    for (uint32_t a = 0; a < nodes; ++a) {
      for (double weight : warped->Weights(a)) least = std::min(least, weight);
    }
    return least;
  };
  // Different planted motifs are far apart on their own scales; on a scale of 10 eps (more than
  // any two poses are apart) every pair is alike.
  EXPECT_LT(lightest(0), 0.1);
  EXPECT_GT(lightest(10), 0.9);
}

TEST(WarpedSimilarityTest, APairFartherApartThanThreeScalesLosesItsEdge) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  const SimilarityGraph graph = CompleteGraph(nodes);
  WarpedSimilarityStats stats;
  auto warped =
      ReweightByWarpedDistance(*archive.reader, archive.instances, graph, kEps, {}, &stats);
  ASSERT_TRUE(warped.ok());
  uint64_t same_motif_pairs = 0;
  for (uint32_t a = 0; a < nodes; ++a) {
    for (uint32_t b = a + 1; b < nodes; ++b) {
      const double weight = Weight(*warped, a, b);
      if (archive.motif_of[a] == archive.motif_of[b]) {
        ++same_motif_pairs;
        EXPECT_GT(weight, 0) << "repetitions " << a << " and " << b << " lost their edge";
      }
      if (weight > 0) {
        EXPECT_GE(weight, std::exp(-9.0));
      }
    }
  }
  // The planted motifs are far apart on their own scales: most pairs of different motifs go.
  EXPECT_GT(stats.dropped_edges, (graph.edge_count() - same_motif_pairs) / 2);
  EXPECT_EQ(warped->edge_count(), graph.edge_count() - stats.dropped_edges);

  WarpedSimilarityOptions keep_all;
  keep_all.max_scales = std::numeric_limits<double>::infinity();
  auto whole =
      ReweightByWarpedDistance(*archive.reader, archive.instances, graph, kEps, keep_all, &stats);
  ASSERT_TRUE(whole.ok());
  EXPECT_EQ(stats.dropped_edges, 0u);
  EXPECT_EQ(whole->edge_count(), graph.edge_count());
}

TEST(WarpedSimilarityTest, SameWeightsForAnyThreadCount) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  WarpedSimilarityOptions one;
  one.threads = 1;
  WarpedSimilarityOptions two;
  two.threads = 2;
  auto a =
      ReweightByWarpedDistance(*archive.reader, archive.instances, CompleteGraph(nodes), kEps, one);
  auto b =
      ReweightByWarpedDistance(*archive.reader, archive.instances, CompleteGraph(nodes), kEps, two);
  ASSERT_TRUE(a.ok() && b.ok());
  for (uint32_t node = 0; node < nodes; ++node) {
    ASSERT_EQ(std::vector<double>(a->Weights(node).begin(), a->Weights(node).end()),
              std::vector<double>(b->Weights(node).begin(), b->Weights(node).end()));
  }
}

// The warp of MeanWarpedDistance written out with full cost and step tables, one scalar pose
// distance a cell: the reference the engine's two-row, SIMD-kernel form must match bit for bit.
double FullTableWarpedDistance(const PoseFeatures& features, uint64_t a0, uint64_t a1, uint64_t b0,
                               uint64_t b1) {
  const uint64_t n = a1 - a0;
  const uint64_t m = b1 - b0;
  std::vector<double> cost((n + 1) * (m + 1), std::numeric_limits<double>::infinity());
  std::vector<uint32_t> steps((n + 1) * (m + 1), 0);
  auto at = [m](uint64_t i, uint64_t j) { return i * (m + 1) + j; };
  cost[at(0, 0)] = 0;
  for (uint64_t i = 1; i <= n; ++i) {
    for (uint64_t j = 1; j <= m; ++j) {
      uint64_t best = at(i - 1, j - 1);
      if (cost[at(i - 1, j)] < cost[best]) best = at(i - 1, j);
      if (cost[at(i, j - 1)] < cost[best]) best = at(i, j - 1);
      cost[at(i, j)] = cost[best] + PoseDistance(features, a0 + i - 1, b0 + j - 1);
      steps[at(i, j)] = steps[best] + 1;
    }
  }
  return cost[at(n, m)] / steps[at(n, m)];
}

TEST(WarpedSimilarityTest, EveryPairsDistanceIsTheFullTableWarpsBitForBit) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  // 17 samples: a second, one-frame tile in the kernel's blocks.
  auto samples = ReadInstanceSamples(*archive.reader, archive.instances, 17, kEps, 2);
  ASSERT_TRUE(samples.ok());
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  const uint32_t nodes = static_cast<uint32_t>(archive.instances.size());
  for (uint32_t a = 0; a < nodes; ++a) {
    for (uint32_t b = 0; b < nodes; ++b) pairs.emplace_back(a, b);
  }
  auto distances = WarpedDistances(*samples, pairs, 2);
  ASSERT_TRUE(distances.ok());
  ASSERT_EQ(distances->size(), pairs.size());
  const std::vector<uint64_t>& first = samples->first;
  for (size_t idx = 0; idx < pairs.size(); ++idx) {
    const auto [a, b] = pairs[idx];
    const double reference = FullTableWarpedDistance(samples->features, first[a], first[a + 1],
                                                     first[b], first[b + 1]);
    ASSERT_EQ((*distances)[idx], reference) << a << " " << b;
    ASSERT_EQ(MeanWarpedDistance(samples->features, first[a], first[a + 1], first[b],
                                 first[b + 1]),
              reference)
        << a << " " << b;
    if (a == b) {
      EXPECT_EQ(reference, 0.0);
    }
  }
}

TEST(WarpedSimilarityTest, DisabledKeepsTheWeightsAndBadInputIsRefused) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const SimilarityGraph graph = CompleteGraph(2);
  const std::vector<MotifInstance> two = {archive.instances[0], archive.instances[1]};
  WarpedSimilarityOptions off;
  off.enabled = false;
  auto same = ReweightByWarpedDistance(*archive.reader, two, graph, kEps, off);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(Weight(*same, 0, 1), 1.0);

  WarpedSimilarityOptions no_neighbours;
  no_neighbours.neighbours = 0;
  EXPECT_TRUE(ReweightByWarpedDistance(*archive.reader, two, graph, kEps, no_neighbours)
                  .status()
                  .IsInvalidArgument());
  const uint64_t frames = archive.reader->frame_count();
  const std::vector<MotifInstance> outside = {archive.instances[0], {frames - 10, frames + 10}};
  EXPECT_TRUE(ReweightByWarpedDistance(*archive.reader, outside, graph, kEps, {})
                  .status()
                  .IsInvalidArgument());
}

// The reader warped similarity and held poses share: every instance's rows, each block decoded once
// per span, the same as reading the instance alone.
TEST(InstanceRowsTest, EveryInstanceGetsItsOwnRowsWhateverTheOrderAndOverlap) {
  testing::TempDir dir;
  const PlantedArchive archive = MakePlantedArchive(dir);
  const uint64_t frames = archive.reader->frame_count();
  // Out of order, overlapping, one far away (a span of its own), one at the very end.
  const std::vector<MotifInstance> instances = {
      {5000, 5100}, {100, 400}, {300, 350}, {100, 400}, {frames - 70, frames}, {2500, 2600}};
  const uint64_t stride = archive.reader->layout().stride();
  std::vector<int> visits(instances.size(), 0);
  std::vector<size_t> order;
  const Status status =
      ForEachInstanceRows(*archive.reader, instances, [&](size_t idx, const float* rows) {
        std::vector<float> alone;
        EXPECT_TRUE(
            archive.reader->ReadFrames(instances[idx].start, instances[idx].length(), &alone).ok());
        EXPECT_TRUE(std::equal(alone.begin(), alone.end(), rows)) << "instance " << idx;
        EXPECT_EQ(alone.size(), instances[idx].length() * stride);
        ++visits[idx];
        order.push_back(idx);
        return Status::Ok();
      });
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(visits, std::vector<int>(instances.size(), 1));
  EXPECT_EQ(order, (std::vector<size_t>{1, 3, 2, 5, 0, 4}));  // by start, ties by index

  // With two threads the spans are read in parallel: the same rows, each instance once.
  std::vector<std::atomic<int>> parallel_visits(instances.size());
  const Status parallel = ForEachInstanceRows(
      *archive.reader, instances,
      [&](size_t idx, const float* rows) {
        std::vector<float> alone;
        EXPECT_TRUE(
            archive.reader->ReadFrames(instances[idx].start, instances[idx].length(), &alone).ok());
        EXPECT_TRUE(std::equal(alone.begin(), alone.end(), rows)) << "instance " << idx;
        ++parallel_visits[idx];
        return Status::Ok();
      },
      2);
  ASSERT_TRUE(parallel.ok()) << parallel.ToString();
  for (size_t idx = 0; idx < instances.size(); ++idx) EXPECT_EQ(parallel_visits[idx], 1) << idx;
  EXPECT_TRUE(ForEachInstanceRows(
                  *archive.reader, instances,
                  [](size_t idx, const float*) {
                    return idx == 5 ? Status::Corruption("stop") : Status::Ok();
                  },
                  2)
                  .IsCorruption());

  EXPECT_TRUE(
      ForEachInstanceRows(*archive.reader, {{frames - 10, frames + 1}}, [](size_t, const float*) {
        return Status::Ok();
      }).IsInvalidArgument());
  EXPECT_TRUE(ForEachInstanceRows(*archive.reader, {{10, 10}}, [](size_t, const float*) {
                return Status::Ok();
              }).IsInvalidArgument());
  // An error of the visitor stops the walk and comes back.
  EXPECT_TRUE(ForEachInstanceRows(*archive.reader, instances, [](size_t, const float*) {
                return Status::Corruption("stop");
              }).IsCorruption());
}

}  // namespace
}  // namespace motif
