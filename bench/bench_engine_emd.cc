// Motion-signature numerics (engine/signature): the Earth Mover's Distance, k-means, and the DTW
// distance between motion words.
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
// * WordDtw/band:R: one DTW between two motion words (W = 16 frames, 12 weighted joints, the
//   trellis's pose distance; engine/signature/word_distance.h) with a Sakoe-Chiba band of radius
//   R (15: unconstrained), no threshold. Words: every word of a 60 s procedural clip at 120 fps
//   (31 joints turning sinusoidally about random axes, 12 of them weighted; 356 words),
//   resampled to 24 Hz by ClipWords; pairs drawn at random outside the timed loop.
//   Counter: frame distances (cells) per DTW.
// * WordDtw/prepared/band:R: the same on words prepared (dequantised) outside the timed loop,
//   as a search comparing each word with many would use them.
// * WordDtw/abandon/band:R: prepared words, with a threshold at the 10th percentile of the pool's
//   distances, as a nearest-word search would pass its current k-th best. Counter: fraction of
//   the calls abandoned.
// * WordSample/joints:31: FrameResampler::InterpolateFeatures, one word frame (12 slerps and
//   their quantisation) from two archive rows at alpha = 0.37. Items: word frames.
// Left out: cache effects between unrelated EMDs (the pool is small and stays in cache), I/O.
// Run: bench/bench_engine_emd --benchmark_min_time=0.2 (docs/design/signatures.md lists results).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "common/split_mix64.h"
#include "engine/signature/clip_words.h"
#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/ground_distance.h"
#include "engine/signature/k_means.h"
#include "engine/signature/transport_problem.h"
#include "engine/signature/transport_reference.h"
#include "engine/signature/word_distance.h"

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

// A procedural clip: `joint_count` joints, each turning sinusoidally about a random axis, every
// other joint of the first 24 weighted (12 weighted joints, as the CMU skeleton's defaults).
struct BenchClip {
  FrameLayout layout;
  std::vector<float> rows;
  std::vector<float> weights;
};

BenchClip MakeBenchClip(uint32_t joint_count, uint64_t frames, uint64_t seed) {
  SplitMix64 random(seed);
  BenchClip clip;
  clip.layout = FrameLayout{joint_count};
  clip.rows.assign(frames * clip.layout.stride(), 0.0f);
  for (uint32_t joint = 0; joint < joint_count; ++joint) {
    clip.weights.push_back(joint < 24 && joint % 2 == 0 ? 1.0f : 0.0f);
    Eigen::Vector3d axis(random.Gaussian(), random.Gaussian(), random.Gaussian());
    axis.normalize();
    const double amplitude = 0.2 + random.Uniform();
    const double frequency = 0.3 + 1.5 * random.Uniform();
    const double phase = 6.283185307179586 * random.Uniform();
    for (uint64_t frame = 0; frame < frames; ++frame) {
      const double angle =
          amplitude * std::sin(6.283185307179586 * frequency * frame / 120.0 + phase);
      const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, axis));
      float* out = &clip.rows[frame * clip.layout.stride() + clip.layout.quaternion_offset(joint)];
      out[0] = static_cast<float>(q.w());
      out[1] = static_cast<float>(q.x());
      out[2] = static_cast<float>(q.y());
      out[3] = static_cast<float>(q.z());
    }
  }
  return clip;
}

// All words of a 60 s clip, and random pairs of them.
struct WordPool {
  WordBatch words;
  std::vector<float> weights;
  std::vector<std::pair<size_t, size_t>> pairs;
};

WordPool MakeWordPool() {
  const BenchClip clip = MakeBenchClip(31, 7200, 5);
  Result<ClipWords> words = ClipWords::FromRows(clip.rows, 120.0, clip.layout, clip.weights);
  if (!words.ok()) Die(words.status());
  WordPool pool;
  words->AllWords(&pool.words);
  pool.weights = words->resampler().weights();
  SplitMix64 random(6);
  for (int pair = 0; pair < 4096; ++pair) {
    pool.pairs.emplace_back(random.Below(pool.words.size()), random.Below(pool.words.size()));
  }
  return pool;
}

void SetDtwCounters(benchmark::State& state, uint32_t band) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  const int64_t radius = std::min<int64_t>(band, 15);
  state.counters["cells"] = static_cast<double>(16 * (2 * radius + 1) - radius * (radius + 1));
}

void BM_WordDtw(benchmark::State& state) {
  const uint32_t band = static_cast<uint32_t>(state.range(0));
  const WordPool pool = MakeWordPool();
  const WordDistance distance(pool.weights, 16, band);
  size_t pair = 0;
  for (auto _ : state) {
    const auto& [a, b] = pool.pairs[pair++ % pool.pairs.size()];
    benchmark::DoNotOptimize(distance.Dtw(pool.words.word(a), pool.words.word(b)));
  }
  SetDtwCounters(state, band);
}

void BM_WordDtwPrepared(benchmark::State& state) {
  const uint32_t band = static_cast<uint32_t>(state.range(0));
  const WordPool pool = MakeWordPool();
  const WordDistance distance(pool.weights, 16, band);
  std::vector<PreparedWord> prepared(pool.words.size());
  for (size_t word = 0; word < pool.words.size(); ++word) {
    distance.Prepare(pool.words.word(word), &prepared[word]);
  }
  size_t pair = 0;
  for (auto _ : state) {
    const auto& [a, b] = pool.pairs[pair++ % pool.pairs.size()];
    benchmark::DoNotOptimize(distance.Dtw(prepared[a], prepared[b]));
  }
  SetDtwCounters(state, band);
}

void BM_WordDtwAbandon(benchmark::State& state) {
  const uint32_t band = static_cast<uint32_t>(state.range(0));
  const WordPool pool = MakeWordPool();
  const WordDistance distance(pool.weights, 16, band);
  std::vector<double> all;
  for (const auto& [a, b] : pool.pairs) {
    all.push_back(distance.Dtw(pool.words.word(a), pool.words.word(b)));
  }
  std::nth_element(all.begin(), all.begin() + all.size() / 10, all.end());
  const double threshold = all[all.size() / 10];
  std::vector<PreparedWord> prepared(pool.words.size());
  for (size_t word = 0; word < pool.words.size(); ++word) {
    distance.Prepare(pool.words.word(word), &prepared[word]);
  }
  size_t pair = 0;
  uint64_t abandoned = 0;
  for (auto _ : state) {
    const auto& [a, b] = pool.pairs[pair++ % pool.pairs.size()];
    const double result = distance.Dtw(prepared[a], prepared[b], threshold);
    abandoned += std::isinf(result);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["abandoned"] =
      static_cast<double>(abandoned) / static_cast<double>(state.iterations());
}

void BM_WordSample(benchmark::State& state) {
  const BenchClip clip = MakeBenchClip(static_cast<uint32_t>(state.range(0)), 64, 7);
  Result<FrameResampler> resampler = FrameResampler::Create(clip.layout, clip.weights);
  if (!resampler.ok()) Die(resampler.status());
  std::vector<int16_t> out(resampler->feature_values());
  const size_t stride = clip.layout.stride();
  size_t frame = 0;
  for (auto _ : state) {
    const float* lower = &clip.rows[(frame % 63) * stride];
    resampler->InterpolateFeatures(lower, lower + stride, 0.37, out.data());
    benchmark::DoNotOptimize(out.data());
    ++frame;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

BENCHMARK(BM_WordDtw)
    ->Name("WordDtw")
    ->ArgNames({"band"})
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(15)
    ->Unit(benchmark::kNanosecond);

BENCHMARK(BM_WordDtwPrepared)
    ->Name("WordDtw/prepared")
    ->ArgNames({"band"})
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(15)
    ->Unit(benchmark::kNanosecond);

BENCHMARK(BM_WordDtwAbandon)
    ->Name("WordDtw/abandon")
    ->ArgNames({"band"})
    ->Arg(2)
    ->Unit(benchmark::kNanosecond);

BENCHMARK(BM_WordSample)->Name("WordSample")->ArgNames({"joints"})->Arg(31);

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
