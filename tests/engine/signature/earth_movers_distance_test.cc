#include "engine/signature/earth_movers_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "common/split_mix64.h"
#include "engine/signature/ground_distance.h"

namespace motif {
namespace {

using Histogram = std::vector<double>;

// Motifs on a line at the given positions: ground(a, b) = |x_a - x_b|.
Eigen::MatrixXd LineGround(const std::vector<double>& positions) {
  const Eigen::Index k = static_cast<Eigen::Index>(positions.size());
  Eigen::MatrixXd ground(k, k);
  for (Eigen::Index a = 0; a < k; ++a) {
    for (Eigen::Index b = 0; b < k; ++b) ground(a, b) = std::abs(positions[a] - positions[b]);
  }
  return ground;
}

std::vector<double> UnitSpacing(size_t k) {
  std::vector<double> positions(k);
  for (size_t bin = 0; bin < k; ++bin) positions[bin] = static_cast<double>(bin);
  return positions;
}

// On a line, the EMD of unit-mass histograms is the L1 distance between their CDFs, each step
// weighted by the gap to the next position (the 1-D Wasserstein distance over motif POSITIONS).
double CdfDistance(const Histogram& p, const Histogram& q, const std::vector<double>& positions) {
  double p_total = 0;
  double q_total = 0;
  for (size_t bin = 0; bin < p.size(); ++bin) {
    p_total += p[bin];
    q_total += q[bin];
  }
  double p_cdf = 0;
  double q_cdf = 0;
  double distance = 0;
  for (size_t bin = 0; bin + 1 < p.size(); ++bin) {
    p_cdf += p[bin] / p_total;
    q_cdf += q[bin] / q_total;
    distance += std::abs(p_cdf - q_cdf) * (positions[bin + 1] - positions[bin]);
  }
  return distance;
}

// A tempting mistake: a 1-D Wasserstein distance between the two sets of bin
// VALUES (sorted, paired), which forgets which motif each bin is.
double ValueWasserstein(Histogram p, Histogram q) {
  std::sort(p.begin(), p.end());
  std::sort(q.begin(), q.end());
  double distance = 0;
  for (size_t idx = 0; idx < p.size(); ++idx) distance += std::abs(p[idx] - q[idx]);
  return distance / static_cast<double>(p.size());
}

Histogram RandomHistogram(size_t k, double zero_fraction, SplitMix64* random) {
  Histogram histogram(k, 0.0);
  for (double& mass : histogram) mass = random->Uniform() < zero_fraction ? 0.0 : random->Uniform();
  histogram[random->Below(k)] += 0.5;  // never empty
  return histogram;
}

// Random points in the plane: their Euclidean distances are a metric ground distance.
Eigen::MatrixXd RandomMetricGround(size_t k, SplitMix64* random) {
  RowMatrixXf centroids(k, 2);
  for (size_t row = 0; row < k; ++row) {
    centroids(row, 0) = static_cast<float>(random->Uniform());
    centroids(row, 1) = static_cast<float>(random->Uniform());
  }
  return CentroidGroundDistance(centroids);
}

double Emd(const Histogram& p, const Histogram& q, const Eigen::MatrixXd& ground,
           EmdMass mass = EmdMass::kNormalize) {
  EarthMoversDistance emd({.mass = mass});
  Result<double> distance = emd.Distance(p, q, ground);
  EXPECT_TRUE(distance.ok()) << distance.status().ToString();
  return distance.ok() ? *distance : std::numeric_limits<double>::quiet_NaN();
}

TEST(EarthMoversDistance, OneDimensionalPointMassesCostTheirSpacing) {
  const Eigen::MatrixXd ground = LineGround(UnitSpacing(4));
  EXPECT_NEAR(Emd({1, 0, 0, 0}, {0, 0, 0, 1}, ground), 3.0, 1e-12);
  EXPECT_NEAR(Emd({1, 0, 0, 0}, {0, 1, 0, 0}, ground), 1.0, 1e-12);
  // Half a unit moves two steps, the other half two steps: 0.5 * 2 + 0.5 * 2.
  EXPECT_NEAR(Emd({0.5, 0.5, 0, 0}, {0, 0, 0.5, 0.5}, ground), 2.0, 1e-12);
  // CDFs 0.5, 1, 1 against 0, 0.5, 0.5: |.5| + |.5| + |.5| = 1.5.
  EXPECT_NEAR(Emd({0.5, 0.5, 0, 0}, {0, 0.5, 0, 0.5}, ground), 1.5, 1e-12);
}

TEST(EarthMoversDistance, OneDimensionalEqualsTheL1DistanceOfTheCdfs) {
  SplitMix64 random(11);
  for (int case_idx = 0; case_idx < 200; ++case_idx) {
    const size_t k = 2 + random.Below(20);
    std::vector<double> positions = UnitSpacing(k);
    const bool uneven = case_idx % 2 == 1;  // odd cases: random gaps between motifs
    if (uneven) {
      for (size_t bin = 1; bin < k; ++bin) positions[bin] = positions[bin - 1] + random.Uniform();
    }
    const Histogram p = RandomHistogram(k, 0.3, &random);
    const Histogram q = RandomHistogram(k, 0.3, &random);
    EXPECT_NEAR(Emd(p, q, LineGround(positions)), CdfDistance(p, q, positions), 1e-10)
        << "case " << case_idx;
  }
}

// p = (.5, .3, .2) onto q = (.4, .4, .2) with an asymmetric, non-metric ground:
//          to 0  to 1  to 2
//   from 0   4     1     3
//   from 1   2     5     4
//   from 2   1     3     6
// Optimal plan: 0->1 .4, 0->2 .1, 1->0 .2, 1->2 .1, 2->0 .2; cost .4 + .3 + .4 + .4 + .2 = 1.7.
// Proof by duals (u_from + v_to = cost on the plan's five cells): u = (0, 1, 0), v = (1, 1, 3);
// the other cells' reduced costs cost - u - v are 3 (0->0), 3 (1->1), 2 (2->1), 3 (2->2), all
// positive, so the plan is optimal and unique (the next best vertex costs 1.9).
TEST(EarthMoversDistance, ThreeByThreeByHand) {
  const Eigen::MatrixXd ground = (Eigen::MatrixXd(3, 3) << 4, 1, 3, 2, 5, 4, 1, 3, 6).finished();
  EarthMoversDistance emd;
  Result<EmdSolution> solution = emd.Solve({{0.5, 0.3, 0.2}}, {{0.4, 0.4, 0.2}}, ground);
  ASSERT_TRUE(solution.ok()) << solution.status().ToString();
  EXPECT_NEAR(solution->distance, 1.7, 1e-12);
  const std::vector<EmdFlow> expected = {
      {0, 1, 0.4}, {0, 2, 0.1}, {1, 0, 0.2}, {1, 2, 0.1}, {2, 0, 0.2}};
  ASSERT_EQ(solution->flows.size(), expected.size());
  for (size_t idx = 0; idx < expected.size(); ++idx) {
    EXPECT_EQ(solution->flows[idx].from_bin, expected[idx].from_bin) << idx;
    EXPECT_EQ(solution->flows[idx].to_bin, expected[idx].to_bin) << idx;
    EXPECT_NEAR(solution->flows[idx].mass, expected[idx].mass, 1e-12) << idx;
  }
}

// Symmetric with a zero diagonal but not a metric (0 -> 2 costs 10 > 1 + 1): the optimum does not
// leave the shared mass of bin 1 in place, it shifts everything one bin to the right.
TEST(EarthMoversDistance, MovesSharedMassWhenTheGroundIsNotAMetric) {
  Eigen::MatrixXd ground(3, 3);
  ground << 0, 1, 10, 1, 0, 1, 10, 1, 0;
  EXPECT_NEAR(Emd({0.5, 0.5, 0}, {0, 0.5, 0.5}, ground), 1.0, 1e-12);
}

TEST(EarthMoversDistance, IdentityIsZero) {
  SplitMix64 random(12);
  for (int case_idx = 0; case_idx < 50; ++case_idx) {
    const size_t k = 1 + random.Below(100);
    const Eigen::MatrixXd ground = RandomMetricGround(k, &random);
    const Histogram p = RandomHistogram(k, 0.5, &random);
    EXPECT_NEAR(Emd(p, p, ground), 0.0, 1e-12);
    // Under kNormalize a histogram and any multiple of it are the same distribution.
    Histogram scaled = p;
    for (double& mass : scaled) mass *= 7.5;
    EXPECT_NEAR(Emd(p, scaled, ground), 0.0, 1e-12);
  }
}

TEST(EarthMoversDistance, IsSymmetric) {
  SplitMix64 random(13);
  for (int case_idx = 0; case_idx < 100; ++case_idx) {
    const size_t k = 1 + random.Below(60);
    const Eigen::MatrixXd ground = RandomMetricGround(k, &random);
    const Histogram p = RandomHistogram(k, 0.4, &random);
    const Histogram q = RandomHistogram(k, 0.4, &random);
    EXPECT_NEAR(Emd(p, q, ground), Emd(q, p, ground), 1e-12) << "case " << case_idx;
  }
}

TEST(EarthMoversDistance, SatisfiesTheTriangleInequalityOverAMetricGround) {
  SplitMix64 random(14);
  for (int case_idx = 0; case_idx < 200; ++case_idx) {
    const size_t k = 2 + random.Below(40);
    const Eigen::MatrixXd ground = RandomMetricGround(k, &random);
    const Histogram p = RandomHistogram(k, 0.4, &random);
    const Histogram q = RandomHistogram(k, 0.4, &random);
    const Histogram r = RandomHistogram(k, 0.4, &random);
    const double pq = Emd(p, q, ground);
    const double qr = Emd(q, r, ground);
    const double pr = Emd(p, r, ground);
    EXPECT_LE(pr, pq + qr + 1e-12) << "case " << case_idx;
    EXPECT_GE(pq, 0.0);
  }
}

// Which motif each bin is matters. q1 and q2 hold the same VALUES as p (one bin of 1, three of
// 0), at different motifs: moving p's mass to motif 1 costs 1, to motif 3 costs 3. A distance
// over the bin values alone (ValueWasserstein, the tempting mistake above) gives 0 for
// both, so it fails every expectation below.
TEST(EarthMoversDistance, PermutingBinsChangesTheDistance) {
  const Eigen::MatrixXd ground = LineGround(UnitSpacing(4));
  const Histogram p = {1, 0, 0, 0};
  const Histogram q1 = {0, 1, 0, 0};
  const Histogram q2 = {0, 0, 0, 1};
  EXPECT_EQ(ValueWasserstein(p, q1), 0.0);  // the wrong distance cannot tell them apart
  EXPECT_EQ(ValueWasserstein(p, q2), 0.0);
  EXPECT_NEAR(Emd(p, q1, ground), 1.0, 1e-12);
  EXPECT_NEAR(Emd(p, q2, ground), 3.0, 1e-12);

  // The same with random histograms: permuting the bins of q changes the EMD, and the distance
  // to a permutation of itself is not 0.
  SplitMix64 random(15);
  const size_t k = 30;
  const Eigen::MatrixXd random_ground = RandomMetricGround(k, &random);
  const Histogram a = RandomHistogram(k, 0.0, &random);
  Histogram reversed(a.rbegin(), a.rend());
  EXPECT_EQ(ValueWasserstein(a, reversed), 0.0);
  EXPECT_GT(Emd(a, reversed, random_ground), 1e-3);
}

TEST(EarthMoversDistance, PartialMassFollowsRubner) {
  const Eigen::MatrixXd ground = LineGround(UnitSpacing(3));
  // |p| = 1 < |q| = 2: all of p moves, to q's nearest mass; cost / 1.
  EXPECT_NEAR(Emd({1, 0, 0}, {1, 0, 1}, ground, EmdMass::kPartial), 0.0, 1e-12);
  EXPECT_NEAR(Emd({0, 1, 0}, {0, 0, 2}, ground, EmdMass::kPartial), 1.0, 1e-12);
  // Normalised instead: (1, 0, 0) against (.5, 0, .5) moves half a unit two steps.
  EXPECT_NEAR(Emd({1, 0, 0}, {1, 0, 1}, ground, EmdMass::kNormalize), 1.0, 1e-12);
  // Equal totals: the two definitions agree.
  const Histogram p = {0.2, 0.5, 0.3};
  const Histogram q = {0.6, 0.1, 0.3};
  EXPECT_NEAR(Emd(p, q, ground, EmdMass::kPartial), Emd(p, q, ground, EmdMass::kNormalize), 1e-12);
  // The smaller side (p, total 1) moves entirely onto q's mass in its own bin; q's extra .5 stays.
  EXPECT_NEAR(Emd({0.0, 0.0, 1.0}, {0.5, 0.0, 1.0}, ground, EmdMass::kPartial), 0.0, 1e-12);
}

TEST(EarthMoversDistance, OnlyBinsWithMassEnterTheProblem) {
  const Histogram p = {0, 0.5, 0, 0.5, 0};
  const Histogram q = {0, 0, 1, 0, 0};
  Eigen::MatrixXd ground = LineGround(UnitSpacing(5));
  ground(0, 0) = std::numeric_limits<double>::quiet_NaN();  // never read
  ground(4, 1) = std::numeric_limits<double>::quiet_NaN();
  EarthMoversDistance emd;
  Result<EmdSolution> solution = emd.Solve(p, q, ground);
  ASSERT_TRUE(solution.ok()) << solution.status().ToString();
  EXPECT_EQ(solution->source_bins, 2u);
  EXPECT_EQ(solution->sink_bins, 1u);
  EXPECT_NEAR(solution->distance, 1.0, 1e-12);
}

TEST(EarthMoversDistance, ReportsInvalidInput) {
  const Eigen::MatrixXd ground = LineGround(UnitSpacing(3));
  EarthMoversDistance emd;
  EXPECT_TRUE(emd.Distance({{1.0, 0.0}}, {{1.0, 0.0, 0.0}}, ground).status().IsInvalidArgument());
  EXPECT_TRUE(
      emd.Distance({{0.0, 0.0, 0.0}}, {{1.0, 0.0, 0.0}}, ground).status().IsInvalidArgument());
  EXPECT_TRUE(
      emd.Distance({{-1.0, 2.0, 0.0}}, {{1.0, 0.0, 0.0}}, ground).status().IsInvalidArgument());
  // The object stays usable after an error.
  Result<double> distance = emd.Distance({{1.0, 0.0, 0.0}}, {{0.0, 0.0, 1.0}}, ground);
  ASSERT_TRUE(distance.ok());
  EXPECT_NEAR(*distance, 2.0, 1e-12);
}

}  // namespace
}  // namespace motif
