// LSH eps-neighbour search (engine/lsh, docs/design/lsh.md) over archives of N = 2^14 .. 2^20
// frames, with 1 and 2 threads (the thread count goes to the search's own task_arena):
//   LshBuild/<data>          LshSearch::Create: parameters from the data, hashing in shards,
//                            the merge. Items: frames per second.
//   LshQuery/<data>          SearchColumns over a block of 4096 consecutive columns (all of them
//                            below 4096 frames) from the middle of the archive. Items: columns
//                            per second.
//   LshQuery/heavy           2^18 synthetic frames plus 2^14 frames of one static T-pose (a
//                            heavy bucket in every table); the block starts in the T-pose.
// <data> is "synth" (MotionSynthesizer, procedural, seed 7) or "resequenced" (real CMU BVH takes
// re-sequenced by MotionSynthesizer::CreateFromTakes; skipped when ../shared/data/mocap or
// $MOTIF_MOCAP_DIR is absent). eps = mu - 2 sigma of 20,000 sampled pairs, a 30-frame exclusion
// radius, k_max = 256.
// Counters (query): evaluations_per_column (exact D computations), entries_per_column (bucket
// entries read), recall (share of the exact k_max-nearest found, 256 sampled columns, exact by
// ExactSearch), speedup_vs_exact (columns per second against ExactSearch's on the same
// archive and thread count, measured on 512 columns right after), index_bytes_per_frame, and
// rss_bytes_per_frame: the growth of the resident set from before LshSearch::Create to the end
// of the queries, i.e. index + search scratch, over N (PoseFeatures' 96 bytes a frame are held
// before and not included: add them for the total). Build: rss_growth_bytes_per_frame likewise.
// peak_rss_bytes: the process's peak resident set, features included (bench_util.h).
// LshScale/{build,query}/<data>: the same, 2 threads, N = 2^14, 2^15, ... (scripts/bench.sh).
// Left out: reading the archive and writing the trellis. Archives are made once per size,
// outside the timed loops; the memory figures come from the first run of each benchmark.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/distance/exact_search.h"
#include "engine/lsh/lsh_search.h"

namespace motif {
namespace {

constexpr uint64_t kQueryBlock = 4096;
constexpr int kRecallColumns = 256;  // sampled columns for the recall counter

using bench::CurrentRssBytes;

// The archives (synth, resequenced, heavy) and their rules: bench/bench_archives.h.
using bench::Archive;
using bench::ArchiveOf;

// Defaults, or for tuning sweeps the environment's MOTIF_LSH_PROBES, MOTIF_LSH_MAX_CANDIDATES,
// MOTIF_LSH_MAX_ENTRIES, MOTIF_LSH_WIDTH_PER_HASH and MOTIF_LSH_RANKING (sort|code).
LshOptions OptionsFor(uint32_t threads) {
  LshOptions options;
  options.threads = static_cast<int>(threads);
  auto from_env = [](const char* name, auto* value) {
    if (const char* text = std::getenv(name))
      *value = static_cast<std::decay_t<decltype(*value)>>(std::atof(text));
  };
  from_env("MOTIF_LSH_PROBES", &options.probes_per_table);
  from_env("MOTIF_LSH_MAX_CANDIDATES", &options.max_candidates);
  from_env("MOTIF_LSH_MAX_ENTRIES", &options.max_entries);
  from_env("MOTIF_LSH_WIDTH_PER_HASH", &options.width_per_hash);
  if (const char* ranking = std::getenv("MOTIF_LSH_RANKING"))
    ParseLshRanking(ranking, &options.ranking);
  return options;
}

void BM_LshBuild(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const uint32_t threads = static_cast<uint32_t>(state.range(1));
  const Archive& archive = ArchiveOf(data, frames);
  if (!archive.error.empty()) {
    state.SkipWithError(archive.error.c_str());
    return;
  }
  double rss_growth = -1;
  double before = 0;
  double peak = 0;
  uint64_t index_bytes = 0;
  for (auto _ : state) {
    before = CurrentRssBytes();
    bench::ResetPeakRss();
    auto search = LshSearch::Create(*archive.features, archive.rules, OptionsFor(threads));
    if (!search.ok()) {
      state.SkipWithError(search.status().ToString().c_str());
      return;
    }
    peak = bench::PeakRssBytes();
    if (rss_growth < 0) rss_growth = peak - before;
    index_bytes = (*search)->index().memory_bytes();
    benchmark::DoNotOptimize(search->get());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["index_bytes_per_frame"] = static_cast<double>(index_bytes) / frames;
  state.counters["rss_growth_bytes_per_frame"] = rss_growth / frames;
  bench::SetMemoryCounters(state, peak, before, frames);
}

void BM_LshQuery(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const uint32_t threads = static_cast<uint32_t>(state.range(1));
  const Archive& archive = ArchiveOf(data, frames);
  if (!archive.error.empty()) {
    state.SkipWithError(archive.error.c_str());
    return;
  }
  const PoseFeatures& features = *archive.features;
  const double before = CurrentRssBytes();
  bench::ResetPeakRss();
  auto created = LshSearch::Create(features, archive.rules, OptionsFor(threads));
  if (!created.ok()) {
    state.SkipWithError(created.status().ToString().c_str());
    return;
  }
  const LshSearch& search = **created;
  const uint64_t count = std::min(frames, kQueryBlock);
  // The heavy archive's T-pose clip is its last: start the block inside it.
  const uint64_t first =
      data == "heavy" ? features.clip_first_frames().back() - count / 2 : (frames - count) / 2;
  std::vector<std::vector<Neighbour>> columns;
  SearchStats stats;
  LshQueryStats lsh_stats;
  for (auto _ : state) {
    stats = SearchStats();
    lsh_stats = LshQueryStats();
    Status status = search.SearchColumns(first, count, &columns, &stats, &lsh_stats);
    if (!status.ok()) {
      state.SkipWithError(status.ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(columns.data());
  }
  const double peak = bench::PeakRssBytes();
  const double rss_growth = peak - before;
  bench::SetMemoryCounters(state, peak, before, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * count));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["evaluations_per_column"] =
      static_cast<double>(stats.distance_evaluations) / count;
  state.counters["entries_per_column"] = static_cast<double>(lsh_stats.entries_examined) / count;
  state.counters["probes_per_column"] = static_cast<double>(lsh_stats.probes) / count;
  state.counters["extensions_per_column"] = static_cast<double>(lsh_stats.extensions) / count;
  state.counters["budget_capped_share"] =
      static_cast<double>(lsh_stats.columns_budget_capped) / count;
  state.counters["neighbours_per_column"] = static_cast<double>(stats.neighbours) / count;
  state.counters["index_bytes_per_frame"] =
      static_cast<double>(search.index().memory_bytes()) / frames;
  state.counters["rss_bytes_per_frame"] = rss_growth / frames;

  // After the timed loop: recall on 64 sampled columns, and the exact search's speed.
  ExactSearchOptions exact_options;
  exact_options.threads = threads;
  const ExactSearch exact(features, archive.rules, exact_options);
  uint64_t exact_total = 0;
  uint64_t found = 0;
  uint64_t state_bits = 11;
  for (int sample = 0; sample < kRecallColumns; ++sample) {
    state_bits = state_bits * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t column = (state_bits >> 17) % frames;
    std::vector<std::vector<Neighbour>> exact_column;
    std::vector<std::vector<Neighbour>> lsh_column;
    SearchStats ignored;
    if (!exact.SearchColumns(column, 1, &exact_column, &ignored).ok() ||
        !search.SearchColumns(column, 1, &lsh_column, &ignored).ok()) {
      state.SkipWithError("sampled column failed");
      return;
    }
    for (const Neighbour& neighbour : exact_column[0]) {
      for (const Neighbour& candidate : lsh_column[0]) found += candidate.frame == neighbour.frame;
    }
    exact_total += exact_column[0].size();
  }
  // Two of ExactSearch's 256-query blocks, so that both threads have one.
  const uint64_t exact_count = std::min<uint64_t>(frames - first, 512);
  std::vector<std::vector<Neighbour>> exact_columns;
  SearchStats exact_stats;
  const auto exact_start = std::chrono::steady_clock::now();
  if (!exact.SearchColumns(first, exact_count, &exact_columns, &exact_stats).ok()) {
    state.SkipWithError("exact search failed");
    return;
  }
  const double exact_seconds_per_column =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - exact_start).count() /
      exact_count;
  const auto lsh_start = std::chrono::steady_clock::now();
  if (!search.SearchColumns(first, count, &columns, &stats).ok()) {
    state.SkipWithError("lsh search failed");
    return;
  }
  const double lsh_seconds_per_column =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - lsh_start).count() / count;
  state.counters["recall"] = exact_total ? static_cast<double>(found) / exact_total : 1.0;
  state.counters["speedup_vs_exact"] = exact_seconds_per_column / lsh_seconds_per_column;
  state.counters["eps"] = archive.rules.eps;
  state.SetLabel(search.DescribeParams());
}

// Sizes outer, threads inner, so each archive is made once per benchmark family.
void Sizes(benchmark::internal::Benchmark* benchmark) {
  for (int64_t frames = 1 << 14; frames <= (1 << 20); frames *= 4) {
    for (int64_t threads : {1, 2}) benchmark->Args({frames, threads});
  }
}

const bool registered = [] {
  for (const std::string data : {"synth", "resequenced"}) {
    benchmark::RegisterBenchmark(("LshBuild/" + data).c_str(), BM_LshBuild, data)
        ->ArgNames({"frames", "threads"})
        ->Apply(Sizes)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1)
        ->Complexity(benchmark::oNLogN);
    benchmark::RegisterBenchmark(("LshQuery/" + data).c_str(), BM_LshQuery, data)
        ->ArgNames({"frames", "threads"})
        ->Apply(Sizes)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1)
        ->Complexity(benchmark::oAuto);
  }
  // The scaling series (scripts/bench.sh): 2 threads, N = 2^14, 2^15, ... up to
  // $MOTIF_BENCH_MAX_FRAMES (bench_util.h).
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames, 2});
  for (const std::string data : {"synth", "resequenced"}) {
    for (auto [name, function, complexity] :
         {std::tuple{"LshScale/build/", &BM_LshBuild, benchmark::oNLogN},
          std::tuple{"LshScale/query/", &BM_LshQuery, benchmark::oAuto}}) {
      if (auto* family = bench::RegisterRows(std::string(name) + data, rows, function, data)) {
        family->ArgNames({"frames", "threads"})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1)
            ->Complexity(complexity);
      }
    }
  }
  benchmark::RegisterBenchmark("LshQuery/heavy", BM_LshQuery, std::string("heavy"))
      ->ArgNames({"frames", "threads"})
      ->Args({1 << 18, 2})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
