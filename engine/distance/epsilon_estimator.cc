#include "engine/distance/epsilon_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/distance/distance_kernel.h"
#include "engine/distance/exact_search.h"

namespace motif {
namespace {

constexpr uint32_t kMaxTries = 64;
constexpr uint64_t kPairStream = 1;
constexpr uint64_t kQueryStream = 2;

uint64_t Mix(uint64_t value) {  // SplitMix64's finaliser
  value += 0x9e3779b97f4a7c15ull;
  value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ull;
  value = (value ^ (value >> 27)) * 0x94d049bb133111ebull;
  return value ^ (value >> 31);
}

// The draw_idx-th 64-bit draw of `stream` for `seed`: a pure function, so any draw can be made
// by any thread in any order.
uint64_t Draw(uint64_t seed, uint64_t stream, uint64_t draw_idx) {
  return Mix(Mix(seed ^ Mix(stream)) + draw_idx);
}

// A uniform index below `bound` from 64 random bits (multiply-high; bias below bound / 2^64).
uint64_t Below(uint64_t bits, uint64_t bound) {
  return static_cast<uint64_t>((static_cast<unsigned __int128>(bits) * bound) >> 64);
}

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

tbb::task_arena MakeArena(uint32_t threads) {
  return tbb::task_arena(threads > 0 ? static_cast<int>(threads) : tbb::task_arena::automatic);
}

}  // namespace

EpsilonEstimator::EpsilonEstimator(const PoseFeatures& features, NeighbourRules rules,
                                   EpsilonOptions options)
    : features_(features), rules_(std::move(rules)), options_(std::move(options)) {
  if (rules_.clip_first_frames.empty()) rules_.clip_first_frames = features.clip_first_frames();
}

Result<std::vector<FramePair>> EpsilonEstimator::SamplePairs() const {
  const uint64_t frame_count = features_.frame_count();
  const std::vector<uint64_t>& starts = rules_.clip_first_frames;
  MOTIF_RETURN_IF_ERROR(ValidateClipStarts(starts));
  // Is any pair allowed? Two non-empty clips, or one clip longer than the exclusion reach.
  const uint64_t min_gap = std::max<uint64_t>(rules_.exclusion_frames, 1);
  uint64_t non_empty_clips = 0;
  bool long_clip = false;
  for (size_t clip_idx = 0; clip_idx < starts.size(); ++clip_idx) {
    const uint64_t end = clip_idx + 1 < starts.size() ? starts[clip_idx + 1] : frame_count;
    const uint64_t length = end > starts[clip_idx] ? end - starts[clip_idx] : 0;
    if (length > 0) ++non_empty_clips;
    if (length > min_gap) long_clip = true;
  }
  if (non_empty_clips < 2 && !long_clip) {
    return Status::InvalidArgument(
        "epsilon estimate: no pair of frames to sample: " + std::to_string(frame_count) +
        " frames in " + std::to_string(non_empty_clips) +
        " clip(s), and frames of one clip must be " + std::to_string(min_gap) + " or more apart");
  }
  std::vector<FramePair> pairs;
  pairs.reserve(options_.sample_pairs);
  for (uint64_t pair_idx = 0; pair_idx < options_.sample_pairs; ++pair_idx) {
    for (uint32_t try_idx = 0; try_idx < kMaxTries; ++try_idx) {
      const uint64_t draw_idx = 2 * (pair_idx * kMaxTries + try_idx);
      const uint64_t a = Below(Draw(options_.seed, kPairStream, draw_idx), frame_count);
      const uint64_t b = Below(Draw(options_.seed, kPairStream, draw_idx + 1), frame_count);
      if (!ExclusionRangeOf(rules_, a, frame_count).Contains(b)) {
        pairs.emplace_back(a, b);
        break;
      }
    }
  }
  return pairs;
}

Result<EpsilonRule> ParseEpsilonRule(const std::string& text) {
  if (text == "joint-angle") return EpsilonRule::kJointAngle;
  if (text == "paper") return EpsilonRule::kPaper;
  return Status::InvalidOption("eps-rule", "must be joint-angle or paper, not '" + text + "'");
}

const char* EpsilonRuleName(EpsilonRule rule) {
  return rule == EpsilonRule::kPaper ? "paper" : "joint-angle";
}

double JointAngleEpsilon(const std::vector<float>& weights, double theta_degrees) {
  double weight_sum = 0;
  for (float weight : weights) weight_sum += weight;
  return weight_sum * 2.0 * std::sin(theta_degrees * M_PI / 180.0 / 4.0);
}

Result<EpsilonEstimate> EpsilonEstimator::Estimate() const {
  if (options_.explicit_eps &&
      !(std::isfinite(*options_.explicit_eps) && *options_.explicit_eps > 0)) {
    return Status::InvalidArgument("eps must be a positive number, not " +
                                   std::to_string(*options_.explicit_eps));
  }
  if (!(options_.joint_angle_degrees > 0 && options_.joint_angle_degrees <= 180)) {
    return Status::InvalidArgument(
        "the joint angle of the eps rule must be in (0, 180] degrees, not " +
        std::to_string(options_.joint_angle_degrees));
  }
  // Only the paper's rule needs the sample; the others report its statistics when there is one
  // (a take shorter than the exclusion radius has no pair to sample).
  const bool needs_sample = !options_.explicit_eps && options_.rule == EpsilonRule::kPaper;
  Result<std::vector<FramePair>> pairs = SamplePairs();
  if (!pairs.ok() && needs_sample) return pairs.status();
  if (pairs.ok() && pairs->empty() && needs_sample) {
    return Status::InvalidArgument("epsilon estimate: no frame pairs sampled (sample_pairs is " +
                                   std::to_string(options_.sample_pairs) + ")");
  }
  std::vector<float> distances = pairs.ok() ? SampledDistances(*pairs) : std::vector<float>{};
  EpsilonEstimate estimate = SampleStatistics(distances);
  estimate.rule = options_.rule;
  if (options_.explicit_eps) {
    estimate.eps = *options_.explicit_eps;
    estimate.explicit_eps = true;
    estimate.how = "given explicitly";
  } else if (options_.rule == EpsilonRule::kJointAngle) {
    estimate.eps =
        static_cast<float>(JointAngleEpsilon(features_.weights(), options_.joint_angle_degrees));
    estimate.how = "joint-angle rule: " + Format("%g", options_.joint_angle_degrees) +
                   " degrees on each of " + std::to_string(features_.weighted_joint_count()) +
                   " weighted joints";
  } else {
    ApplyPaperRule(std::move(distances), &estimate);
  }
  return estimate;
}

std::vector<float> EpsilonEstimator::SampledDistances(const std::vector<FramePair>& pairs) const {
  std::vector<float> distances(pairs.size());
  tbb::task_arena arena = MakeArena(options_.threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), /*grainsize=*/4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t pair_idx = range.begin(); pair_idx != range.end(); ++pair_idx) {
                          distances[pair_idx] = PoseDistance(features_, pairs[pair_idx].first,
                                                             pairs[pair_idx].second);
                        }
                      });
  });
  return distances;
}

EpsilonEstimate EpsilonEstimator::SampleStatistics(const std::vector<float>& distances) {
  EpsilonEstimate estimate;
  estimate.sampled_pairs = distances.size();
  if (!distances.empty()) {
    // Serial sums in pair order: the same bits for any thread count.
    double sum = 0;
    for (float distance : distances) sum += distance;
    estimate.mu = sum / static_cast<double>(distances.size());
    double squares = 0;
    for (float distance : distances) {
      squares += (distance - estimate.mu) * (distance - estimate.mu);
    }
    estimate.sigma =
        distances.size() > 1 ? std::sqrt(squares / static_cast<double>(distances.size() - 1)) : 0.0;
  }
  estimate.paper_eps = estimate.mu - 2.0 * estimate.sigma;
  return estimate;
}

void EpsilonEstimator::ApplyPaperRule(std::vector<float> distances, EpsilonEstimate* estimate) {
  const double estimated = estimate->paper_eps;
  estimate->how =
      "paper rule: mu - 2 sigma of " + std::to_string(distances.size()) + " sampled pair distances";
  if (estimated > 0) {
    estimate->eps = static_cast<float>(estimated);
    return;
  }
  // mu - 2 sigma <= 0: a heavy cluster of near-identical pairs; take the 1st percentile.
  const size_t rank = (distances.size() - 1) / 100;
  std::nth_element(distances.begin(), distances.begin() + rank, distances.end());
  float fallback = distances[rank];
  std::string rule = "the 1st percentile of the sampled distances";
  if (fallback <= 0) {
    fallback = 0;
    for (float distance : distances) {
      if (distance > 0 && (fallback == 0 || distance < fallback)) fallback = distance;
    }
    rule = "the smallest positive sampled distance (the 1st percentile is 0)";
  }
  estimate->eps = fallback;
  estimate->note = "mu - 2 sigma = " + Format("%.4f", estimated) + " <= 0 (mu " +
                   Format("%.4f", estimate->mu) + ", sigma " + Format("%.4f", estimate->sigma) +
                   "): eps is " + rule + ", " + Format("%.4f", fallback);
}

Result<NeighbourDensity> EpsilonEstimator::MeasureDensity(float eps, uint64_t query_count) const {
  if (!std::isfinite(eps) || eps < 0) {
    return Status::InvalidArgument("neighbour density: eps must be a non-negative number, not " +
                                   std::to_string(eps));
  }
  MOTIF_RETURN_IF_ERROR(ValidateClipStarts(rules_.clip_first_frames));
  const uint64_t frame_count = features_.frame_count();
  std::vector<uint64_t> queries;
  if (query_count >= frame_count) {
    queries.resize(frame_count);
    for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx)
      queries[frame_idx] = frame_idx;
  } else {
    std::unordered_set<uint64_t> chosen;
    for (uint64_t draw_idx = 0; queries.size() < query_count; ++draw_idx) {
      const uint64_t frame = Below(Draw(options_.seed, kQueryStream, draw_idx), frame_count);
      if (chosen.insert(frame).second) queries.push_back(frame);
    }
    std::sort(queries.begin(), queries.end());
  }
  NeighbourDensity density;
  density.queries = queries.size();
  if (queries.empty()) return density;

  constexpr uint32_t kQueryBlock = 256;
  constexpr uint32_t kCandidateBlock = 256;
  const DistanceKernel kernel(features_);
  std::vector<uint64_t> counts(queries.size(), 0);
  const uint64_t task_count = (queries.size() + kQueryBlock - 1) / kQueryBlock;
  tbb::task_arena arena = MakeArena(options_.threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, task_count, /*grainsize=*/1),
        [&](const tbb::blocked_range<uint64_t>& range) {
          FrameBlock query_block;
          FrameBlock candidates;
          std::vector<float> tile(static_cast<size_t>(kQueryBlock) * kCandidateBlock);
          std::vector<ExclusionRange> excluded(kQueryBlock);
          for (uint64_t task_idx = range.begin(); task_idx != range.end(); ++task_idx) {
            const uint64_t first = task_idx * kQueryBlock;
            const uint32_t block_count =
                static_cast<uint32_t>(std::min<uint64_t>(kQueryBlock, queries.size() - first));
            query_block.LoadFrames(features_, &queries[first], block_count);
            for (uint32_t query_idx = 0; query_idx < block_count; ++query_idx) {
              excluded[query_idx] =
                  ExclusionRangeOf(rules_, queries[first + query_idx], frame_count);
            }
            for (uint64_t block_first = 0; block_first < frame_count;
                 block_first += kCandidateBlock) {
              const uint32_t candidate_count = static_cast<uint32_t>(
                  std::min<uint64_t>(kCandidateBlock, frame_count - block_first));
              candidates.LoadRange(features_, block_first, candidate_count);
              kernel.Compute(query_block, candidates, tile.data(), kCandidateBlock);
              for (uint32_t query_idx = 0; query_idx < block_count; ++query_idx) {
                const float* row = &tile[static_cast<size_t>(query_idx) * kCandidateBlock];
                const ExclusionRange& skip = excluded[query_idx];
                uint64_t within = 0;
                for (uint32_t candidate_idx = 0; candidate_idx < candidate_count; ++candidate_idx) {
                  if (row[candidate_idx] <= eps)
                    within += !skip.Contains(block_first + candidate_idx);
                }
                counts[first + query_idx] += within;
              }
            }
          }
        });
  });
  uint64_t total = 0;
  for (uint64_t count : counts) total += count;
  density.mean = static_cast<double>(total) / static_cast<double>(counts.size());
  density.fraction_of_frames = density.mean / static_cast<double>(frame_count);
  std::vector<uint64_t> sorted = counts;
  std::sort(sorted.begin(), sorted.end());
  density.median = sorted[(sorted.size() - 1) / 2];
  density.p90 = sorted[(sorted.size() * 9 + 9) / 10 - 1];  // nearest rank
  density.max = sorted.back();
  return density;
}

}  // namespace motif
