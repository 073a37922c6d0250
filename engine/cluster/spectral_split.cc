#include "engine/cluster/spectral_split.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Spectra/SymEigsSolver.h>
#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/status.h"

namespace motif {

namespace {

// The Lanczos starting vector: SplitMix64, fixed by its definition on every platform.
class StartVectorRandom {
 public:
  explicit StartVectorRandom(uint64_t seed) : state_(seed) {}
  double Centred() {  // uniform in [-0.5, 0.5)
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53 - 0.5;
  }

 private:
  uint64_t state_;
};

// y = (N − 3·v1·v1ᵀ) x, N = D^(-1/2) W D^(-1/2), for Spectra's Lanczos. Each edge's
// w_ij·d_j^(-1/2) is taken once, not at every product (the same value: the product was formed
// in that order), and the rows of a large graph are summed in parallel, each row alone, so the
// result is the same on any thread count.
class DeflatedNormalizedAdjacency {
 public:
  using Scalar = double;

  DeflatedNormalizedAdjacency(const SimilarityGraph& graph, const std::vector<double>& inv_sqrt,
                              const Eigen::VectorXd& top)
      : graph_(graph), inv_sqrt_(inv_sqrt), top_(top) {
    const uint32_t n = graph.node_count();
    row_offsets_.reserve(n + 1);
    row_offsets_.push_back(0);
    for (uint32_t node = 0; node < n; ++node) {
      const auto targets = graph.Targets(node);
      const auto weights = graph.Weights(node);
      for (size_t edge = 0; edge < targets.size(); ++edge) {
        scaled_weights_.push_back(weights[edge] * inv_sqrt[targets[edge]]);
      }
      row_offsets_.push_back(scaled_weights_.size());
    }
  }
  Eigen::Index rows() const { return graph_.node_count(); }
  Eigen::Index cols() const { return graph_.node_count(); }

  void perform_op(const double* x_in, double* y_out) const {
    const uint32_t n = graph_.node_count();
    double top_dot = 0;
    for (uint32_t node = 0; node < n; ++node) top_dot += top_[node] * x_in[node];
    const auto rows = [&](uint32_t begin, uint32_t end) {
      for (uint32_t node = begin; node < end; ++node) {
        const uint32_t* targets = graph_.Targets(node).data();
        const double* scaled = scaled_weights_.data() + row_offsets_[node];
        const size_t edges = row_offsets_[node + 1] - row_offsets_[node];
        double sum = 0;
        for (size_t edge = 0; edge < edges; ++edge) sum += scaled[edge] * x_in[targets[edge]];
        y_out[node] = inv_sqrt_[node] * sum - 3.0 * top_[node] * top_dot;
      }
    };
    if (scaled_weights_.size() < kParallelEdges) {
      rows(0, n);
      return;
    }
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 256),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                        rows(range.begin(), range.end());
                      });
  }

 private:
  // Below this many edges a product takes a few microseconds: not worth the threads.
  static constexpr size_t kParallelEdges = size_t{1} << 15;

  const SimilarityGraph& graph_;
  const std::vector<double>& inv_sqrt_;
  const Eigen::VectorXd& top_;
  std::vector<uint64_t> row_offsets_;
  std::vector<double> scaled_weights_;
};

FiedlerVector DenseFiedler(const SimilarityGraph& graph, const std::vector<double>& inv_sqrt) {
  const uint32_t n = graph.node_count();
  Eigen::MatrixXd normalized = Eigen::MatrixXd::Zero(n, n);
  for (uint32_t node = 0; node < n; ++node) {
    const auto targets = graph.Targets(node);
    const auto weights = graph.Weights(node);
    for (size_t edge = 0; edge < targets.size(); ++edge) {
      normalized(node, targets[edge]) = weights[edge] * inv_sqrt[node] * inv_sqrt[targets[edge]];
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(normalized);
  FiedlerVector result;
  if (solver.info() != Eigen::Success) return result;
  // Eigenvalues ascending: the largest is 1 (the trivial vector), the second largest is ours.
  const Eigen::VectorXd v = solver.eigenvectors().col(n - 2);
  result.eigenvalue = 1.0 - solver.eigenvalues()(n - 2);
  result.values.resize(n);
  for (uint32_t node = 0; node < n; ++node) result.values[node] = v(node) * inv_sqrt[node];
  return result;
}

FiedlerVector SparseFiedler(const SimilarityGraph& graph, const std::vector<double>& inv_sqrt,
                            uint64_t seed) {
  const uint32_t n = graph.node_count();
  Eigen::VectorXd top(n);
  for (uint32_t node = 0; node < n; ++node) top(node) = 1.0 / inv_sqrt[node];
  top.normalize();
  DeflatedNormalizedAdjacency op(graph, inv_sqrt, top);
  Eigen::VectorXd start(n);
  StartVectorRandom random(seed);
  for (uint32_t node = 0; node < n; ++node) start(node) = random.Centred();
  FiedlerVector result;
  result.sparse = true;
  // The sweep only needs the order of the nodes along the vector, so a moderate tolerance is
  // enough. Graphs with a tiny spectral gap (many loosely joined groups) converge slowly with a
  // narrow basis: on a real 10^6-frame archive a 32-vector basis at 1e-6 spent up to 4,833
  // products and often gave up, where 64 vectors at 1e-4 took 479-1,213 and gave the same cuts
  // (docs/benchmarks.md, "motifmine mine end to end"). A wider, looser attempt is the fallback.
  for (const auto& [ncv, tolerance] : {std::pair<int, double>{64, 1e-4}, {128, 1e-3}}) {
    Spectra::SymEigsSolver<DeflatedNormalizedAdjacency> solver(op, 1,
                                                               std::min<Eigen::Index>(ncv, n));
    solver.init(start.data());
    solver.compute(Spectra::SortRule::LargestAlge, 300, tolerance);
    if (solver.info() != Spectra::CompInfo::Successful) continue;
    const Eigen::VectorXd v = solver.eigenvectors().col(0);
    result.eigenvalue = 1.0 - solver.eigenvalues()(0);
    result.values.resize(n);
    for (uint32_t node = 0; node < n; ++node) result.values[node] = v(node) * inv_sqrt[node];
    return result;
  }
  return result;
}

}  // namespace

FiedlerVector ComputeFiedlerVector(const SimilarityGraph& graph, const SpectralOptions& options) {
  const uint32_t n = graph.node_count();
  MOTIF_CHECK(n >= 2);
  std::vector<double> inv_sqrt(n);
  for (uint32_t node = 0; node < n; ++node) {
    MOTIF_CHECK(graph.Degree(node) > 0);
    inv_sqrt[node] = 1.0 / std::sqrt(graph.Degree(node));
  }
  // Lanczos needs a basis larger than the one vector wanted and smaller than the graph.
  if (n <= options.dense_max_nodes || n < 8) return DenseFiedler(graph, inv_sqrt);
  return SparseFiedler(graph, inv_sqrt, options.seed);
}

TwoWayCut BestSweepCut(const SimilarityGraph& graph, const std::vector<double>& values,
                       uint32_t min_side) {
  const uint32_t n = graph.node_count();
  MOTIF_CHECK(values.size() == n);
  TwoWayCut best;
  min_side = std::max<uint32_t>(min_side, 1);
  if (n < 2 * min_side) return best;
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return values[a] != values[b] ? values[a] < values[b] : a < b;
  });
  double total = 0;
  for (uint32_t node = 0; node < n; ++node) total += graph.Degree(node);
  std::vector<bool> in_a(n, false);
  double cut = 0;
  double assoc_a = 0;
  uint32_t best_count = 0;
  for (uint32_t count = 1; count < n; ++count) {
    const uint32_t node = order[count - 1];
    in_a[node] = true;
    assoc_a += graph.Degree(node);
    const auto targets = graph.Targets(node);
    const auto weights = graph.Weights(node);
    for (size_t edge = 0; edge < targets.size(); ++edge) {
      cut += in_a[targets[edge]] ? -weights[edge] : weights[edge];
    }
    if (count < min_side || n - count < min_side) continue;
    const double assoc_b = total - assoc_a;
    if (!(assoc_a > 0) || !(assoc_b > 0)) continue;
    const double ncut = std::max(0.0, cut) / assoc_a + std::max(0.0, cut) / assoc_b;
    if (ncut < best.ncut) {
      best.ncut = ncut;
      best_count = count;
    }
  }
  if (best_count == 0) return best;
  best.side_a.assign(order.begin(), order.begin() + best_count);
  best.side_b.assign(order.begin() + best_count, order.end());
  std::sort(best.side_a.begin(), best.side_a.end());
  std::sort(best.side_b.begin(), best.side_b.end());
  return best;
}

double NormalizedCutValue(const SimilarityGraph& graph, const std::vector<bool>& in_a) {
  double cut = 0;
  double assoc_a = 0;
  double assoc_b = 0;
  for (uint32_t node = 0; node < graph.node_count(); ++node) {
    (in_a[node] ? assoc_a : assoc_b) += graph.Degree(node);
    const auto targets = graph.Targets(node);
    const auto weights = graph.Weights(node);
    for (size_t edge = 0; edge < targets.size(); ++edge) {
      if (in_a[node] && !in_a[targets[edge]]) cut += weights[edge];
    }
  }
  if (!(assoc_a > 0) || !(assoc_b > 0)) return std::numeric_limits<double>::infinity();
  return cut / assoc_a + cut / assoc_b;
}

}  // namespace motif
