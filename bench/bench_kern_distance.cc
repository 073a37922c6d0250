// Pose distance kernels, single thread: the scalar PoseDistance (one pair at a time, int16
// features dequantised per pair) against the block kernel (DistanceKernel: both blocks
// dequantised once, then a SIMD pass per candidate tile): Distance/Block uses the fastest path
// of this CPU (AVX2 where present, chosen at run time), Distance/BlockPortable the portable
// Eigen path (SSE2 in a default x86-64 build). Items are pair distances D evaluated;
// the block benchmarks include dequantising their two blocks in the timed loop. The frames are
// random unit quaternions (fixed seed) held in memory: this leaves out reading and decoding the
// archive, and the neighbour selection that follows the kernel in a search. The block
// benchmarks also report speedup_vs_scalar, the ratio to the scalar rate measured once on the
// same frames (both in process CPU time, so other load on the machine does not skew it).
//
// DistanceScale/<data>/frames:N (scripts/bench.sh): 64 query frames against every frame of an
// archive of N frames (bench/bench_archives.h: "synth" or "resequenced"), the candidates
// dequantised and compared in blocks of 4096, one thread: a column search's kernel work for 64
// columns, without the neighbour selection. N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES.
// Items: pair distances; memory counters (bench_util.h) include the features (96 B a frame).
#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <random>

#include <benchmark/benchmark.h>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/distance/distance_kernel.h"
#include "engine/distance/pose_features.h"

namespace motif {
namespace {

// `frame_count` frames of `joint_count` random unit quaternions, every joint weighted 1.
const PoseFeatures& RandomFeatures(uint32_t joint_count) {
  static std::map<uint32_t, PoseFeatures> cache;
  auto it = cache.find(joint_count);
  if (it != cache.end()) return it->second;
  constexpr uint64_t kFrames = 4096;
  const FrameLayout layout{joint_count};
  std::mt19937_64 rng(17);
  std::normal_distribution<float> normal;
  std::vector<float> rows(kFrames * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < kFrames; ++frame_idx) {
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      float* q = &rows[frame_idx * layout.stride() + layout.quaternion_offset(joint_idx)];
      float norm = 0;
      for (int component = 0; component < 4; ++component) {
        q[component] = normal(rng);
        norm += q[component] * q[component];
      }
      for (int component = 0; component < 4; ++component) q[component] /= std::sqrt(norm);
    }
  }
  return cache
      .emplace(joint_count, PoseFeatures::FromRows(rows.data(), kFrames, joint_count,
                                                   std::vector<float>(joint_count, 1.0f), {0}))
      .first->second;
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Scalar pair distances per CPU second on `features` (timed once, about 0.3 s).
double ScalarRate(const PoseFeatures& features) {
  static std::map<uint32_t, double> cache;
  auto it = cache.find(features.weighted_joint_count());
  if (it != cache.end()) return it->second;
  const double start = CpuSeconds();
  uint64_t pairs = 0;
  float sink = 0;
  double seconds = 0;
  while (seconds < 0.3) {
    for (uint64_t query = 0; query < 64; ++query) {
      for (uint64_t candidate = 0; candidate < 1024; ++candidate) {
        sink += PoseDistance(features, query, 1024 + candidate);
      }
    }
    pairs += 64 * 1024;
    seconds = CpuSeconds() - start;
  }
  benchmark::DoNotOptimize(sink);
  return cache[features.weighted_joint_count()] = static_cast<double>(pairs) / seconds;
}

void BM_DistanceScalar(benchmark::State& state) {
  const PoseFeatures& features = RandomFeatures(static_cast<uint32_t>(state.range(0)));
  constexpr uint64_t kQueries = 16;
  constexpr uint64_t kCandidates = 1024;
  for (auto _ : state) {
    for (uint64_t query = 0; query < kQueries; ++query) {
      float total = 0;
      for (uint64_t candidate = 0; candidate < kCandidates; ++candidate) {
        total += PoseDistance(features, query, kQueries + candidate);
      }
      benchmark::DoNotOptimize(total);
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kQueries * kCandidates));
}
BENCHMARK(BM_DistanceScalar)->Name("Distance/Scalar")->ArgName("joints")->Arg(4)->Arg(12)->Arg(31);

void BlockBenchmark(benchmark::State& state, DistanceKernel::Simd simd) {
  const PoseFeatures& features = RandomFeatures(static_cast<uint32_t>(state.range(0)));
  const uint32_t query_count = static_cast<uint32_t>(state.range(1));
  const uint32_t candidate_count = static_cast<uint32_t>(state.range(2));
  const DistanceKernel kernel(features, simd);
  state.SetLabel(kernel.simd() == DistanceKernel::Simd::kAvx2 ? "avx2" : "portable");
  FrameBlock queries;
  FrameBlock candidates;
  std::vector<float> out(static_cast<size_t>(query_count) * candidate_count);
  const double start = CpuSeconds();
  for (auto _ : state) {
    queries.LoadRange(features, 0, query_count);
    candidates.LoadRange(features, features.frame_count() - candidate_count, candidate_count);
    kernel.Compute(queries, candidates, out.data(), candidate_count);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  const double seconds = CpuSeconds() - start;
  const double pairs = static_cast<double>(state.iterations()) * query_count * candidate_count;
  state.SetItemsProcessed(static_cast<int64_t>(pairs));
  state.counters["speedup_vs_scalar"] = pairs / seconds / ScalarRate(features);
}

void BM_DistanceBlock(benchmark::State& state) {
  BlockBenchmark(state, DistanceKernel::BestSimd());
}
BENCHMARK(BM_DistanceBlock)
    ->Name("Distance/Block")
    ->ArgNames({"joints", "queries", "candidates"})
    ->Args({4, 256, 1024})
    ->Args({12, 64, 1024})
    ->Args({12, 256, 1024})
    ->Args({12, 256, 4096})
    ->Args({31, 256, 1024});

void BM_DistanceBlockPortable(benchmark::State& state) {
  BlockBenchmark(state, DistanceKernel::Simd::kPortable);
}
BENCHMARK(BM_DistanceBlockPortable)
    ->Name("Distance/BlockPortable")
    ->ArgNames({"joints", "queries", "candidates"})
    ->Args({4, 256, 1024})
    ->Args({12, 256, 1024})
    ->Args({31, 256, 1024});

void BM_DistanceScale(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const bench::Archive& archive = bench::ArchiveOf(data, frames);
  if (!archive.error.empty()) {
    state.SkipWithError(archive.error.c_str());
    return;
  }
  constexpr uint32_t kQueries = 64;
  constexpr uint64_t kBlock = 4096;
  const PoseFeatures& features = *archive.features;
  const DistanceKernel kernel(features, DistanceKernel::BestSimd());
  state.SetLabel(kernel.simd() == DistanceKernel::Simd::kAvx2 ? "avx2" : "portable");
  FrameBlock queries;
  FrameBlock candidates;
  std::vector<float> out(kQueries * kBlock);
  queries.LoadRange(features, frames / 2, kQueries);
  const double baseline = bench::StartMemoryMeasurement();
  for (auto _ : state) {
    for (uint64_t first = 0; first < frames; first += kBlock) {
      const uint64_t count = std::min(kBlock, frames - first);
      candidates.LoadRange(features, first, count);
      kernel.Compute(queries, candidates, out.data(), count);
      benchmark::DoNotOptimize(out.data());
    }
    benchmark::ClobberMemory();
  }
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames * kQueries));
  state.SetComplexityN(static_cast<int64_t>(frames));
}

const bool scale_registered = [] {
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames});
  for (const std::string data : {"synth", "resequenced"}) {
    if (auto* family = bench::RegisterRows("DistanceScale/" + data, rows, BM_DistanceScale, data)) {
      family->ArgName("frames")
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Complexity(benchmark::oN);
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
