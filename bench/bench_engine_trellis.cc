// The whole matching-trellis build (BuildTrellis, engine/trellis): reading the archive into
// PoseFeatures, estimating eps (mu - 2 sigma of 200,000 pairs), the search index, the column
// search and the spill of every column block to the .mtr file, over archives of N frames:
//   TrellisBuild/<data>/lsh                 the LSH search, N = 2^14, 2^15, ... up to
//                                           $MOTIF_BENCH_MAX_FRAMES (default 2^17; 2^24 in
//                                           scripts/bench.sh full), 2 threads; 1 thread too at
//                                           2^20 (thread scaling), in a family of its own.
//   TrellisBuild/<data>/exact               the exact search (ExactSearch, O(N^2)), full builds
//                                           while practical: N = 2^14 .. 2^17, 2 threads.
//   TrellisBuild/<data>/exact_extrapolated  above 2^17: EXTRAPOLATED, not a full build. The
//                                           features and eps stages are run and timed, the exact
//                                           search is timed on kExactSampleColumns consecutive
//                                           columns from the middle of the archive, and the
//                                           reported time (manual time) is features + eps +
//                                           (search seconds per column) x N.
// <data>: "synth" (MotionSynthesizer, procedural, seed 7) or "resequenced" (the real CMU BVH
// takes re-sequenced by MotionSynthesizer::CreateFromTakes, as in bench_engine_lsh; skipped when
// ../shared/data/mocap or $MOTIF_MOCAP_DIR is absent). Archives: bench/bench_archives.h (written
// once to $MOTIF_BENCH_DIR/archives and reused); the trellis file, in $MOTIF_BENCH_DIR/trellis,
// is deleted before and after each build. eps auto, k_max 256, exclusion 30 frames
// (half of 0.5 s at 120 fps), seed 1: BuildTrellis's defaults.
//
// Counters (items per second = frames per second of the whole build):
//   peak_rss_bytes(_per_frame) the process's peak resident set (VmHWM, reset just before the
//                             build, after malloc_trim), and over N. It includes the process's
//                             own baseline (baseline_rss_bytes, the resident set when the mark
//                             was reset: 5-20 MB, which dominates below 2^17 frames).
//   evaluations_per_column    exact distance evaluations per column (N for the exact search).
//   recall                    share of the exact k_max-nearest found in the trellis file, pooled
//                             over kRecallColumns sampled columns (exact columns by ExactSearch,
//                             after the build, outside the time and memory figures).
//   exact_extrapolated_s, speedup_vs_exact (LSH rows): the exact build's time extrapolated as
//                             above, measured in the same process right after the LSH build, and
//                             its ratio to the LSH build's time.
//   build_cpu_s, exact_search_cpu_extrapolated_s, cpu_speedup_vs_exact: the same in process CPU
//                             seconds (the exact side: its column search only), which a machine
//                             shared with other jobs disturbs far less than wall time.
//   write_s, write_wait_s:    compressing and writing blocks (on the writer thread, beside the
//                             search), and how long the search waited for it.
//   features_s, eps_s, index_s, search_s: BuildTrellis's stages (search_s includes the writes);
//   search_cpu_per_wall: process CPU time over wall time during the column search (about the
//                             thread count when every thread works); us_per_column = search_s/N.
//   trellis_bytes_per_frame, mean_k, eps.
// One iteration each (a build is long); Complexity() fits when several sizes run in one process.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/pipeline/stage_options.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

constexpr uint64_t kRecallColumns = 500;
constexpr uint64_t kExactSampleColumns = 1024;  // 4 of ExactSearch's 256-query blocks
constexpr uint64_t kLargestFullExact = 1 << 17;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

using bench::ProcessCpuSeconds;

std::string WorkDir() {
  const std::string dir = bench::WorkDir() + "/trellis";
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  return dir;
}

void RemoveTrellis(const std::string& path) {
  std::error_code error;
  std::filesystem::remove(path, error);
  std::filesystem::remove(path + ".partial", error);
}

struct LoadedArchive {
  std::unique_ptr<PoseFeatures> features;
  NeighbourRules rules;  // eps left to the caller
  double features_seconds = 0;
};

Result<LoadedArchive> LoadFeatures(const std::string& archive_path) {
  const auto start = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader,
                         FrameFileReader::Open(archive_path));
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights, LoadDistanceWeights(reader->skeleton(), ""));
  MOTIF_ASSIGN_OR_RETURN(PoseFeatures features, PoseFeatures::FromArchive(*reader, weights));
  LoadedArchive loaded;
  loaded.features = std::make_unique<PoseFeatures>(std::move(features));
  loaded.rules.k_max = TrellisOptions().k_max;
  loaded.rules.exclusion_frames = ResolvedExclusionFrames(motifmine::MineOptions{}, reader->fps());
  loaded.rules.clip_first_frames = loaded.features->clip_first_frames();
  loaded.features_seconds = Seconds(start);
  return loaded;
}

// Wall and process CPU seconds per column of the exact search with `threads` threads, timed on
// kExactSampleColumns consecutive columns from the middle of the archive (fewer on small ones).
struct PerColumn {
  double wall = 0;
  double cpu = 0;
};
Result<PerColumn> ExactSecondsPerColumn(const LoadedArchive& archive, int threads) {
  const uint64_t frames = archive.features->frame_count();
  const uint64_t count = std::min(frames, kExactSampleColumns);
  ExactSearchOptions options;
  options.threads = static_cast<uint32_t>(threads);
  const ExactSearch exact(*archive.features, archive.rules, options);
  std::vector<std::vector<Neighbour>> columns;
  SearchStats stats;
  const double cpu_start = ProcessCpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  MOTIF_RETURN_IF_ERROR(exact.SearchColumns((frames - count) / 2, count, &columns, &stats));
  PerColumn per_column;
  per_column.wall = Seconds(start) / static_cast<double>(count);
  per_column.cpu = (ProcessCpuSeconds() - cpu_start) / static_cast<double>(count);
  return per_column;
}

// Recall of the trellis file against the exact columns of kRecallColumns sampled columns (the
// exact columns computed in parallel, one sampled column per task).
Result<double> RecallOf(const LoadedArchive& archive, const std::string& trellis_path,
                        int threads) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                         TrellisFileReader::Open(trellis_path));
  const uint64_t frames = archive.features->frame_count();
  std::vector<uint64_t> sample;
  uint64_t bits = 11;
  for (uint64_t idx = 0; idx < std::min(kRecallColumns, frames); ++idx) {
    bits = bits * 6364136223846793005ull + 1442695040888963407ull;
    sample.push_back((bits >> 17) % frames);
  }
  ExactSearchOptions options;
  options.threads = 1;
  const ExactSearch exact(*archive.features, archive.rules, options);
  std::atomic<uint64_t> exact_total{0}, found{0}, failures{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sample.size(), 1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t idx = range.begin(); idx != range.end(); ++idx) {
                          std::vector<std::vector<Neighbour>> truth;
                          std::vector<std::vector<Neighbour>> stored;
                          SearchStats ignored;
                          if (!exact.SearchColumns(sample[idx], 1, &truth, &ignored).ok() ||
                              !trellis->ReadColumns(sample[idx], 1, &stored).ok()) {
                            ++failures;
                            continue;
                          }
                          uint64_t hits = 0;
                          size_t stored_idx = 0;
                          for (const Neighbour& neighbour : truth[0]) {  // both sorted by frame
                            while (stored_idx < stored[0].size() &&
                                   stored[0][stored_idx].frame < neighbour.frame) {
                              ++stored_idx;
                            }
                            hits += stored_idx < stored[0].size() &&
                                    stored[0][stored_idx].frame == neighbour.frame;
                          }
                          found += hits;
                          exact_total += truth[0].size();
                        }
                      });
  });
  if (failures > 0) return Status::IOError("recall: a sampled column failed");
  return exact_total ? static_cast<double>(found) / static_cast<double>(exact_total) : 1.0;
}

void BM_TrellisBuild(benchmark::State& state, std::string data, TrellisSearchMode mode) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Result<std::string> archive = bench::ArchiveFileOf(data, frames);
  if (!archive.ok()) {
    state.SkipWithError(archive.status().ToString().c_str());
    return;
  }
  const std::string trellis = WorkDir() + "/" + data + "-" + std::to_string(frames) +
                              (mode == TrellisSearchMode::kExact ? "-exact" : "-lsh") + "-t" +
                              std::to_string(threads) + ".mtr";
  TrellisOptions options;
  options.search = mode;
  options.threads = threads;
  double search_cpu_start = 0;
  double search_cpu = 0;
  std::chrono::steady_clock::time_point search_wall_start;
  double search_wall = 0;
  options.progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (stage != "trellis") return;
    if (search_cpu_start == 0) {
      search_cpu_start = ProcessCpuSeconds();
      search_wall_start = std::chrono::steady_clock::now();
    }
    if (done == total) {
      search_cpu = ProcessCpuSeconds() - search_cpu_start;
      search_wall = Seconds(search_wall_start);
    }
  };
  Result<TrellisReport> report = Status::NotFound("not run");
  double baseline = 0;
  double peak = 0;
  double seconds = 0;
  double cpu_seconds = 0;
  for (auto _ : state) {
    RemoveTrellis(trellis);
    baseline = bench::StartMemoryMeasurement();
    const double cpu_start = ProcessCpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    report = BuildTrellis(*archive, trellis, options);
    seconds = Seconds(start);
    cpu_seconds = ProcessCpuSeconds() - cpu_start;
    peak = bench::PeakRssBytes();
    if (!report.ok()) {
      state.SkipWithError(report.status().ToString().c_str());
      RemoveTrellis(trellis);
      return;
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  std::error_code error;
  const double trellis_bytes = static_cast<double>(std::filesystem::file_size(trellis, error));
  const double n = static_cast<double>(frames);
  bench::SetMemoryCounters(state, peak, baseline, frames);
  state.counters["peak_rss_mb"] = peak / (1 << 20);
  state.counters["baseline_rss_mb"] = baseline / (1 << 20);
  state.counters["evaluations_per_column"] = static_cast<double>(report->distance_evaluations) / n;
  state.counters["build_cpu_s"] = cpu_seconds;
  state.counters["features_s"] = report->features_seconds;
  state.counters["eps_s"] = report->eps_seconds;
  state.counters["index_s"] = report->index_seconds;
  state.counters["write_s"] = report->write_seconds;
  state.counters["write_wait_s"] = report->write_wait_seconds;
  state.counters["search_s"] = report->search_seconds;
  state.counters["us_per_column"] = 1e6 * report->search_seconds / n;
  state.counters["search_cpu_per_wall"] = search_wall > 0 ? search_cpu / search_wall : 0;
  state.counters["trellis_bytes_per_frame"] = trellis_bytes / n;
  state.counters["mean_k"] = report->mean_k;
  state.counters["eps"] = report->params.eps;

  // After the build (outside its time and memory): recall, and for LSH the exact build's time.
  Result<LoadedArchive> loaded = LoadFeatures(*archive);
  if (!loaded.ok()) {
    state.SkipWithError(loaded.status().ToString().c_str());
    RemoveTrellis(trellis);
    return;
  }
  loaded->rules.eps = report->params.eps;
  Result<double> recall = RecallOf(*loaded, trellis, threads);
  RemoveTrellis(trellis);
  if (!recall.ok()) {
    state.SkipWithError(recall.status().ToString().c_str());
    return;
  }
  state.counters["recall"] = *recall;
  Result<PerColumn> exact_per_column = ExactSecondsPerColumn(*loaded, threads);
  if (!exact_per_column.ok()) {
    state.SkipWithError(exact_per_column.status().ToString().c_str());
    return;
  }
  const double exact_seconds =
      report->features_seconds + report->eps_seconds + exact_per_column->wall * n;
  // CPU: the exact column search alone (its features and eps stages left out, so a lower bound).
  const double exact_cpu_seconds = exact_per_column->cpu * n;
  state.counters["exact_extrapolated_s"] = exact_seconds;
  state.counters["exact_search_cpu_extrapolated_s"] = exact_cpu_seconds;
  if (mode != TrellisSearchMode::kExact) {
    state.counters["speedup_vs_exact"] = exact_seconds / seconds;
    state.counters["cpu_speedup_vs_exact"] = exact_cpu_seconds / cpu_seconds;
  }
  state.SetLabel(report->params.search_params);
}

// EXTRAPOLATED exact build: features and eps run and timed; the search timed on a sample of
// columns and scaled to N. The reported (manual) time is the extrapolated build time.
void BM_TrellisExactExtrapolated(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Result<std::string> archive = bench::ArchiveFileOf(data, frames);
  if (!archive.ok()) {
    state.SkipWithError(archive.status().ToString().c_str());
    return;
  }
  double features_seconds = 0, eps_seconds = 0, per_column = 0, cpu_per_column = 0, peak = 0;
  double baseline = 0;
  float eps = 0;
  for (auto _ : state) {
    baseline = bench::StartMemoryMeasurement();
    Result<LoadedArchive> loaded = LoadFeatures(*archive);
    if (!loaded.ok()) {
      state.SkipWithError(loaded.status().ToString().c_str());
      return;
    }
    features_seconds = loaded->features_seconds;
    const auto eps_start = std::chrono::steady_clock::now();
    EpsilonOptions eps_options;
    eps_options.seed = 1;
    eps_options.threads = static_cast<uint32_t>(threads);
    Result<EpsilonEstimate> estimate =
        EpsilonEstimator(*loaded->features, loaded->rules, eps_options).Estimate();
    if (!estimate.ok()) {
      state.SkipWithError(estimate.status().ToString().c_str());
      return;
    }
    eps_seconds = Seconds(eps_start);
    eps = estimate->eps;
    loaded->rules.eps = eps;
    Result<PerColumn> exact_per_column = ExactSecondsPerColumn(*loaded, threads);
    if (!exact_per_column.ok()) {
      state.SkipWithError(exact_per_column.status().ToString().c_str());
      return;
    }
    per_column = exact_per_column->wall;
    cpu_per_column = exact_per_column->cpu;
    peak = bench::PeakRssBytes();
    state.SetIterationTime(features_seconds + eps_seconds + per_column * frames);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["extrapolated"] = 1;
  state.counters["sampled_columns"] = static_cast<double>(std::min(frames, kExactSampleColumns));
  state.counters["features_s"] = features_seconds;
  state.counters["eps_s"] = eps_seconds;
  state.counters["us_per_column"] = 1e6 * per_column;
  state.counters["exact_search_cpu_extrapolated_s"] = cpu_per_column * frames;
  state.counters["evaluations_per_column"] = static_cast<double>(frames);
  state.counters["recall"] = 1;
  // Features and the search's blocks: what an exact build holds (it has no index).
  bench::SetMemoryCounters(state, peak, baseline, frames);
  state.counters["eps"] = eps;
  state.SetLabel("EXTRAPOLATED from " + std::to_string(std::min(frames, kExactSampleColumns)) +
                 " timed columns");
}

const bool registered = [] {
  for (const std::string data : {"synth", "resequenced"}) {
    const std::string prefix = "TrellisBuild/" + data;
    std::vector<std::vector<int64_t>> lsh_rows, one_thread_rows, exact_rows, extrapolated_rows;
    for (int64_t frames : bench::ScalingFrames()) {
      lsh_rows.push_back({frames, 2});
      if (frames == (1 << 20)) one_thread_rows.push_back({frames, 1});
      (static_cast<uint64_t>(frames) <= kLargestFullExact ? exact_rows : extrapolated_rows)
          .push_back({frames, 2});
    }
    auto* lsh = bench::RegisterRows(prefix + "/lsh", lsh_rows, BM_TrellisBuild, data,
                                    TrellisSearchMode::kLsh);
    // The 1-thread rows in a family of their own, so that each complexity fit has one count.
    auto* lsh_one_thread = bench::RegisterRows(prefix + "/lsh", one_thread_rows, BM_TrellisBuild,
                                               data, TrellisSearchMode::kLsh);
    auto* exact = bench::RegisterRows(prefix + "/exact", exact_rows, BM_TrellisBuild, data,
                                      TrellisSearchMode::kExact);
    auto* extrapolated = bench::RegisterRows(prefix + "/exact_extrapolated", extrapolated_rows,
                                             BM_TrellisExactExtrapolated, data);
    for (auto* entry : {lsh, lsh_one_thread, exact, extrapolated}) {
      if (entry == nullptr) continue;
      entry->ArgNames({"frames", "threads"})->Unit(benchmark::kSecond)->Iterations(1);
      if (entry == extrapolated) {
        entry->Complexity(benchmark::oNSquared)->UseManualTime();
      } else if (entry == exact) {
        entry->Complexity(benchmark::oNSquared)->UseRealTime();
      } else {
        // oAuto: Google Benchmark picks the best of O(1), O(lg N), O(N), O(N lg N), O(N^2),
        // O(N^3): the claim to check is that the LSH build fits below O(N^2).
        entry->Complexity(benchmark::oAuto)->UseRealTime();
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
