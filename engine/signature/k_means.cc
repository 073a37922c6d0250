#include "engine/signature/k_means.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/split_mix64.h"

namespace motif {
namespace {

using RowVectorMap = Eigen::Map<const Eigen::RowVectorXf>;

// The fixed partition of the points: a function of n (and the option) only, never of the thread
// count, so the partial sums below are the same for any number of threads. At most ~256 chunks
// by default, which bounds the memory of the per-chunk centroid sums.
struct ChunkPlan {
  size_t rows = 0;
  size_t count = 0;
  size_t Begin(size_t chunk_idx) const { return chunk_idx * rows; }
  size_t End(size_t chunk_idx, size_t n) const { return std::min(n, (chunk_idx + 1) * rows); }
};

ChunkPlan MakeChunkPlan(size_t n, uint32_t chunk_rows) {
  ChunkPlan plan;
  plan.rows = chunk_rows > 0 ? chunk_rows : std::max<size_t>(1024, (n + 255) / 256);
  plan.count = (n + plan.rows - 1) / plan.rows;
  return plan;
}

inline float SquaredDistance(const float* a, const float* b, Eigen::Index d) {
  return (RowVectorMap(a, d) - RowVectorMap(b, d)).squaredNorm();
}

// The nearest row (ties: the lowest index): shared by the Lloyd loop and NearestCentroid, so a
// word is later assigned to a motif by exactly the rule that built the motifs.
template <typename Matrix>
inline uint32_t NearestRow(const Matrix& centroids, const float* point, float* distance) {
  const Eigen::Index d = centroids.cols();
  uint32_t best = 0;
  float best_distance = SquaredDistance(centroids.row(0).data(), point, d);
  for (Eigen::Index centroid = 1; centroid < centroids.rows(); ++centroid) {
    const float candidate = SquaredDistance(centroids.row(centroid).data(), point, d);
    if (candidate < best_distance) {
      best_distance = candidate;
      best = static_cast<uint32_t>(centroid);
    }
  }
  *distance = best_distance;
  return best;
}

class KMeansRun {
 public:
  KMeansRun(const Eigen::Ref<const RowMatrixXf>& points, const KMeansOptions& options)
      : points_(points),
        options_(options),
        n_(static_cast<size_t>(points.rows())),
        d_(points.cols()),
        k_(options.k),
        plan_(MakeChunkPlan(n_, options.chunk_rows)),
        arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {}

  Result<KMeansResult> Run();

 private:
  const float* Point(size_t point_idx) const { return points_.row(point_idx).data(); }

  // Runs body(chunk_idx) for every chunk, in parallel; each call writes only its own slots.
  template <typename Body>
  void ForEachChunk(const Body& body) {
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, plan_.count, /*grainsize=*/1),
                        [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t chunk_idx = range.begin(); chunk_idx != range.end();
                               ++chunk_idx) {
                            body(chunk_idx);
                          }
                        });
    });
  }

  Status Seed(RowMatrixXf* centroids);
  // One assignment pass against `centroids`: assignments_, point_cost_ and the merged sums,
  // counts and inertia. Returns how many assignments changed.
  uint64_t Assign(const RowMatrixXf& centroids);
  // Means of the last pass's clusters; empty clusters re-seeded. Returns how many were empty.
  uint32_t Update(RowMatrixXf* centroids);

  const Eigen::Ref<const RowMatrixXf>& points_;
  const KMeansOptions& options_;
  const size_t n_;
  const Eigen::Index d_;
  const uint32_t k_;
  const ChunkPlan plan_;
  tbb::task_arena arena_;

  std::vector<uint32_t> assignments_;
  std::vector<float> point_cost_;        // squared distance to the assigned centroid
  std::vector<double> chunk_sums_;       // chunk x k x d
  std::vector<uint64_t> chunk_counts_;   // chunk x k
  std::vector<double> chunk_inertia_;    // chunk
  std::vector<uint64_t> chunk_changed_;  // chunk
  Eigen::MatrixXd sums_;                 // k x d (column-major is fine: filled serially)
  std::vector<uint64_t> counts_;
  double inertia_ = 0;
};

Status KMeansRun::Seed(RowMatrixXf* centroids) {
  SplitMix64 random(options_.seed);
  centroids->resize(k_, d_);
  const size_t first = static_cast<size_t>(random.Below(n_));
  centroids->row(0) = points_.row(first);

  // D^2 sampling: each next centroid is a point drawn with probability proportional to its
  // squared distance to the nearest centroid so far. The draw walks the chunk masses, then the
  // points of the chosen chunk, both in index order.
  std::vector<double> nearest(n_, std::numeric_limits<double>::infinity());
  std::vector<double> chunk_mass(plan_.count, 0.0);
  for (uint32_t centroid = 1; centroid < k_; ++centroid) {
    const float* newest = centroids->row(centroid - 1).data();
    ForEachChunk([&](size_t chunk_idx) {
      double mass = 0;
      for (size_t point_idx = plan_.Begin(chunk_idx); point_idx < plan_.End(chunk_idx, n_);
           ++point_idx) {
        const double distance = SquaredDistance(Point(point_idx), newest, d_);
        nearest[point_idx] = std::min(nearest[point_idx], distance);
        mass += nearest[point_idx];
      }
      chunk_mass[chunk_idx] = mass;
    });
    double total = 0;
    for (double mass : chunk_mass) total += mass;
    if (!(total > 0)) {
      return Status::InvalidArgument("k-means: k = " + std::to_string(k_) +
                                     " but the points have only " + std::to_string(centroid) +
                                     " distinct values");
    }
    const double target = random.Uniform() * total;
    size_t chosen = n_;
    size_t last_positive = n_;
    double cumulative = 0;
    for (size_t chunk_idx = 0; chunk_idx < plan_.count && chosen == n_; ++chunk_idx) {
      if (chunk_mass[chunk_idx] > 0) {
        if (cumulative + chunk_mass[chunk_idx] <= target) {
          cumulative += chunk_mass[chunk_idx];
          // Remember a point with mass in case rounding carries the target past the end.
          for (size_t point_idx = plan_.End(chunk_idx, n_); point_idx-- > plan_.Begin(chunk_idx);) {
            if (nearest[point_idx] > 0) {
              last_positive = point_idx;
              break;
            }
          }
          continue;
        }
        for (size_t point_idx = plan_.Begin(chunk_idx); point_idx < plan_.End(chunk_idx, n_);
             ++point_idx) {
          if (nearest[point_idx] <= 0) continue;
          last_positive = point_idx;
          cumulative += nearest[point_idx];
          if (cumulative > target) {
            chosen = point_idx;
            break;
          }
        }
      }
    }
    if (chosen == n_) chosen = last_positive;
    MOTIF_CHECK(chosen < n_);
    centroids->row(centroid) = points_.row(chosen);
  }
  return Status::Ok();
}

uint64_t KMeansRun::Assign(const RowMatrixXf& centroids) {
  const size_t stride = static_cast<size_t>(k_) * static_cast<size_t>(d_);
  ForEachChunk([&](size_t chunk_idx) {
    double* sums = &chunk_sums_[chunk_idx * stride];
    uint64_t* counts = &chunk_counts_[chunk_idx * k_];
    std::fill(sums, sums + stride, 0.0);
    std::fill(counts, counts + k_, 0);
    double inertia = 0;
    uint64_t changed = 0;
    for (size_t point_idx = plan_.Begin(chunk_idx); point_idx < plan_.End(chunk_idx, n_);
         ++point_idx) {
      const float* point = Point(point_idx);
      float distance = 0;
      const uint32_t centroid = NearestRow(centroids, point, &distance);
      changed += assignments_[point_idx] != centroid;
      assignments_[point_idx] = centroid;
      point_cost_[point_idx] = distance;
      inertia += distance;
      ++counts[centroid];
      double* sum = sums + static_cast<size_t>(centroid) * d_;
      for (Eigen::Index dim = 0; dim < d_; ++dim) sum[dim] += point[dim];
    }
    chunk_inertia_[chunk_idx] = inertia;
    chunk_changed_[chunk_idx] = changed;
  });

  // Merged serially in chunk order: the same additions in the same order for any thread count.
  sums_.setZero(k_, d_);
  counts_.assign(k_, 0);
  inertia_ = 0;
  uint64_t changed = 0;
  for (size_t chunk_idx = 0; chunk_idx < plan_.count; ++chunk_idx) {
    const double* sums = &chunk_sums_[chunk_idx * stride];
    for (uint32_t centroid = 0; centroid < k_; ++centroid) {
      counts_[centroid] += chunk_counts_[chunk_idx * k_ + centroid];
      for (Eigen::Index dim = 0; dim < d_; ++dim) {
        sums_(centroid, dim) += sums[static_cast<size_t>(centroid) * d_ + dim];
      }
    }
    inertia_ += chunk_inertia_[chunk_idx];
    changed += chunk_changed_[chunk_idx];
  }
  return changed;
}

uint32_t KMeansRun::Update(RowMatrixXf* centroids) {
  std::vector<uint32_t> empty;
  for (uint32_t centroid = 0; centroid < k_; ++centroid) {
    if (counts_[centroid] == 0) {
      empty.push_back(centroid);
      continue;
    }
    const double count = static_cast<double>(counts_[centroid]);
    for (Eigen::Index dim = 0; dim < d_; ++dim) {
      (*centroids)(centroid, dim) = static_cast<float>(sums_(centroid, dim) / count);
    }
  }
  if (empty.empty()) return 0;
  // The points worst served by the current centroids, farthest first (ties: lower index).
  std::vector<uint32_t> order(n_);
  for (size_t point_idx = 0; point_idx < n_; ++point_idx) {
    order[point_idx] = static_cast<uint32_t>(point_idx);
  }
  const size_t take = std::min(empty.size(), n_);
  std::partial_sort(order.begin(), order.begin() + take, order.end(), [&](uint32_t a, uint32_t b) {
    return point_cost_[a] != point_cost_[b] ? point_cost_[a] > point_cost_[b] : a < b;
  });
  for (size_t empty_idx = 0; empty_idx < take; ++empty_idx) {
    centroids->row(empty[empty_idx]) = points_.row(order[empty_idx]);
  }
  return static_cast<uint32_t>(empty.size());
}

Result<KMeansResult> KMeansRun::Run() {
  KMeansResult result;
  MOTIF_RETURN_IF_ERROR(Seed(&result.centroids));

  assignments_.assign(n_, std::numeric_limits<uint32_t>::max());
  point_cost_.assign(n_, 0.0f);
  chunk_sums_.assign(plan_.count * k_ * static_cast<size_t>(d_), 0.0);
  chunk_counts_.assign(plan_.count * k_, 0);
  chunk_inertia_.assign(plan_.count, 0.0);
  chunk_changed_.assign(plan_.count, 0);

  double previous_inertia = std::numeric_limits<double>::infinity();
  bool consistent = false;
  for (uint32_t iteration = 1; iteration <= options_.max_iterations; ++iteration) {
    const uint64_t changed = Assign(result.centroids);
    result.iterations = iteration;
    consistent = true;
    if (iteration > 1 && changed == 0) {
      result.converged = true;
      break;
    }
    if (std::isfinite(previous_inertia) &&
        previous_inertia - inertia_ <= options_.tolerance * previous_inertia) {
      result.converged = true;
      break;
    }
    if (iteration == options_.max_iterations) break;
    result.reseeded += Update(&result.centroids);
    consistent = false;
    previous_inertia = inertia_;
  }
  if (!consistent) Assign(result.centroids);

  result.assignments = assignments_;
  result.cluster_sizes = counts_;
  result.inertia = inertia_;
  return result;
}

}  // namespace

uint32_t NearestCentroid(const Eigen::Ref<const RowMatrixXf>& centroids, const float* point,
                         float* squared_distance) {
  MOTIF_CHECK(centroids.rows() > 0);
  float distance = 0;
  const uint32_t nearest = NearestRow(centroids, point, &distance);
  if (squared_distance != nullptr) *squared_distance = distance;
  return nearest;
}

Result<KMeansResult> RunKMeans(const Eigen::Ref<const RowMatrixXf>& points,
                               const KMeansOptions& options) {
  if (options.k == 0) return Status::InvalidArgument("k-means: k must be at least 1");
  if (points.rows() == 0 || points.cols() == 0) {
    return Status::InvalidArgument("k-means: no points, or points with no dimensions");
  }
  if (options.max_iterations == 0) {
    return Status::InvalidArgument("k-means: max_iterations must be at least 1");
  }
  if (!(options.tolerance >= 0)) {
    return Status::InvalidArgument("k-means: the tolerance must be >= 0");
  }
  if (static_cast<uint64_t>(options.k) > static_cast<uint64_t>(points.rows())) {
    return Status::InvalidArgument("k-means: k = " + std::to_string(options.k) + " exceeds the " +
                                   std::to_string(points.rows()) + " points");
  }
  for (Eigen::Index point_idx = 0; point_idx < points.rows(); ++point_idx) {
    if (!points.row(point_idx).allFinite()) {
      return Status::InvalidArgument("k-means: point " + std::to_string(point_idx) +
                                     " has a NaN or infinite coordinate");
    }
  }
  KMeansRun run(points, options);
  return run.Run();
}

}  // namespace motif
