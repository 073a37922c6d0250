#include "engine/signature/ground_distance.h"

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(CentroidGroundDistance, IsTheEuclideanDistanceBetweenCentroids) {
  RowMatrixXf centroids(3, 2);
  centroids << 0, 0, 3, 4, 6, 8;
  const Eigen::MatrixXd ground = CentroidGroundDistance(centroids);
  ASSERT_EQ(ground.rows(), 3);
  ASSERT_EQ(ground.cols(), 3);
  const Eigen::MatrixXd expected =
      (Eigen::MatrixXd(3, 3) << 0, 5, 10, 5, 0, 5, 10, 5, 0).finished();
  EXPECT_TRUE(ground.isApprox(expected, 1e-12)) << ground;
  EXPECT_EQ(ground(1, 1), 0.0);
  EXPECT_EQ(ground(0, 2), ground(2, 0));
}

}  // namespace
}  // namespace motif
