// k-means over float vectors: Lloyd's iterations (Lloyd 1982) from k-means++ seeding (Arthur &
// Vassilvitskii, "k-means++: the advantages of careful seeding", SODA 2007). Motion motifs are
// the k-means centroids of the embedded motion words (Aristidou et al. 2018, k = 100).
//
// Conventions: n points of d dimensions are the rows of a row-major float matrix; distances are
// squared Euclidean, computed in float; sums, means and the inertia in double. A point belongs to
// its nearest centroid, ties to the lowest centroid index (NearestCentroid, also the rule for
// assigning new words to motifs later).
//
// Determinism. The result depends only on the points and the options, never on the thread count:
//  * the random numbers come from SplitMix64 seeded with options.seed (no std::random_device, no
//    <random> distributions, whose output differs between standard libraries);
//  * the points are cut into fixed chunks of chunk_rows rows (a function of n alone); each chunk
//    computes its own partial sums (per-centroid sums and counts, inertia, the D^2 mass of
//    seeding) and the partials are merged serially in chunk order, so every floating-point sum is
//    added in the same order whatever the number of threads;
//  * empty clusters are re-seeded with the points farthest from their centroids (ties: the lower
//    point index), in cluster order.
// Stopping: after an assignment pass, stop when no assignment changed, or when the inertia fell
// by at most `tolerance` times its previous value, or after max_iterations passes. The returned
// centroids, assignments and inertia always agree (a last assignment pass follows the last update
// when the iteration limit stops the loop).
// Thread-safety: pure function; it runs its parallel loops in its own tbb::task_arena.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"

namespace motif {

using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct KMeansOptions {
  uint32_t k = 100;
  uint64_t seed = 1;
  uint32_t max_iterations = 100;  // assignment passes, >= 1
  double tolerance = 1e-6;        // relative inertia decrease below which the loop stops
  int threads = 0;                // 0: all cores
  uint32_t chunk_rows = 0;        // rows per chunk; 0: max(1024, ceil(n / 256))
};

struct KMeansResult {
  RowMatrixXf centroids;                // k x d
  std::vector<uint32_t> assignments;    // n: the nearest centroid of each point
  std::vector<uint64_t> cluster_sizes;  // k: points per centroid (0 only if the limit stopped it)
  double inertia = 0;                   // sum of squared distances to the assigned centroids
  uint32_t iterations = 0;              // assignment passes of the Lloyd loop
  bool converged = false;               // stopped by the change or tolerance rule
  uint32_t reseeded = 0;                // empty clusters re-seeded, over all iterations
};

// Clusters the rows of `points` into options.k clusters.
// InvalidArgument: k = 0, no points or no dimensions, a NaN or infinite coordinate,
// max_iterations = 0, a negative or NaN tolerance, or fewer than k distinct points (k-means++
// runs out of points that are not already centroids).
Result<KMeansResult> RunKMeans(const Eigen::Ref<const RowMatrixXf>& points,
                               const KMeansOptions& options);

// The index of the row of `centroids` nearest to `point` (d = centroids.cols() floats; ties: the
// lowest index), and its squared distance in `squared_distance` if not null.
uint32_t NearestCentroid(const Eigen::Ref<const RowMatrixXf>& centroids, const float* point,
                         float* squared_distance = nullptr);

}  // namespace motif
