#include "engine/embedding/embedding_net.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/split_mix64.h"

namespace motif {
namespace {

using NetD = EmbeddingNetT<double>;

EmbeddingNetShape SmallShape() {
  EmbeddingNetShape shape;
  shape.frames = 9;
  shape.input_channels = 5;
  shape.conv1_channels = 6;
  shape.conv1_kernel = 3;
  shape.conv2_channels = 4;
  shape.conv2_kernel = 3;
  shape.conv2_stride = 2;
  shape.embedding_dims = 3;
  return shape;
}

NetD::Matrix RandomMatrix(Eigen::Index rows, Eigen::Index cols, uint64_t seed) {
  SplitMix64 random(seed);
  NetD::Matrix m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) m(r, c) = random.Gaussian();
  }
  return m;
}

// loss = sum over rows of weights . embedding: d loss / d embeddings = weights.
double Loss(const NetD& net, const NetD::Matrix& input, const NetD::Matrix& weights) {
  NetD::Workspace workspace;
  net.Forward(input, &workspace);
  return (workspace.embeddings.array() * weights.array()).sum();
}

// Central differences for the parameters `indices`, against the analytic gradient.
void CheckGradient(const EmbeddingNetShape& shape, const std::vector<size_t>& indices,
                   uint64_t seed) {
  NetD net(shape);
  net.Initialize(seed);
  std::vector<double> mean(shape.input_channels);
  std::vector<double> deviation(shape.input_channels);
  for (uint32_t c = 0; c < shape.input_channels; ++c) {
    mean[c] = 0.1 * c;
    deviation[c] = 0.5 + 0.25 * c;
  }
  net.SetInputStandardisation(mean, deviation);
  // Non-zero biases, so the check covers them in general position.
  SplitMix64 random(seed + 1);
  for (double& value : net.mutable_parameters()) value += 0.05 * random.Gaussian();
  const NetD::Matrix input = RandomMatrix(4, shape.input_size(), seed + 2);
  const NetD::Matrix weights = RandomMatrix(4, shape.embedding_dims, seed + 3);

  NetD::Workspace workspace;
  net.Forward(input, &workspace);
  std::vector<double> gradient(shape.parameter_count(), 0.0);
  net.Backward(weights, &workspace, gradient.data());

  const double step = 1e-6;
  double worst = 0;
  for (size_t idx : indices) {
    NetD plus = net;
    NetD minus = net;
    plus.mutable_parameters()[idx] += step;
    minus.mutable_parameters()[idx] -= step;
    const double numeric = (Loss(plus, input, weights) - Loss(minus, input, weights)) / (2 * step);
    const double error = std::abs(numeric - gradient[idx]) / std::max(1e-3, std::abs(numeric));
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-5) << "parameter " << idx << ": numeric " << numeric << ", analytic "
                           << gradient[idx];
  }
  ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(EmbeddingNet, DefaultShapeHas39328Parameters) {
  EmbeddingNetShape shape;
  shape.input_channels = 76;
  EXPECT_EQ(shape.conv1_frames(), 14u);
  EXPECT_EQ(shape.conv2_frames(), 6u);
  EXPECT_EQ(shape.parameter_count(), 39328u);
}

TEST(EmbeddingNet, GradientMatchesCentralDifferencesForEveryParameterOfASmallNet) {
  const EmbeddingNetShape shape = SmallShape();
  std::vector<size_t> all(shape.parameter_count());
  for (size_t idx = 0; idx < all.size(); ++idx) all[idx] = idx;
  CheckGradient(shape, all, 11);
}

TEST(EmbeddingNet, GradientMatchesCentralDifferencesAtTheDefaultShape) {
  EmbeddingNetShape shape;
  shape.input_channels = 76;
  // Every bias and a spread of weights of each block.
  std::vector<size_t> indices;
  const size_t blocks[][2] = {{shape.conv1_weight_offset(), shape.conv1_bias_offset()},
                              {shape.conv1_bias_offset(), shape.conv2_weight_offset()},
                              {shape.conv2_weight_offset(), shape.conv2_bias_offset()},
                              {shape.conv2_bias_offset(), shape.linear_weight_offset()},
                              {shape.linear_weight_offset(), shape.linear_bias_offset()},
                              {shape.linear_bias_offset(), shape.parameter_count()}};
  for (const auto& block : blocks) {
    const size_t stride = std::max<size_t>(1, (block[1] - block[0]) / 40);
    for (size_t idx = block[0]; idx < block[1]; idx += stride) indices.push_back(idx);
  }
  CheckGradient(shape, indices, 5);
}

TEST(EmbeddingNet, EmbeddingsAreUnitAndIndependentOfTheBatch) {
  EmbeddingNetShape shape = SmallShape();
  EmbeddingNet net(shape);
  net.Initialize(3);
  EmbeddingNet::Matrix input = RandomMatrix(5, shape.input_size(), 9).cast<float>();
  EmbeddingNet::Workspace all;
  net.Forward(input, &all);
  for (Eigen::Index row = 0; row < 5; ++row) {
    EXPECT_NEAR(all.embeddings.row(row).norm(), 1.0f, 1e-5f);
    EmbeddingNet::Workspace one;
    net.Forward(input.row(row), &one);
    EXPECT_LT((one.embeddings.row(0) - all.embeddings.row(row)).norm(), 1e-6f);
  }
}

TEST(EmbeddingNet, StandardisationIsAppliedPerChannel) {
  const EmbeddingNetShape shape = SmallShape();
  NetD plain(shape);
  plain.Initialize(4);
  NetD standardising = plain;
  std::vector<double> mean(shape.input_channels);
  std::vector<double> deviation(shape.input_channels);
  for (uint32_t c = 0; c < shape.input_channels; ++c) {
    mean[c] = 1.0 + c;
    deviation[c] = 2.0 + c;
  }
  standardising.SetInputStandardisation(mean, deviation);
  const NetD::Matrix input = RandomMatrix(3, shape.input_size(), 8);
  NetD::Matrix standardised = input;
  for (Eigen::Index col = 0; col < input.cols(); ++col) {
    const size_t c = static_cast<size_t>(col) % shape.input_channels;
    standardised.col(col) = (input.col(col).array() - mean[c]) / deviation[c];
  }
  NetD::Workspace a;
  NetD::Workspace b;
  plain.Forward(standardised, &a);
  standardising.Forward(input, &b);
  EXPECT_LT((a.embeddings - b.embeddings).norm(), 1e-12);
}

TEST(EmbeddingNet, RefusesShapesWithoutOutputFrames) {
  EmbeddingNetShape shape = SmallShape();
  shape.conv1_kernel = 10;
  EXPECT_TRUE(ValidateEmbeddingNetShape(shape).IsInvalidArgument());
  shape = SmallShape();
  shape.conv2_kernel = 8;
  EXPECT_TRUE(ValidateEmbeddingNetShape(shape).IsInvalidArgument());
  shape = SmallShape();
  shape.embedding_dims = 0;
  EXPECT_TRUE(ValidateEmbeddingNetShape(shape).IsInvalidArgument());
  EXPECT_TRUE(ValidateEmbeddingNetShape(SmallShape()).ok());
}

}  // namespace
}  // namespace motif
