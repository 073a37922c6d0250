// Motion-signature numerics (engine/signature): the Earth Mover's Distance and k-means.
//
// * Emd/simplex/k:K/support:S: one EMD between two signatures over K motifs with S bins of mass
//   each (S = K: a whole take, every motif used; S = 9 or 12: the paper's windows of 9 and 12
//   words, at most that many motifs), by the network simplex (TransportSimplex through
//   EarthMoversDistance). Ground: Euclidean distances between K random centroids in 32
//   dimensions (motif centroids are embedded words). Masses: uniform random on S random bins.
//   A pool of 64 signatures is built outside the timed loop; each iteration takes the next pair.
//   Counter: pivots per EMD.
// * Emd/boost/k:K/support:S: the same pairs by Boost.Graph's successive shortest paths
//   (SolveTransportWithBoost), the reference the simplex is tested against. Both series time
//   the whole call, building the transportation problem included.
// * KMeans/points:N/threads:T: RunKMeans with k = 100 on N points of 32 dimensions drawn around
//   100 random centres, at most 10 Lloyd iterations (tolerance 0), in a task_arena of T threads
//   (wall time). Items: points x Lloyd iterations per second (k-means++ seeding, about one more
//   pass over the points, is inside the timing but not counted as an item).
// Left out: cache effects between unrelated EMDs (the pool is small and stays in cache), I/O.
// Run: bench/bench_engine_emd --benchmark_min_time=0.2 (docs/design/signatures.md lists results).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/lsh/split_mix64.h"
#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/ground_distance.h"
#include "engine/signature/k_means.h"
#include "engine/signature/transport_problem.h"
#include "engine/signature/transport_reference.h"

namespace motif {
namespace {

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_emd: %s\n", status.ToString().c_str());
  std::exit(1);
}

constexpr uint32_t kDimensions = 32;
constexpr size_t kPool = 64;

RowMatrixXf RandomCentroids(uint32_t k, uint64_t seed) {
  SplitMix64 random(seed);
  RowMatrixXf centroids(k, kDimensions);
  for (uint32_t row = 0; row < k; ++row) {
    for (uint32_t dim = 0; dim < kDimensions; ++dim) {
      centroids(row, dim) = static_cast<float>(random.Gaussian());
    }
  }
  return centroids;
}

std::vector<std::vector<double>> SignaturePool(uint32_t k, uint32_t support, uint64_t seed) {
  SplitMix64 random(seed);
  std::vector<std::vector<double>> pool(kPool, std::vector<double>(k, 0.0));
  std::vector<uint32_t> bins(k);
  for (std::vector<double>& signature : pool) {
    for (uint32_t bin = 0; bin < k; ++bin) bins[bin] = bin;
    for (uint32_t idx = 0; idx < support; ++idx) {  // a random subset of `support` bins
      std::swap(bins[idx], bins[idx + random.Below(k - idx)]);
      signature[bins[idx]] = 0.05 + random.Uniform();
    }
  }
  return pool;
}

void BM_EmdSimplex(benchmark::State& state) {
  const uint32_t k = static_cast<uint32_t>(state.range(0));
  const uint32_t support = static_cast<uint32_t>(state.range(1));
  const Eigen::MatrixXd ground = CentroidGroundDistance(RandomCentroids(k, 1));
  const std::vector<std::vector<double>> pool = SignaturePool(k, support, 2);
  EarthMoversDistance emd;
  size_t pair = 0;
  uint64_t pivots = 0;
  for (auto _ : state) {
    Result<EmdSolution> solution = emd.Solve(pool[pair % kPool], pool[(pair + 1) % kPool], ground);
    if (!solution.ok()) Die(solution.status());
    benchmark::DoNotOptimize(solution->distance);
    pivots += solution->pivots;
    ++pair;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["pivots"] = static_cast<double>(pivots) / static_cast<double>(state.iterations());
}

void BM_EmdBoost(benchmark::State& state) {
  const uint32_t k = static_cast<uint32_t>(state.range(0));
  const uint32_t support = static_cast<uint32_t>(state.range(1));
  const Eigen::MatrixXd ground = CentroidGroundDistance(RandomCentroids(k, 1));
  const std::vector<std::vector<double>> pool = SignaturePool(k, support, 2);
  TransportProblem problem;
  TransportPlan plan;
  size_t pair = 0;
  for (auto _ : state) {
    const Status status = BuildTransportProblem(pool[pair % kPool], pool[(pair + 1) % kPool],
                                                ground, EmdMass::kNormalize, &problem);
    if (!status.ok()) Die(status);
    SolveTransportWithBoost(problem, &plan);
    benchmark::DoNotOptimize(plan.cost);
    ++pair;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void BM_KMeans(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const uint32_t k = 100;
  const RowMatrixXf centres = RandomCentroids(k, 3);
  SplitMix64 random(4);
  RowMatrixXf points(n, kDimensions);
  for (uint32_t row = 0; row < n; ++row) {
    const uint32_t centre = static_cast<uint32_t>(random.Below(k));
    for (uint32_t dim = 0; dim < kDimensions; ++dim) {
      points(row, dim) = centres(centre, dim) + 0.3f * static_cast<float>(random.Gaussian());
    }
  }
  KMeansOptions options;
  options.k = k;
  options.max_iterations = 10;
  options.tolerance = 0;
  options.threads = threads;
  uint64_t iterations = 0;
  for (auto _ : state) {
    Result<KMeansResult> result = RunKMeans(points, options);
    if (!result.ok()) Die(result.status());
    benchmark::DoNotOptimize(result->inertia);
    iterations += result->iterations;
  }
  state.SetItemsProcessed(static_cast<int64_t>(iterations) * n);
  state.counters["lloyd_iterations"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
}

BENCHMARK(BM_EmdSimplex)
    ->Name("Emd/simplex")
    ->ArgNames({"k", "support"})
    ->Args({25, 25})
    ->Args({50, 50})
    ->Args({100, 100})
    ->Args({200, 200})
    ->Args({100, 9})
    ->Args({100, 12})
    ->Args({100, 25})
    ->Args({100, 50})
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_EmdBoost)
    ->Name("Emd/boost")
    ->ArgNames({"k", "support"})
    ->Args({25, 25})
    ->Args({50, 50})
    ->Args({100, 100})
    ->Args({200, 200})
    ->Args({100, 12})
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_KMeans)
    ->Name("KMeans")
    ->ArgNames({"points", "threads"})
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
