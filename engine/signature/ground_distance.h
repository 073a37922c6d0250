// The ground distance of the Earth Mover's Distance between motion signatures: the Euclidean
// distance between motif centroids in the embedding (Aristidou et al. 2018: words are assigned
// to the nearest motif by L2, and the EMD's ground distance is the distance between clusters).
// Computed in double from float centroids, so it is symmetric with an exactly zero diagonal and
// satisfies the triangle inequality to rounding: the EMD over it is then a metric.
// Thread-safety: a pure function.
#pragma once

#include <Eigen/Core>

#include "engine/signature/k_means.h"

namespace motif {

// k x k: entry (a, b) = || centroid_a - centroid_b ||_2, for the k rows of `centroids`.
Eigen::MatrixXd CentroidGroundDistance(const Eigen::Ref<const RowMatrixXf>& centroids);

}  // namespace motif
