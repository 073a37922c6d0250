// Whole-take analysis: classical MDS, leave-one-out kNN and precision@k, the signature distance
// matrix and DTW between takes, on cases with known answers.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/split_mix64.h"
#include "engine/signature/classical_mds.h"
#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/k_means.h"
#include "engine/signature/signature_matrix.h"
#include "engine/signature/take_dtw.h"
#include "engine/signature/take_retrieval.h"
#include "tests/engine/signature/word_test_util.h"

namespace motif {
namespace {

Eigen::MatrixXd EuclideanDistances(const Eigen::MatrixXd& points) {
  const Eigen::Index n = points.rows();
  Eigen::MatrixXd d(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = 0; b < n; ++b) d(a, b) = (points.row(a) - points.row(b)).norm();
  }
  return d;
}

TEST(ClassicalMds, ReproducesEuclideanDistancesOfPointsInTheGivenDimensions) {
  SplitMix64 random(3);
  Eigen::MatrixXd points(30, 3);
  for (Eigen::Index idx = 0; idx < points.size(); ++idx) points.data()[idx] = random.Gaussian();
  const Eigen::MatrixXd d = EuclideanDistances(points);
  auto mds = ClassicalMds(d, 3);
  ASSERT_TRUE(mds.ok()) << mds.status().ToString();
  EXPECT_LT((EuclideanDistances(mds->coordinates) - d).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GE(mds->eigenvalues[0], mds->eigenvalues[1]);
  EXPECT_GE(mds->eigenvalues[1], mds->eigenvalues[2]);
  // In 2 dimensions: the best 2-D fit; the points' third coordinate is lost.
  auto flat = ClassicalMds(d, 2);
  ASSERT_TRUE(flat.ok());
  EXPECT_EQ(flat->coordinates.cols(), 2);
}

TEST(ClassicalMds, FourCornersOfASquare) {
  Eigen::MatrixXd square(4, 2);
  square << 0, 0, 1, 0, 1, 1, 0, 1;
  auto mds = ClassicalMds(EuclideanDistances(square), 2);
  ASSERT_TRUE(mds.ok());
  // B's non-zero eigenvalues are both n s^2 / 4 = 1 for the unit square.
  EXPECT_NEAR(mds->eigenvalues[0], 1.0, 1e-12);
  EXPECT_NEAR(mds->eigenvalues[1], 1.0, 1e-12);
  EXPECT_LT(
      (EuclideanDistances(mds->coordinates) - EuclideanDistances(square)).cwiseAbs().maxCoeff(),
      1e-12);
}

TEST(ClassicalMds, RefusesBadMatrices) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_TRUE(ClassicalMds(d, 3).status().IsInvalidArgument());  // dims >= n
  EXPECT_TRUE(ClassicalMds(d, 0).status().IsInvalidArgument());
  d(0, 1) = 1;  // not symmetric
  EXPECT_TRUE(ClassicalMds(d, 1).status().IsInvalidArgument());
  d(1, 0) = 1;
  d(2, 2) = 0.5;  // diagonal
  EXPECT_TRUE(ClassicalMds(d, 1).status().IsInvalidArgument());
  EXPECT_TRUE(ClassicalMds(Eigen::MatrixXd::Zero(2, 3), 1).status().IsInvalidArgument());
}

// Points on a line at 0, 1, 2, 10, 11, 20: distances |a - b|.
Eigen::MatrixXd LineDistances() {
  const double x[6] = {0, 1, 2, 10, 11, 20};
  Eigen::MatrixXd d(6, 6);
  for (int a = 0; a < 6; ++a) {
    for (int b = 0; b < 6; ++b) d(a, b) = std::abs(x[a] - x[b]);
  }
  return d;
}

TEST(TakeRetrieval, NearestItemsBreakTiesByIndexAndSkipUnlabelled) {
  const Eigen::MatrixXd d = LineDistances();
  const std::vector<uint32_t> labels = {0, 0, kUnlabelled, 1, 1, 1};
  EXPECT_EQ(NearestItems(d, labels, 1, 3, false), (std::vector<uint32_t>{0, 2, 3}));
  EXPECT_EQ(NearestItems(d, labels, 1, 3, true), (std::vector<uint32_t>{0, 3, 4}));
  EXPECT_EQ(NearestItems(d, labels, 0, 10, true).size(), 4u);
}

TEST(TakeRetrieval, LeaveOneOutKnnAndPrecisionByHand) {
  const Eigen::MatrixXd d = LineDistances();
  const std::vector<uint32_t> labels = {0, 0, 0, 1, 1, 1};
  // 1-NN: 0->1, 1->0 (tie 0,2 at 1: lower index), 2->1, 3->4, 4->3, 5->4: all right.
  KnnEvaluation one = LeaveOneOutKnn(d, labels, 2, 1);
  EXPECT_EQ(one.labelled, 6u);
  EXPECT_EQ(one.correct, 6u);
  EXPECT_DOUBLE_EQ(one.accuracy, 1.0);
  // 3-NN, ties of distance to the lower index: item 3 (at 10) sees 4, 2, 1 (labels 1, 0, 0) and
  // is wrong; item 4 (at 11) sees 3, 2 and 5 (2 and 5 both at 9) and is right: 5 of 6.
  KnnEvaluation three = LeaveOneOutKnn(d, labels, 2, 3);
  EXPECT_EQ(three.correct, 5u);
  EXPECT_EQ(three.predicted[3], 0u);
  EXPECT_EQ(three.confusion[1][0], 1u);
  // With 5 neighbours every item sees 2 of its own and 3 of the others: all wrong.
  KnnEvaluation five = LeaveOneOutKnn(d, labels, 2, 5);
  EXPECT_EQ(five.correct, 0u);
  EXPECT_EQ(five.confusion[0][1], 3u);
  // precision@2: items 3 (4, 2) and 4 (3, 2) score 1/2, the others 1: 5/6. precision@3: item 3
  // scores 1/3, the others 2/3: 11/18.
  EXPECT_NEAR(PrecisionAtK(d, labels, 2), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(PrecisionAtK(d, labels, 3), 11.0 / 18.0, 1e-12);
  // A tie of votes goes to the label met first: item 3's 2 nearest are 4 (label 0) and 2 (1).
  const std::vector<uint32_t> mixed = {0, 0, 1, 1, 0, 1};
  KnnEvaluation two = LeaveOneOutKnn(d, mixed, 2, 2);
  EXPECT_EQ(two.predicted[3], 0u);
}

TEST(SignatureDistanceMatrix, IsTheEmdOfEveryPairForAnyThreadCount) {
  SplitMix64 random(5);
  const uint32_t k = 6;
  RowMatrixXf centroids(k, 3);
  for (Eigen::Index idx = 0; idx < centroids.size(); ++idx) {
    centroids.data()[idx] = static_cast<float>(random.Gaussian());
  }
  Eigen::MatrixXd ground(k, k);
  for (uint32_t a = 0; a < k; ++a) {
    for (uint32_t b = 0; b < k; ++b) {
      ground(a, b) = (centroids.row(a) - centroids.row(b)).cast<double>().norm();
    }
  }
  std::vector<std::vector<double>> signatures(7, std::vector<double>(k, 0.0));
  for (auto& signature : signatures) {
    for (double& value : signature) value = random.Uniform() < 0.5 ? random.Uniform() : 0.0;
    signature[random.Below(k)] += 0.5;
  }
  auto one = SignatureDistanceMatrix(signatures, ground, 1);
  auto two = SignatureDistanceMatrix(signatures, ground, 2);
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_EQ(*one, *two);
  EarthMoversDistance emd;
  for (size_t a = 0; a < signatures.size(); ++a) {
    EXPECT_EQ((*one)(a, a), 0.0);
    for (size_t b = 0; b < signatures.size(); ++b) {
      if (a == b) continue;
      EXPECT_EQ((*one)(a, b),
                *emd.Distance(signatures[std::min(a, b)], signatures[std::max(a, b)], ground));
    }
  }
  signatures[3].assign(k, 0.0);  // no mass
  EXPECT_TRUE(SignatureDistanceMatrix(signatures, ground, 1).status().IsInvalidArgument());
}

TEST(TakeDtw, HandCaseAndWarpedCopies) {
  // Frames of one joint (weight 1) at known rotations about X: D between angles a and b is
  // |q(a) - q(b)| = 2 sin(|a - b| / 4).
  auto frame = [](double angle) {
    const int16_t w =
        static_cast<int16_t>(std::lround(std::cos(angle / 2) * PoseFeatures::kQuantScale));
    const int16_t x =
        static_cast<int16_t>(std::lround(std::sin(angle / 2) * PoseFeatures::kQuantScale));
    return std::vector<float>{static_cast<float>(w) / PoseFeatures::kQuantScale,
                              static_cast<float>(x) / PoseFeatures::kQuantScale, 0.0f, 0.0f};
  };
  // Take A: 0, 0.1, 0.2, 0.3; take B: 0, 0.1, 0.1, 0.2, 0.3 (A with one frame held): DTW 0.
  // Take C: 0.4 throughout (3 frames).
  const std::vector<double> angles = {0, 0.1, 0.2, 0.3, 0, 0.1, 0.1, 0.2, 0.3, 0.4, 0.4, 0.4};
  std::vector<float> rows;
  for (double angle : angles) {
    for (float value : frame(angle)) rows.push_back(value);
    for (int extra = 0; extra < 4; ++extra) rows.push_back(0.0f);  // height, velocity, heading
  }
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), angles.size(), 1, {1.0f}, {0, 4, 9});
  const TakeFrames a{0, 4};
  const TakeFrames b{4, 9};
  const TakeFrames c{9, 12};
  EXPECT_NEAR(TakeDtw(features, a, b, 1), 0.0, 1e-6);
  // A against C: every frame of A aligns with some 0.4 frame; the cheapest path has 4 cells
  // (A's frames 0..3 each once, C's three frames along them) of D(angle, 0.4).
  double expected = 0;
  for (double angle : {0.0, 0.1, 0.2, 0.3}) expected += 2 * std::sin((0.4 - angle) / 4);
  EXPECT_NEAR(TakeDtw(features, a, c, 1), expected / 7.0, 2e-4);
  auto matrix = TakeDtwMatrix(features, {a, b, c}, 1, 2);
  ASSERT_TRUE(matrix.ok());
  EXPECT_EQ((*matrix)(0, 2), (*matrix)(2, 0));
  EXPECT_EQ((*matrix)(1, 1), 0.0);
  EXPECT_DOUBLE_EQ((*matrix)(0, 2), TakeDtw(features, a, c, 1));
  EXPECT_TRUE(TakeDtwMatrix(features, {a, TakeFrames{3, 3}}, 1, 1).status().IsInvalidArgument());
  EXPECT_TRUE(TakeDtwMatrix(features, {a}, 0, 1).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
