#include "engine/signature/ground_distance.h"

#include <cmath>

namespace motif {

Eigen::MatrixXd CentroidGroundDistance(const Eigen::Ref<const RowMatrixXf>& centroids) {
  const Eigen::Index k = centroids.rows();
  const Eigen::MatrixXd points = centroids.cast<double>();
  Eigen::MatrixXd ground = Eigen::MatrixXd::Zero(k, k);
  for (Eigen::Index a = 0; a < k; ++a) {
    for (Eigen::Index b = a + 1; b < k; ++b) {
      const double distance = (points.row(a) - points.row(b)).norm();
      ground(a, b) = distance;
      ground(b, a) = distance;
    }
  }
  return ground;
}

}  // namespace motif
