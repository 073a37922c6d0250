// EpsilonEstimator: the neighbour radius eps of the matching trellis, and how many neighbours a
// frame has at that radius.
//
// Two rules (docs/design/motif_quality.md has the measurements that chose the default):
//  * kJointAngle (the default): eps = sum over the weighted joints of w_k * 2 sin(theta / 4),
//    the pose distance of two poses whose every weighted joint differs by the rotation angle
//    theta (the per-joint term |q - p| of two unit quaternions is 2 sin(angle / 4)). It says how
//    closely a person repeats a movement, which does not depend on the archive: the same for one
//    short take, a folder of mixed takes and a huge archive, and adding a take never moves it.
//  * kPaper: eps = mu - 2 sigma, with mu and sigma the mean and standard deviation of the pose
//    distance D over a seeded sample of frame pairs (Meng et al. 2008; its text says mu + 2
//    sigma, its own numbers give mu - 2 sigma). It describes how far apart unrelated poses of the
//    archive are. When mu - 2 sigma <= 0 (a very skewed sample: many near-identical pairs), eps
//    falls back to the 1st percentile of the sampled distances (or, if that is 0, the smallest
//    positive one) and `note` says so.
// Pairs that NeighbourRules excludes (a frame with itself, two frames of one clip closer than
// exclusion_frames) are never sampled; mu and sigma are reported whatever the rule. An explicit
// eps overrides both.
//
// MeasureDensity counts, for Q sampled query frames, the frames within eps of each (exact, with
// the block kernel, over all N frames, before any k_max cap, NeighbourRules' exclusions
// applied): the "achieved mean K" of a run.
//
// Determinism: pair i and query i are drawn from a hash of (seed, i), and distances are summed
// serially in pair order, so the results are the same for a seed whatever the thread count.
// Thread-safety: const methods are safe from many threads; the PoseFeatures must outlive it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "motifmine/defaults.h"

namespace motif {

using FramePair = std::pair<uint64_t, uint64_t>;

enum class EpsilonRule {
  kJointAngle,  // eps = sum_k w_k * 2 sin(theta / 4)
  kPaper,       // eps = mu - 2 sigma of sampled pair distances
};

// The default tolerated rotation per weighted joint, theta, in degrees (chosen on the labelled
// repetitions: docs/design/motif_quality.md).
inline constexpr double kDefaultJointAngleDegrees = motifmine::defaults::kEpsAngleDegrees;

// "joint-angle" / "paper"; InvalidArgument naming the text otherwise.
Result<EpsilonRule> ParseEpsilonRule(const std::string& text);
const char* EpsilonRuleName(EpsilonRule rule);

// The joint-angle rule's eps for per-joint weights and theta in degrees.
double JointAngleEpsilon(const std::vector<float>& weights, double theta_degrees);

struct EpsilonOptions {
  EpsilonRule rule = EpsilonRule::kJointAngle;
  double joint_angle_degrees = kDefaultJointAngleDegrees;  // theta of kJointAngle, in (0, 180]
  uint64_t sample_pairs = 200000;
  uint64_t seed = 1;
  std::optional<float> explicit_eps;  // overrides the estimate; must be finite and > 0
  uint32_t threads = 0;               // 0: all cores
};

struct EpsilonEstimate {
  float eps = 0;
  double mu = 0;     // mean of D over the sampled pairs
  double sigma = 0;  // its standard deviation (divided by n - 1)
  uint64_t sampled_pairs = 0;
  bool explicit_eps = false;
  EpsilonRule rule = EpsilonRule::kJointAngle;
  double paper_eps = 0;  // mu - 2 sigma, whatever the rule
  std::string how;       // one line on how eps was chosen, for the user
  std::string note;  // a warning about the choice (the paper's rule falling back); empty otherwise
};

struct NeighbourDensity {
  uint64_t queries = 0;
  double mean = 0;  // mean number of frames within eps per query frame
  uint64_t median = 0;
  uint64_t p90 = 0;  // 90th percentile
  uint64_t max = 0;
  double fraction_of_frames = 0;  // mean / N
};

class EpsilonEstimator {
 public:
  // Uses rules.exclusion_frames and rules.clip_first_frames (the archive's clips if empty);
  // rules.eps and k_max are ignored.
  EpsilonEstimator(const PoseFeatures& features, NeighbourRules rules, EpsilonOptions options = {});

  // The sampled pairs (a, b), a != b, none excluded by the rules, in sampling order. A pair
  // whose draws keep landing on excluded pairs is given up after 64 tries, so on tiny archives
  // fewer than sample_pairs may be returned. InvalidArgument if no pair at all is allowed
  // (fewer than two frames, or a single clip not longer than exclusion_frames), or if the clip
  // list does not start with 0 or is not ascending.
  Result<std::vector<FramePair>> SamplePairs() const;

  // mu, sigma and eps as described above. InvalidArgument: with the paper's rule, as
  // SamplePairs or no pair sampled (sample_pairs = 0); with any rule, an explicit eps that is
  // not a positive finite number, or a joint angle outside (0, 180].
  Result<EpsilonEstimate> Estimate() const;

  // The neighbour counts at `eps` of `query_count` sampled frames (every frame if query_count
  // >= N, otherwise distinct frames drawn from the seed). InvalidArgument if eps is negative or
  // not finite, or the clip list is malformed.
  Result<NeighbourDensity> MeasureDensity(float eps, uint64_t query_count) const;

 private:
  std::vector<float> SampledDistances(const std::vector<FramePair>& pairs) const;
  static EpsilonEstimate SampleStatistics(const std::vector<float>& distances);
  // eps = mu - 2 sigma, or its fallback (consumes the distances).
  static void ApplyPaperRule(std::vector<float> distances, EpsilonEstimate* estimate);

  const PoseFeatures& features_;
  NeighbourRules rules_;
  EpsilonOptions options_;
};

}  // namespace motif
