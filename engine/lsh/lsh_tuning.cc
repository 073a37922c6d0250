#include "engine/lsh/lsh_tuning.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/split_mix64.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/query_distance.h"

namespace motif {
namespace {

constexpr uint32_t kSampleQueries = 64;
constexpr uint64_t kSubsampleFrames = uint64_t{1} << 17;

// The frames of the subsample: all of a small archive, else evenly spaced from a seeded start.
std::vector<uint64_t> Subsample(uint64_t frame_count, SplitMix64* random) {
  std::vector<uint64_t> frames;
  if (frame_count <= kSubsampleFrames) {
    frames.resize(frame_count);
    for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx)
      frames[frame_idx] = frame_idx;
    return frames;
  }
  const double step = static_cast<double>(frame_count) / kSubsampleFrames;
  const double start = random->Uniform() * step;
  frames.resize(kSubsampleFrames);
  for (uint64_t idx = 0; idx < kSubsampleFrames; ++idx) {
    frames[idx] = std::min<uint64_t>(
        frame_count - 1, static_cast<uint64_t>(start + step * static_cast<double>(idx)));
  }
  return frames;
}

}  // namespace

namespace {

// The sampled frames' radii and their neighbour pairs' embedding distances: one slot per sampled
// frame, so the result depends neither on the threads nor on the ranks that fill them.
struct ScaleSamples {
  std::vector<float> radii;      // per query
  std::vector<uint32_t> counts;  // per query: its pairs
  std::vector<float> pair_l2;    // per query: `slots` values, the first counts[q] used
  size_t slots = 0;
};

// Fills the samples of queries [first, end).
void SampleQueries(const PoseFeatures& features, const NeighbourRules& rules,
                   const LshOptions& options, const std::vector<uint64_t>& queries,
                   const std::vector<uint64_t>& subsample, uint64_t first, uint64_t end,
                   ScaleSamples* samples) {
  const HashFamily embedding = HashFamily::Draw(features.weights(), 1, 1, 1.0f, 1);
  const uint32_t dims = embedding.embedding_dims();
  const size_t rank = samples->slots;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(first, end, 1), [&](const tbb::blocked_range<size_t>& range) {
          QueryDistance distance(features);
          std::vector<std::pair<float, uint64_t>> near;
          std::vector<float> query_e(dims);
          std::vector<float> frame_e(dims);
          for (size_t query_idx = range.begin(); query_idx != range.end(); ++query_idx) {
            const uint64_t query = queries[query_idx];
            const uint32_t query_clip = features.ClipOf(query);
            distance.SetQuery(query);
            near.clear();
            for (uint64_t frame : subsample) {
              if (rules.Excluded(query, frame, query_clip, features.ClipOf(frame))) continue;
              const float value = distance.To(frame, rules.eps);
              if (value <= rules.eps) near.push_back({value, frame});
            }
            size_t kept = near.size();
            if (near.size() >= rank) {
              std::nth_element(near.begin(), near.begin() + (rank - 1), near.end());
              samples->radii[query_idx] = std::min(rules.eps, near[rank - 1].first);
              kept = rank;
            }
            embedding.Embed(features.frame(query), query_e.data());
            float* out = &samples->pair_l2[query_idx * rank];
            for (size_t idx = 0; idx < kept; ++idx) {
              embedding.Embed(features.frame(near[idx].second), frame_e.data());
              double squared = 0;
              for (uint32_t dim = 0; dim < dims; ++dim) {
                const double diff = frame_e[dim] - query_e[dim];
                squared += diff * diff;
              }
              out[idx] = static_cast<float>(std::sqrt(squared));
            }
            samples->counts[query_idx] = static_cast<uint32_t>(kept);
          }
        });
  });
}

// The scale of filled samples.
SearchScale ScaleOf(ScaleSamples samples) {
  SearchScale scale;
  std::vector<float>& radii = samples.radii;
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  scale.radius = std::max(radii[radii.size() / 2], 1e-4f);
  std::vector<float> pooled;
  for (size_t query_idx = 0; query_idx < samples.counts.size(); ++query_idx) {
    const float* values = &samples.pair_l2[query_idx * samples.slots];
    pooled.insert(pooled.end(), values, values + samples.counts[query_idx]);
  }
  scale.neighbour_pairs = pooled.size();
  if (pooled.empty()) {
    scale.neighbour_l2 = scale.neighbour_l2_p90 = scale.radius / 2;
  } else {
    std::sort(pooled.begin(), pooled.end());
    scale.neighbour_l2 = std::max(pooled[pooled.size() / 2], 1e-4f);
    scale.neighbour_l2_p90 = std::max(pooled[pooled.size() * 9 / 10], 1e-4f);
  }
  return scale;
}

}  // namespace

SearchScale EstimateSearchScale(const PoseFeatures& features, const NeighbourRules& rules,
                                const LshOptions& options) {
  Result<SearchScale> scale = EstimateSearchScale(features, rules, options, nullptr);
  MOTIF_CHECK(scale.ok());  // only an exchange between ranks can fail
  return *scale;
}

Result<SearchScale> EstimateSearchScale(const PoseFeatures& features, const NeighbourRules& rules,
                                        const LshOptions& options, RankGroup* ranks) {
  const uint64_t frame_count = features.frame_count();
  if (frame_count < 2 || features.weighted_joint_count() == 0) {
    SearchScale scale;
    scale.radius = rules.eps;
    scale.neighbour_l2 = scale.neighbour_l2_p90 = rules.eps / 2;
    return scale;
  }
  SplitMix64 random(options.seed ^ 0x7261646975735eedull);
  std::vector<uint64_t> queries(kSampleQueries);
  for (uint64_t& query : queries) query = random.Below(frame_count);
  const std::vector<uint64_t> subsample = Subsample(frame_count, &random);
  const double scaled_rank = static_cast<double>(rules.k_max) *
                             static_cast<double>(subsample.size()) /
                             static_cast<double>(frame_count);
  ScaleSamples samples;
  samples.slots = std::max<size_t>(4, static_cast<size_t>(std::llround(scaled_rank)));
  samples.radii.assign(queries.size(), rules.eps);
  samples.counts.assign(queries.size(), 0);
  samples.pair_l2.assign(queries.size() * samples.slots, 0.0f);
  // A distributed run: each rank samples a share of the queries, then all exchange them.
  const RankShare share = ShareOf(queries.size(), ranks);
  const std::vector<uint64_t>& starts = share.starts;
  SampleQueries(features, rules, options, queries, subsample, share.first(), share.end(), &samples);
  if (share.shared()) {
    MOTIF_RETURN_IF_ERROR(ranks->ShareParts(samples.radii.data(), sizeof(float), starts));
    MOTIF_RETURN_IF_ERROR(ranks->ShareParts(samples.counts.data(), sizeof(uint32_t), starts));
    MOTIF_RETURN_IF_ERROR(
        ranks->ShareParts(samples.pair_l2.data(), samples.slots * sizeof(float), starts));
  }
  return ScaleOf(std::move(samples));
}

uint32_t DefaultHashesPerTable(uint64_t frame_count) {
  const double bits = std::log2(static_cast<double>(std::max<uint64_t>(frame_count, 2)));
  return static_cast<uint32_t>(std::clamp<long long>(4 + std::llround(0.6 * bits), 8, 24));
}

LshOptions ResolveLshOptions(const LshOptions& options, uint64_t frame_count,
                             uint32_t weighted_joint_count, const SearchScale& scale) {
  LshOptions resolved = options;
  if (resolved.hashes_per_table == 0) {
    // At most the embedding's dimension - 1 (one more row is the sort direction).
    resolved.hashes_per_table =
        std::min(DefaultHashesPerTable(frame_count),
                 HashFamily::kDimsPerJoint * std::max(1u, weighted_joint_count) - 1);
  }
  if (resolved.bucket_width == 0) {
    resolved.bucket_width = resolved.width_per_hash *
                            static_cast<float>(resolved.hashes_per_table) * scale.neighbour_l2_p90;
  }
  return resolved;
}

LshOptions ResolveLshOptions(const PoseFeatures& features, const NeighbourRules& rules,
                             const LshOptions& options) {
  const SearchScale scale =
      options.bucket_width == 0 ? EstimateSearchScale(features, rules, options) : SearchScale();
  return ResolveLshOptions(options, features.frame_count(), features.weighted_joint_count(), scale);
}

}  // namespace motif
