// Helpers for the LSH tests: archives as PoseFeatures (synthetic with planted motifs, or the real
// CMU BVH takes), eps = mu - 2 sigma of sampled pair distances, the exact column by a direct
// double loop with the scalar PoseDistance, recall against it, and the parts of a query
// (QueryParts) for the tests of its steps alone.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_index.h"
#include "engine/lsh/lsh_options.h"
#include "engine/lsh/lsh_query_context.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/resample.h"

namespace motif::testing {

// Joint weights of a skeleton (its defaults).
inline std::vector<float> DefaultWeights(const Skeleton& skeleton) {
  std::vector<float> weights;
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    weights.push_back(skeleton.joint(joint_idx).weight);
  }
  return weights;
}

// Concatenates clips (rows in FrameLayout order) into PoseFeatures with the skeleton's default
// weights and the clips' boundaries.
inline PoseFeatures FeaturesFromClips(const Skeleton& skeleton,
                                      const std::vector<ClipFrames>& clips) {
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  std::vector<float> rows;
  std::vector<uint64_t> clip_first_frames;
  uint64_t frames = 0;
  for (const ClipFrames& clip : clips) {
    clip_first_frames.push_back(frames);
    rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
    frames += clip.rows.size() / layout.stride();
  }
  return PoseFeatures::FromRows(rows.data(), frames, layout.joint_count, DefaultWeights(skeleton),
                                clip_first_frames);
}

// A procedural synthetic archive of `frames` frames.
inline PoseFeatures SyntheticFeatures(uint64_t frames, uint64_t seed = 7) {
  SynthOptions options;
  options.frames = frames;
  options.seed = seed;
  options.motifs = static_cast<uint32_t>(std::clamp<uint64_t>(frames / 10000, 2, 8));
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  if (!synthesizer.ok()) return PoseFeatures();
  std::vector<ClipFrames> clips;
  Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    clips.push_back(clip);
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok()) << status.ToString();
  return FeaturesFromClips((*synthesizer)->skeleton(), clips);
}

// Every BVH take under `bvh_dir`, imported as the importer does (canonical skeleton, default
// weights), conformed to the first take's skeleton and at its rate, one clip per take.
inline Result<PoseFeatures> RealTakeFeatures(const std::string& bvh_dir) {
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources,
                         DiscoverTakes({bvh_dir}, ImportOptions()));
  std::vector<ClipFrames> clips;
  Skeleton skeleton;
  double fps = 0;
  for (const TakeSource& source : sources) {
    MOTIF_ASSIGN_OR_RETURN(Take take, ImportTake(source, ImportOptions()));
    if (clips.empty()) {
      skeleton = take.skeleton;
      fps = take.fps;
    } else {
      MOTIF_RETURN_IF_ERROR(ConformToSkeleton(skeleton, &take));
    }
    clips.push_back(TakeToClipFrames(ResampleTake(take, fps)));
  }
  if (clips.empty()) return Status::NotFound("no BVH takes in " + bvh_dir);
  return FeaturesFromClips(skeleton, clips);
}

// Rules with eps = mu - 2 sigma of `pairs` random pairs of allowed frames.
inline NeighbourRules RulesWithEstimatedEps(const PoseFeatures& features, uint32_t k_max = 256,
                                            uint32_t pairs = 20000, uint64_t seed = 3) {
  NeighbourRules rules;
  rules.k_max = k_max;
  rules.exclusion_frames = 30;
  rules.clip_first_frames = features.clip_first_frames();
  uint64_t state = seed;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 17;
  };
  double sum = 0;
  double squares = 0;
  uint32_t taken = 0;
  while (taken < pairs) {
    const uint64_t a = next() % features.frame_count();
    const uint64_t b = next() % features.frame_count();
    if (rules.Excluded(a, b, features.ClipOf(a), features.ClipOf(b))) continue;
    const double distance = PoseDistance(features, a, b);
    sum += distance;
    squares += distance * distance;
    ++taken;
  }
  const double mean = sum / taken;
  const double sigma = std::sqrt(std::max(0.0, squares / taken - mean * mean));
  rules.eps = static_cast<float>(mean - 2 * sigma);
  return rules;
}

// The exact column by a direct loop over all frames.
inline std::vector<Neighbour> ExactColumn(const PoseFeatures& features, const NeighbourRules& rules,
                                          uint64_t column) {
  std::vector<Neighbour> found;
  const uint32_t column_clip = features.ClipOf(column);
  for (uint64_t frame = 0; frame < features.frame_count(); ++frame) {
    if (rules.Excluded(column, frame, column_clip, features.ClipOf(frame))) continue;
    const float distance = PoseDistance(features, column, frame);
    if (distance <= rules.eps) found.push_back({static_cast<uint32_t>(frame), distance});
  }
  FinishColumn(rules.k_max, &found);
  return found;
}

// The first `count` columns from `first` on, in steps of 97, with at least `at_least` exact
// neighbours below `frame_limit` (new frames with older neighbours, for the reverse queries).
inline std::vector<uint64_t> ColumnsWithOlderNeighbours(const PoseFeatures& features,
                                                        const NeighbourRules& rules, uint64_t first,
                                                        uint64_t frame_limit, size_t at_least,
                                                        size_t count) {
  std::vector<uint64_t> columns;
  for (uint64_t column = first; column < features.frame_count() && columns.size() < count;
       column += 97) {
    const std::vector<Neighbour> exact = ExactColumn(features, rules, column);
    const size_t older = std::count_if(exact.begin(), exact.end(),
                                       [&](const Neighbour& n) { return n.frame < frame_limit; });
    if (older >= at_least) columns.push_back(column);
  }
  EXPECT_EQ(columns.size(), count) << "columns with older neighbours";
  return columns;
}

// Seeded sample of distinct columns, ascending.
inline std::vector<uint64_t> SampleColumns(uint64_t frame_count, uint32_t count, uint64_t seed) {
  std::vector<uint64_t> columns;
  uint64_t state = seed;
  while (columns.size() < std::min<uint64_t>(count, frame_count)) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t column = (state >> 17) % frame_count;
    if (std::find(columns.begin(), columns.end(), column) == columns.end())
      columns.push_back(column);
  }
  std::sort(columns.begin(), columns.end());
  return columns;
}

struct RecallStats {
  uint64_t exact = 0;       // neighbours in the exact columns
  uint64_t found = 0;       // of those, in the approximate columns
  double column_mean = 0;   // mean over columns of found / exact (1 for empty exact columns)
  double worst_column = 1;  // the lowest such share
  double pooled() const { return exact ? static_cast<double>(found) / exact : 1.0; }
};

// Recall of `approximate` columns (sorted by frame) against `exact` ones (same order).
inline RecallStats Recall(const std::vector<std::vector<Neighbour>>& exact,
                          const std::vector<std::vector<Neighbour>>& approximate) {
  RecallStats stats;
  double share_sum = 0;
  for (size_t column_idx = 0; column_idx < exact.size(); ++column_idx) {
    uint64_t hits = 0;
    for (const Neighbour& neighbour : exact[column_idx]) {
      const auto& column = approximate[column_idx];
      auto it =
          std::lower_bound(column.begin(), column.end(), neighbour.frame,
                           [](const Neighbour& a, uint32_t frame) { return a.frame < frame; });
      if (it != column.end() && it->frame == neighbour.frame) ++hits;
    }
    stats.exact += exact[column_idx].size();
    stats.found += hits;
    const double share =
        exact[column_idx].empty() ? 1.0 : static_cast<double>(hits) / exact[column_idx].size();
    share_sum += share;
    stats.worst_column = std::min(stats.worst_column, share);
  }
  stats.column_mean = exact.empty() ? 1.0 : share_sum / exact.size();
  return stats;
}

// The parts an LshQueryContext refers to, owned together, for the tests of a query's steps
// (ColumnQuery, ReversePass, ...). Not to be moved once context() has been taken.
struct QueryParts {
  PoseFeatures features;
  NeighbourRules rules;
  LshOptions options;
  HashFamily family;
  LshIndex index;
  float extension_radius = 0;

  LshQueryContext context() const {
    return {features, rules, options, family, index, extension_radius};
  }
};

// Parts whose query is exhaustive: a cell a million times wider than the archive's spread puts
// every frame in one bucket of each table, and the budgets and scan depths exceed the frame
// count, so a column's query verifies every frame within reach of its radius and finds the exact
// column. No chaining.
inline QueryParts ExhaustiveParts(PoseFeatures features, NeighbourRules rules,
                                  LshRanking ranking = LshRanking::kSortValue) {
  QueryParts parts;
  parts.features = std::move(features);
  parts.rules = std::move(rules);
  const uint32_t frames = static_cast<uint32_t>(parts.features.frame_count());
  parts.options.tables = 2;
  parts.options.hashes_per_table = 4;
  parts.options.bucket_width = 1e6f;
  parts.options.probes_per_table = 3;
  parts.options.max_candidates = frames + 64;
  parts.options.max_entries = frames + 64;
  parts.options.max_bucket_scan = frames + 64;
  parts.options.ranking = ranking;
  parts.options.chain_columns = 0;
  parts.family = HashFamily::Draw(parts.features.weights(), parts.options.tables,
                                  parts.options.hashes_per_table, parts.options.bucket_width, 5);
  auto index =
      LshIndex::Build(parts.features, parts.family, 1024, 1, ranking == LshRanking::kPositionCode);
  EXPECT_TRUE(index.ok()) << index.status().ToString();
  if (index.ok()) parts.index = std::move(*index);
  parts.extension_radius = parts.rules.eps;
  return parts;
}

}  // namespace motif::testing
