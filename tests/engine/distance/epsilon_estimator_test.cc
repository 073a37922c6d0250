#include "engine/distance/epsilon_estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "engine/distance/exact_search.h"
#include "formats/import/take_importer.h"
#include "formats/motion/resample.h"
#include "tests/engine/distance/distance_test_util.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

NeighbourRules Rules(const PoseFeatures& features, uint32_t exclusion_frames = 30) {
  NeighbourRules rules;
  rules.exclusion_frames = exclusion_frames;
  rules.clip_first_frames = features.clip_first_frames();
  return rules;
}

// The paper's rule: most tests here are about the sample and mu - 2 sigma.
EpsilonOptions Options(uint64_t pairs, uint64_t seed = 1, uint32_t threads = 0) {
  EpsilonOptions options;
  options.rule = EpsilonRule::kPaper;
  options.sample_pairs = pairs;
  options.seed = seed;
  options.threads = threads;
  return options;
}

const PoseFeatures& SharedFeatures() {
  static const auto* features = new PoseFeatures(testing::SynthArchive(4000, 41).Features());
  return *features;
}

TEST(EpsilonEstimator, SampledPairsRespectTheNeighbourRules) {
  const PoseFeatures& features = SharedFeatures();
  const NeighbourRules rules = Rules(features);
  Result<std::vector<FramePair>> pairs =
      EpsilonEstimator(features, rules, Options(20000)).SamplePairs();
  ASSERT_TRUE(pairs.ok()) << pairs.status().ToString();
  ASSERT_EQ(pairs->size(), 20000u);
  uint64_t same_clip = 0;
  for (const auto& [a, b] : *pairs) {
    ASSERT_LT(a, features.frame_count());
    ASSERT_LT(b, features.frame_count());
    ASSERT_FALSE(rules.Excluded(a, b, features.ClipOf(a), features.ClipOf(b))) << a << " " << b;
    same_clip += features.ClipOf(a) == features.ClipOf(b);
  }
  EXPECT_GT(same_clip, 0u) << "pairs inside one clip far enough apart are sampled too";
  // Roughly uniform: every tenth of the archive is hit.
  std::vector<uint64_t> tenths(10, 0);
  for (const auto& [a, b] : *pairs) ++tenths[a * 10 / features.frame_count()];
  for (uint64_t hits : tenths) EXPECT_GT(hits, 1500u);
}

TEST(EpsilonEstimator, SamplingIsDeterministicForASeed) {
  const PoseFeatures& features = SharedFeatures();
  auto sample = [&](uint64_t seed) {
    return EpsilonEstimator(features, Rules(features), Options(5000, seed)).SamplePairs().value();
  };
  EXPECT_EQ(sample(3), sample(3));
  EXPECT_NE(sample(3), sample(4));
}

TEST(EpsilonEstimator, EstimateIsMuMinusTwoSigmaOfTheSampledDistances) {
  const PoseFeatures& features = SharedFeatures();
  const EpsilonEstimator estimator(features, Rules(features), Options(30000, 9));
  Result<EpsilonEstimate> estimate = estimator.Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  const std::vector<FramePair> pairs = estimator.SamplePairs().value();
  double sum = 0;
  double squares = 0;
  for (const auto& [a, b] : pairs) sum += PoseDistance(features, a, b);
  const double mu = sum / static_cast<double>(pairs.size());
  for (const auto& [a, b] : pairs) {
    squares += (PoseDistance(features, a, b) - mu) * (PoseDistance(features, a, b) - mu);
  }
  const double sigma = std::sqrt(squares / static_cast<double>(pairs.size() - 1));
  EXPECT_EQ(estimate->sampled_pairs, 30000u);
  EXPECT_NEAR(estimate->mu, mu, 1e-9);
  EXPECT_NEAR(estimate->sigma, sigma, 1e-9);
  EXPECT_NEAR(estimate->eps, mu - 2 * sigma, 1e-6);
  EXPECT_GT(estimate->eps, 0.0f);
  EXPECT_FALSE(estimate->explicit_eps);
  EXPECT_TRUE(estimate->note.empty()) << estimate->note;
}

TEST(EpsilonEstimator, JointAngleRuleIsTheDistanceOfPosesTurnedByThetaAtEveryWeightedJoint) {
  // Two unit quaternions theta apart are 2 sin(theta / 4) apart: 10 degrees on 12 joints of
  // weight 1 is 24 sin(2.5 degrees) = 1.046865.
  EXPECT_NEAR(JointAngleEpsilon(std::vector<float>(12, 1.0f), 10.0), 1.046865, 1e-6);
  EXPECT_NEAR(JointAngleEpsilon({1.0f, 0.5f}, 180.0), 1.5 * std::sqrt(2.0), 1e-9);
  // The rule's eps is exactly the distance of a frame and its copy with every joint turned by
  // theta about some axis (a synthetic two-frame check through PoseDistance).
  const uint32_t joint_count = 3;
  const FrameLayout layout{joint_count};
  std::vector<float> rows(2 * layout.stride(), 0.0f);
  const double half = 10.0 * M_PI / 180.0 / 2.0;
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    float* first = &rows[layout.quaternion_offset(joint_idx)];
    float* second = &rows[layout.stride() + layout.quaternion_offset(joint_idx)];
    first[0] = 1.0f;
    second[0] = static_cast<float>(std::cos(half));
    second[1 + joint_idx] = static_cast<float>(std::sin(half));  // about x, y, z in turn
  }
  const std::vector<float> weights = {1.0f, 2.0f, 0.5f};
  const PoseFeatures two = PoseFeatures::FromRows(rows.data(), 2, joint_count, weights, {0});
  EXPECT_NEAR(PoseDistance(two, 0, 1), JointAngleEpsilon(weights, 10.0), 2e-3);
}

TEST(EpsilonEstimator, JointAngleRuleIsTheDefaultAndReportsThePaperRuleBeside) {
  const PoseFeatures& features = SharedFeatures();
  EpsilonOptions options;
  options.sample_pairs = 20000;
  Result<EpsilonEstimate> estimate =
      EpsilonEstimator(features, Rules(features), options).Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  EXPECT_EQ(estimate->rule, EpsilonRule::kJointAngle);
  EXPECT_FLOAT_EQ(estimate->eps, static_cast<float>(JointAngleEpsilon(features.weights(),
                                                                      kDefaultJointAngleDegrees)));
  EXPECT_NEAR(estimate->paper_eps, estimate->mu - 2 * estimate->sigma, 1e-12);
  EXPECT_NE(estimate->how.find("joint-angle rule"), std::string::npos) << estimate->how;
  EXPECT_TRUE(estimate->note.empty()) << estimate->note;
  options.joint_angle_degrees = 20.0;
  EXPECT_FLOAT_EQ(EpsilonEstimator(features, Rules(features), options).Estimate()->eps,
                  static_cast<float>(JointAngleEpsilon(features.weights(), 20.0)));
  for (double bad : {0.0, -5.0, 181.0, std::nan("")}) {
    options.joint_angle_degrees = bad;
    EXPECT_TRUE(EpsilonEstimator(features, Rules(features), options)
                    .Estimate()
                    .status()
                    .IsInvalidArgument())
        << bad;
  }
  EXPECT_EQ(ParseEpsilonRule("paper").value(), EpsilonRule::kPaper);
  EXPECT_EQ(ParseEpsilonRule("joint-angle").value(), EpsilonRule::kJointAngle);
  EXPECT_TRUE(ParseEpsilonRule("mu").status().IsInvalidArgument());
}

TEST(EpsilonEstimator, EstimateIsTheSameForAnyThreadCount) {
  const PoseFeatures& features = SharedFeatures();
  const EpsilonEstimate one =
      EpsilonEstimator(features, Rules(features), Options(50000, 5, 1)).Estimate().value();
  const EpsilonEstimate two =
      EpsilonEstimator(features, Rules(features), Options(50000, 5, 2)).Estimate().value();
  EXPECT_EQ(one.mu, two.mu);
  EXPECT_EQ(one.sigma, two.sigma);
  EXPECT_EQ(one.eps, two.eps);
  EXPECT_EQ(one.sampled_pairs, two.sampled_pairs);
}

TEST(EpsilonEstimator, ExplicitEpsilonOverridesTheEstimate) {
  const PoseFeatures& features = SharedFeatures();
  EpsilonOptions options = Options(10000);
  options.explicit_eps = 0.75f;
  Result<EpsilonEstimate> estimate =
      EpsilonEstimator(features, Rules(features), options).Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  EXPECT_EQ(estimate->eps, 0.75f);
  EXPECT_TRUE(estimate->explicit_eps);
  EXPECT_GT(estimate->mu, 0.0);  // the statistics are still reported
  EXPECT_NE(estimate->how.find("given"), std::string::npos) << estimate->how;
  // No sample needed when eps is given; without one, an empty sample is an error.
  options.sample_pairs = 0;
  estimate = EpsilonEstimator(features, Rules(features), options).Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  EXPECT_EQ(estimate->eps, 0.75f);
  EXPECT_EQ(estimate->sampled_pairs, 0u);
  EXPECT_TRUE(EpsilonEstimator(features, Rules(features), Options(0))
                  .Estimate()
                  .status()
                  .IsInvalidArgument());
  options.sample_pairs = 1000;
  for (float bad : {0.0f, -1.0f, std::nanf("")}) {
    options.explicit_eps = bad;
    EXPECT_TRUE(EpsilonEstimator(features, Rules(features), options)
                    .Estimate()
                    .status()
                    .IsInvalidArgument())
        << bad;
  }
}

TEST(EpsilonEstimator, FallsBackToTheFirstPercentileWhenMuMinusTwoSigmaIsNotPositive) {
  // 80 % of the frames hold nearly one pose, the rest are random: most pairs are tiny, a few
  // large, and mu - 2 sigma < 0.
  const uint32_t joint_count = 4;
  const uint64_t frame_count = 1000;
  std::vector<float> rows = testing::RandomRows(frame_count, joint_count, 3);
  const FrameLayout layout{joint_count};
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 0.003);
  for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    if (frame_idx % 5 == 0) continue;
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      Eigen::Quaterniond q(1.0, noise(rng), noise(rng), noise(rng));
      q.normalize();
      float* out = &rows[frame_idx * layout.stride() + layout.quaternion_offset(joint_idx)];
      out[0] = static_cast<float>(q.w());
      out[1] = static_cast<float>(q.x());
      out[2] = static_cast<float>(q.y());
      out[3] = static_cast<float>(q.z());
    }
  }
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), frame_count, joint_count,
                                                       std::vector<float>(joint_count, 1.0f), {0});
  const EpsilonEstimator estimator(features, Rules(features), Options(20000));
  Result<EpsilonEstimate> estimate = estimator.Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  ASSERT_LE(estimate->mu - 2 * estimate->sigma, 0.0);
  std::vector<float> distances;
  const std::vector<FramePair> pairs = estimator.SamplePairs().value();
  for (const auto& [a, b] : pairs) {
    distances.push_back(PoseDistance(features, a, b));
  }
  std::sort(distances.begin(), distances.end());
  EXPECT_EQ(estimate->eps, distances[(distances.size() - 1) / 100]);
  EXPECT_GT(estimate->eps, 0.0f);
  EXPECT_NE(estimate->note.find("1st percentile"), std::string::npos) << estimate->note;
  EXPECT_NE(estimate->note.find("<= 0"), std::string::npos) << estimate->note;
}

TEST(EpsilonEstimator, RejectsAnArchiveWithNoPairToSampleOrAMalformedClipList) {
  const std::vector<float> rows = testing::RandomRows(30, 1, 5);
  const PoseFeatures one_clip = PoseFeatures::FromRows(rows.data(), 30, 1, {1.0f}, {0});
  Result<EpsilonEstimate> estimate =
      EpsilonEstimator(one_clip, Rules(one_clip, 30), Options(100)).Estimate();
  EXPECT_TRUE(estimate.status().IsInvalidArgument()) << estimate.status().ToString();
  // One clip of 31 frames has exactly one allowed pair, (0, 30), in either order.
  const std::vector<float> more = testing::RandomRows(31, 1, 5);
  const PoseFeatures longer = PoseFeatures::FromRows(more.data(), 31, 1, {1.0f}, {0});
  Result<std::vector<FramePair>> pairs =
      EpsilonEstimator(longer, Rules(longer, 30), Options(100)).SamplePairs();
  ASSERT_TRUE(pairs.ok()) << pairs.status().ToString();
  EXPECT_GT(pairs->size(), 0u);
  for (const auto& [a, b] : *pairs) EXPECT_EQ(std::min(a, b) + 30, std::max(a, b));
  // A malformed clip list.
  NeighbourRules bad_clips = Rules(longer, 30);
  bad_clips.clip_first_frames = {3, 1};
  EXPECT_TRUE(
      EpsilonEstimator(longer, bad_clips, Options(10)).Estimate().status().IsInvalidArgument());
  EXPECT_TRUE(
      EpsilonEstimator(longer, bad_clips).MeasureDensity(1.0f, 5).status().IsInvalidArgument());
  // Two clips of one frame each: one pair.
  const PoseFeatures two_clips = PoseFeatures::FromRows(rows.data(), 2, 1, {1.0f}, {0, 1});
  EXPECT_TRUE(EpsilonEstimator(two_clips, Rules(two_clips), Options(10)).Estimate().ok());
}

TEST(EpsilonEstimator, DensityMatchesADirectCountOverAllFrames) {
  const testing::ArchiveRows archive = testing::SynthArchive(2000, 43);
  const PoseFeatures features = archive.Features();
  const NeighbourRules rules = Rules(features);
  const float eps = 1.5f;
  std::vector<uint64_t> counts;
  for (uint64_t t = 0; t < features.frame_count(); ++t) {
    uint64_t count = 0;
    for (uint64_t j = 0; j < features.frame_count(); ++j) {
      count += !rules.Excluded(t, j, features.ClipOf(t), features.ClipOf(j)) &&
               PoseDistance(features, t, j) <= eps;
    }
    counts.push_back(count);
  }
  Result<NeighbourDensity> density =
      EpsilonEstimator(features, rules).MeasureDensity(eps, features.frame_count());
  ASSERT_TRUE(density.ok()) << density.status().ToString();
  uint64_t total = 0;
  for (uint64_t count : counts) total += count;
  std::sort(counts.begin(), counts.end());
  EXPECT_EQ(density->queries, features.frame_count());
  EXPECT_DOUBLE_EQ(density->mean, static_cast<double>(total) / counts.size());
  EXPECT_EQ(density->median, counts[(counts.size() - 1) / 2]);
  EXPECT_EQ(density->max, counts.back());
  EXPECT_GT(density->mean, 10.0) << "the test needs neighbours";
  EXPECT_DOUBLE_EQ(density->fraction_of_frames, density->mean / features.frame_count());
  // The same through ExactSearch with no cap.
  NeighbourRules search_rules = rules;
  search_rules.eps = eps;
  search_rules.k_max = UINT32_MAX;
  SearchStats stats;
  std::vector<std::vector<Neighbour>> columns;
  ASSERT_TRUE(ExactSearch(features, search_rules)
                  .SearchColumns(0, features.frame_count(), &columns, &stats)
                  .ok());
  EXPECT_EQ(stats.neighbours, total);
}

TEST(EpsilonEstimator, DensityOfSampledQueriesIsDeterministic) {
  const PoseFeatures& features = SharedFeatures();
  auto measure = [&](uint64_t seed, uint32_t threads) {
    return EpsilonEstimator(features, Rules(features), Options(0, seed, threads))
        .MeasureDensity(1.2f, 300)
        .value();
  };
  const NeighbourDensity one = measure(7, 1);
  const NeighbourDensity two = measure(7, 2);
  EXPECT_EQ(one.queries, 300u);
  EXPECT_EQ(one.mean, two.mean);
  EXPECT_EQ(one.median, two.median);
  EXPECT_EQ(one.p90, two.p90);
  EXPECT_EQ(one.max, two.max);
  EXPECT_NE(measure(8, 2).mean, one.mean);
  EXPECT_TRUE(EpsilonEstimator(features, Rules(features))
                  .MeasureDensity(-1.0f, 10)
                  .status()
                  .IsInvalidArgument());
}

// The figures of docs/design/algorithm.md 6.2: the 62 BVH takes (40,346 frames), 12 weighted
// joints, sampled pairs: mu = 3.11, sigma = 1.04, eps = mu - 2 sigma = 1.02; at eps 1.02 with a
// 30-frame exclusion radius a frame has on average 359 neighbours (0.9 % of N; median 218, 90th
// percentile 951, max 1631). Measured here (seed 1, 200,000 pairs): mu 3.097, sigma 1.024, so
// eps 1.049 (seeds 2 and 3 give the same to 0.003); the density at eps 1.02 over all N frames is
// mean 359.8, median 219, p90 957, max 1637 (this test samples 4000 query frames to stay fast).
// 05_05.bvh has 180-degree hip flips in the file itself: they are kept, as the data says.
TEST(EpsilonEstimator, ReproducesTheMeasuredFiguresOnTheRealTakes) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const auto start = std::chrono::steady_clock::now();
  ImportOptions import_options;
  Result<std::vector<TakeSource>> sources =
      DiscoverTakes({testing::MocapDir() + "/bvh"}, import_options);
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  testing::ArchiveRows archive;
  for (const TakeSource& source : *sources) {
    Result<Take> take = ImportTake(source, import_options);
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    ASSERT_EQ(take->skeleton.family(), kCmuFamily) << source.path;
    if (archive.frame_count == 0) archive.skeleton = take->skeleton;
    ASSERT_TRUE(take->skeleton.SameHierarchy(archive.skeleton)) << source.path;
    if (!SameFrameRate(take->fps, 120.0)) *take = ResampleTake(*take, 120.0);
    archive.Append(TakeToClipFrames(*take));
  }
  Result<std::vector<float>> weights = LoadDistanceWeights(archive.skeleton, "");
  ASSERT_TRUE(weights.ok());
  const PoseFeatures features = PoseFeatures::FromRows(
      archive.rows.data(), archive.frame_count,
      static_cast<uint32_t>(archive.skeleton.joint_count()), *weights, archive.clip_first_frames);
  EXPECT_EQ(sources->size(), 62u);
  EXPECT_EQ(features.frame_count(), 40346u);
  EXPECT_EQ(features.weighted_joint_count(), 12u);

  const EpsilonEstimator estimator(features, Rules(features, 30), Options(200000, 1));
  Result<EpsilonEstimate> estimate = estimator.Estimate();
  ASSERT_TRUE(estimate.ok()) << estimate.status().ToString();
  Result<NeighbourDensity> at_eps_1_02 = estimator.MeasureDensity(1.02f, 4000);
  Result<NeighbourDensity> at_estimate = estimator.MeasureDensity(estimate->eps, 4000);
  ASSERT_TRUE(at_eps_1_02.ok() && at_estimate.ok());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto print_density = [](const char* label, float eps, const NeighbourDensity& density) {
    std::printf(
        "  at eps %.3f (%s), %llu queries: mean K %.1f (%.2f %% of N), median %llu, "
        "p90 %llu, max %llu\n",
        eps, label, static_cast<unsigned long long>(density.queries), density.mean,
        100 * density.fraction_of_frames, static_cast<unsigned long long>(density.median),
        static_cast<unsigned long long>(density.p90), static_cast<unsigned long long>(density.max));
  };
  std::printf(
      "real takes: %zu takes, %llu frames; %llu pairs: mu %.4f sigma %.4f eps %.4f "
      "(%.1f s in all)\n",
      sources->size(), static_cast<unsigned long long>(features.frame_count()),
      static_cast<unsigned long long>(estimate->sampled_pairs), estimate->mu, estimate->sigma,
      estimate->eps, seconds);
  print_density("algorithm.md 6.2", 1.02f, *at_eps_1_02);
  print_density("estimated", estimate->eps, *at_estimate);
  ::testing::Test::RecordProperty("mu", std::to_string(estimate->mu));
  ::testing::Test::RecordProperty("sigma", std::to_string(estimate->sigma));
  ::testing::Test::RecordProperty("eps", std::to_string(estimate->eps));
  ::testing::Test::RecordProperty("mean_k_at_1_02", std::to_string(at_eps_1_02->mean));
  ::testing::Test::RecordProperty("mean_k_at_eps", std::to_string(at_estimate->mean));

  EXPECT_NEAR(estimate->mu, 3.11, 0.02);
  EXPECT_NEAR(estimate->sigma, 1.04, 0.025);
  EXPECT_NEAR(estimate->eps, 1.02, 0.04);
  EXPECT_NEAR(at_eps_1_02->mean, 359, 20);
  EXPECT_NEAR(static_cast<double>(at_eps_1_02->median), 218, 20);
  EXPECT_NEAR(static_cast<double>(at_eps_1_02->p90), 951, 50);
  EXPECT_LE(at_eps_1_02->max, 1640u);
  // Within the bounds of eps, the density moves as eps does.
  EXPECT_GT(at_estimate->mean, at_eps_1_02->mean);
  EXPECT_LT(at_estimate->mean, 1.2 * at_eps_1_02->mean);
}

}  // namespace
}  // namespace motif
