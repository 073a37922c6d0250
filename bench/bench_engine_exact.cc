// Exact trellis search (ExactSearch: blocked brute force, the O(N^2) baseline of the LSH search):
// the time to find every column of an N-frame archive, N = 2^12 .. 2^16 with 1 thread and
// 2^12 .. 2^17 with 2 threads (an explicit task_arena inside the search), and the fitted
// complexity (expected: N^2).
// Items are columns per second; counters: mean neighbours kept per column, distance
// evaluations per second. The archives are synthetic (MotionSynthesizer, fixed seed, planted
// motifs), built in memory once per size outside the timed loop, with eps = mu - 2 sigma from
// the EpsilonEstimator (seed 1), a 30-frame exclusion radius and k_max = 256. Leaves out reading
// the archive (the features are in memory) and writing the trellis.
// One run at 2^17 frames takes about 40 s with 2 threads (AVX2 kernel) and 80 s with one, so
// the one-thread sweep stops at 2^16 unless MOTIF_BENCH_EXACT_LARGE=1 is set. Time is wall
// time; the CPU column is the whole process's.
//
// The scaling series (scripts/bench.sh), 2 threads, on the archives of bench/bench_archives.h
// ("synth", "resequenced": the real takes' neighbour density), N = 2^14, 2^15, ... up to
// $MOTIF_BENCH_MAX_FRAMES (bench_util.h):
//   ExactScale/<data>               every column, in blocks of 4096 columns (as the trellis
//                                   builder asks for them), while practical: N <= 2^17.
//   ExactScale/<data>/extrapolated  above 2^17: EXTRAPOLATED: 512 consecutive columns from the
//                                   middle of the archive timed, the reported (manual) time is
//                                   their time per column x N.
// Items: columns per second. Memory counters (bench_util.h): the features (96 bytes a frame,
// resident before the measurement starts, so in the peak) and one block of columns.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/distance/distance_kernel.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif {
namespace {

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_exact: %s\n", status.ToString().c_str());
  std::exit(1);
}

struct Archive {
  std::unique_ptr<PoseFeatures> features;
  NeighbourRules rules;
};

// A synthetic archive of `frames` frames and its rules, made once per size.
const Archive& ArchiveOf(uint64_t frames) {
  static std::map<uint64_t, Archive> archives;
  auto it = archives.find(frames);
  if (it != archives.end()) return it->second;
  SynthOptions options;
  options.frames = frames;
  options.motifs = frames >= (1 << 14) ? 4 : 1;
  options.motif_seconds_max = 2.0;
  options.seed = 7;
  auto synthesizer = MotionSynthesizer::Create(options);
  if (!synthesizer.ok()) Die(synthesizer.status());
  const Skeleton& skeleton = (*synthesizer)->skeleton();
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  std::vector<float> rows;
  std::vector<uint64_t> clip_first_frames;
  uint64_t frame_count = 0;
  Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    clip_first_frames.push_back(frame_count);
    rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
    frame_count += clip.info.frame_count;
    return Status::Ok();
  });
  if (!status.ok()) Die(status);
  Result<std::vector<float>> weights = LoadDistanceWeights(skeleton, "");
  if (!weights.ok()) Die(weights.status());
  Archive archive;
  archive.features = std::make_unique<PoseFeatures>(PoseFeatures::FromRows(
      rows.data(), frame_count, layout.joint_count, *weights, clip_first_frames));
  archive.rules.exclusion_frames = 30;
  archive.rules.k_max = 256;
  archive.rules.clip_first_frames = clip_first_frames;
  Result<EpsilonEstimate> estimate = EpsilonEstimator(*archive.features, archive.rules).Estimate();
  if (!estimate.ok()) Die(estimate.status());
  archive.rules.eps = estimate->eps;
  return archives[frames] = std::move(archive);
}

void BM_ExactSearch(benchmark::State& state, uint32_t threads) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const Archive& archive = ArchiveOf(frames);
  ExactSearchOptions options;
  options.threads = threads;
  const ExactSearch search(*archive.features, archive.rules, options);
  std::vector<std::vector<Neighbour>> columns;
  SearchStats stats;
  for (auto _ : state) {
    stats = SearchStats();
    Status status = search.SearchColumns(0, frames, &columns, &stats);
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
    benchmark::DoNotOptimize(columns.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["eps"] = archive.rules.eps;
  state.counters["mean_k"] = static_cast<double>(stats.neighbours) / static_cast<double>(frames);
  state.counters["capped_columns"] = static_cast<double>(stats.capped_columns);
  state.counters["distances_per_second"] = benchmark::Counter(
      static_cast<double>(stats.distance_evaluations) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
  state.SetLabel(DistanceKernel::BestSimd() == DistanceKernel::Simd::kAvx2 ? "avx2" : "portable");
}

constexpr uint64_t kScaleBlock = 4096;
constexpr int64_t kLargestFullScale = 1 << 17;
constexpr uint64_t kExtrapolationColumns = 512;  // two of ExactSearch's 256-query blocks

// Every column of the archive (extrapolated = false), or kExtrapolationColumns of them scaled to
// N (true), 2 threads.
void BM_ExactScale(benchmark::State& state, std::string data, bool extrapolated) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const bench::Archive& archive = bench::ArchiveOf(data, frames);
  if (!archive.error.empty()) {
    state.SkipWithError(archive.error.c_str());
    return;
  }
  ExactSearchOptions options;
  options.threads = static_cast<uint32_t>(state.range(1));
  const ExactSearch search(*archive.features, archive.rules, options);
  std::vector<std::vector<Neighbour>> columns;
  SearchStats stats;
  const uint64_t first = extrapolated ? (frames - kExtrapolationColumns) / 2 : 0;
  const uint64_t count = extrapolated ? kExtrapolationColumns : frames;
  double baseline = 0;
  double cpu_seconds = 0;
  for (auto _ : state) {
    stats = SearchStats();
    baseline = bench::StartMemoryMeasurement();
    const double cpu_start = bench::ProcessCpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    for (uint64_t block = first; block < first + count; block += kScaleBlock) {
      Status status = search.SearchColumns(block, std::min(kScaleBlock, first + count - block),
                                           &columns, &stats);
      if (!status.ok()) {
        state.SkipWithError(status.ToString().c_str());
        return;
      }
      benchmark::DoNotOptimize(columns.data());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu_seconds = (bench::ProcessCpuSeconds() - cpu_start) * frames / count;
    if (extrapolated) state.SetIterationTime(seconds * frames / count);
  }
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["cpu_s"] = cpu_seconds;
  state.counters["eps"] = archive.rules.eps;
  state.counters["mean_k"] = static_cast<double>(stats.neighbours) / static_cast<double>(count);
  state.counters["extrapolated"] = extrapolated;
  if (extrapolated) {
    state.SetLabel("EXTRAPOLATED from " + std::to_string(count) + " timed columns");
  }
}

int64_t LargestFrames(uint32_t threads) {
  const char* large = std::getenv("MOTIF_BENCH_EXACT_LARGE");
  return threads > 1 || (large && *large == '1') ? int64_t{1} << 17 : int64_t{1} << 16;
}

const bool registered = [] {
  for (uint32_t threads : {1u, 2u}) {
    benchmark::RegisterBenchmark(("ExactSearch/threads:" + std::to_string(threads)).c_str(),
                                 BM_ExactSearch, threads)
        ->ArgName("frames")
        ->RangeMultiplier(2)
        ->Range(1 << 12, LargestFrames(threads))
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MeasureProcessCPUTime()
        ->Complexity(benchmark::oNSquared);
  }
  for (const std::string data : {"synth", "resequenced"}) {
    for (bool extrapolated : {false, true}) {
      std::vector<std::vector<int64_t>> rows;
      for (int64_t frames : bench::ScalingFrames()) {
        if ((frames > kLargestFullScale) == extrapolated) rows.push_back({frames, 2});
      }
      auto* entry =
          bench::RegisterRows("ExactScale/" + data + (extrapolated ? "/extrapolated" : ""), rows,
                              BM_ExactScale, data, extrapolated);
      if (entry == nullptr) continue;
      entry->ArgNames({"frames", "threads"})
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->Complexity(benchmark::oNSquared);
      if (extrapolated) {
        entry->UseManualTime();
      } else {
        entry->UseRealTime();
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
