// Path grower throughput: the streaming grower (GrowPaths: one block of the trellis file and one
// O(N) array in memory, O(N·K·B)) against the pairwise reference (GrowPathsReference: the whole
// trellis in memory, O(N·K²)), on synthetic trellis files of N = 2^13, 2^15, 2^17 columns with
// K = 32 .. 1024 nodes a column, B = 5, lambda = 60.
// Items are trellis entries per second. Counters: grower_MB (the grower's own structures: the
// auxiliary array, two columns of leaves, the candidates), peak_rss_MB (the process's peak
// resident set during the runs, which includes the pages of the memory-mapped trellis file the
// reader has touched), candidates.
// The trellises are random walks shaped like real ones: planted paths (runs of 8 consecutive
// frames around a walker that advances 0 to 2 frames a column and lives 100 to 500 columns)
// make up half of each column, uniform random noise nodes the rest. They are written once per
// (N, K) to $TMPDIR (or /tmp) outside the timed loop and removed at exit. The reference is run
// only where it fits: at most 2^24 entries in memory and N·K² at most 2^33.
// Run: bench/bench_engine_grower --benchmark_min_time=0.2s (the command in docs/benchmarks.md).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/grow/path_grower.h"
#include "engine/grow/reference_grower.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {
namespace {

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_grower: %s\n", status.ToString().c_str());
  std::exit(1);
}

// Removes the generated trellis files at exit.
struct TempFiles {
  std::string dir;
  TempFiles() {
    const char* tmp = std::getenv("TMPDIR");
    dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/bench_grower_" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);
  }
  ~TempFiles() {
    std::error_code error;
    std::filesystem::remove_all(dir, error);
  }
};

TempFiles& Files() {
  static TempFiles files;
  return files;
}

// One walker: a planted path through the trellis.
struct Walker {
  uint64_t frame = 0;
  uint64_t columns_left = 0;
};

// Writes the synthetic trellis of N columns, about K nodes each.
std::string TrellisOf(uint64_t frame_count, uint32_t k) {
  static std::map<std::pair<uint64_t, uint32_t>, std::string> paths;
  auto it = paths.find({frame_count, k});
  if (it != paths.end()) return it->second;
  const std::string path = Files().dir + "/t_" + std::to_string(frame_count) + "_" +
                           std::to_string(k) + ".mtr";
  TrellisParams params;
  params.frame_count = frame_count;
  params.eps = 1.0f;
  params.k_max = 2 * k;
  params.search_params = "bench random walk";
  auto writer = TrellisFileWriter::OpenOrResume(path, params);
  if (!writer.ok()) Die(writer.status());
  std::mt19937_64 rng(frame_count * 1000 + k);
  constexpr uint32_t kRun = 8;
  std::vector<Walker> walkers(std::max<uint32_t>(1, k / 2 / kRun));
  auto respawn = [&](Walker* walker) {
    walker->frame = rng() % frame_count;
    walker->columns_left = 100 + rng() % 401;
  };
  for (Walker& walker : walkers) respawn(&walker);
  std::vector<std::vector<Neighbour>> block;
  std::vector<uint32_t> frames;
  const uint32_t block_columns = (*writer)->block_columns();
  for (uint64_t first = 0; first < frame_count; first += block_columns) {
    const uint64_t count = std::min<uint64_t>(block_columns, frame_count - first);
    block.assign(count, {});
    for (uint64_t in_block = 0; in_block < count; ++in_block) {
      frames.clear();
      for (Walker& walker : walkers) {
        for (uint32_t offset = 0; offset < kRun && walker.frame + offset < frame_count; ++offset) {
          frames.push_back(static_cast<uint32_t>(walker.frame + offset));
        }
        walker.frame += rng() % 3;
        if (--walker.columns_left == 0 || walker.frame >= frame_count) respawn(&walker);
      }
      while (frames.size() < k) frames.push_back(static_cast<uint32_t>(rng() % frame_count));
      std::sort(frames.begin(), frames.end());
      frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
      std::vector<Neighbour>& column = block[in_block];
      column.reserve(frames.size());
      for (uint32_t frame : frames) column.push_back({frame, 0.5f});
    }
    Status status = (*writer)->AppendBlock(block);
    if (!status.ok()) Die(status);
  }
  Status status = (*writer)->Finish();
  if (!status.ok()) Die(status);
  return paths[{frame_count, k}] = path;
}

std::vector<uint64_t> ClipStarts(uint64_t frame_count) {
  std::vector<uint64_t> starts;
  for (uint64_t start = 0; start < frame_count; start += 4096) starts.push_back(start);
  return starts;
}

GrowOptions Options() {
  GrowOptions options;
  options.branch = 5;
  options.min_length = 60;
  return options;
}

void BM_StreamingGrower(benchmark::State& state) {
  const uint64_t frame_count = static_cast<uint64_t>(state.range(0));
  const uint32_t k = static_cast<uint32_t>(state.range(1));
  const std::string path = TrellisOf(frame_count, k);
  auto reader = TrellisFileReader::Open(path);
  if (!reader.ok()) Die(reader.status());
  const std::vector<uint64_t> clips = ClipStarts(frame_count);
  GrowStats stats;
  size_t candidates = 0;
  bench::ResetPeakRss();
  for (auto _ : state) {
    auto result = GrowPaths(**reader, clips, Options(), nullptr, &stats);
    if (!result.ok()) Die(result.status());
    candidates = result->size();
    benchmark::DoNotOptimize(result->data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (*reader)->neighbour_count()));
  state.counters["mean_k"] =
      static_cast<double>((*reader)->neighbour_count()) / static_cast<double>(frame_count);
  state.counters["grower_MB"] = static_cast<double>(stats.memory_bytes) / 1e6;
  state.counters["peak_rss_MB"] = bench::PeakRssBytes() / 1e6;
  state.counters["candidates"] = static_cast<double>(candidates);
}

void BM_ReferenceGrower(benchmark::State& state) {
  const uint64_t frame_count = static_cast<uint64_t>(state.range(0));
  const uint32_t k = static_cast<uint32_t>(state.range(1));
  const std::string path = TrellisOf(frame_count, k);
  auto reader = TrellisFileReader::Open(path);
  if (!reader.ok()) Die(reader.status());
  // The reference's input is the trellis in memory: read it once, outside the timed loop.
  std::vector<std::vector<Neighbour>> columns;
  Status status = (*reader)->ReadColumns(0, frame_count, &columns);
  if (!status.ok()) Die(status);
  const std::vector<uint64_t> clips = ClipStarts(frame_count);
  size_t candidates = 0;
  bench::ResetPeakRss();
  for (auto _ : state) {
    auto result = GrowPathsReference(columns, clips, Options());
    if (!result.ok()) Die(result.status());
    candidates = result->size();
    benchmark::DoNotOptimize(result->data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (*reader)->neighbour_count()));
  state.counters["mean_k"] =
      static_cast<double>((*reader)->neighbour_count()) / static_cast<double>(frame_count);
  state.counters["peak_rss_MB"] = bench::PeakRssBytes() / 1e6;
  state.counters["candidates"] = static_cast<double>(candidates);
}

const bool registered = [] {
  for (int64_t frames : {int64_t{1} << 13, int64_t{1} << 15, int64_t{1} << 17}) {
    for (int64_t k : {32, 128, 512, 1024}) {
      benchmark::RegisterBenchmark("StreamingGrower", BM_StreamingGrower)
          ->Args({frames, k})
          ->ArgNames({"frames", "k"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (int64_t frames : {int64_t{1} << 13, int64_t{1} << 15, int64_t{1} << 17}) {
    for (int64_t k : {32, 128, 512, 1024}) {
      const double entries = static_cast<double>(frames) * static_cast<double>(k);
      if (entries > static_cast<double>(1 << 24) ||
          entries * static_cast<double>(k) > static_cast<double>(uint64_t{1} << 33)) {
        continue;
      }
      benchmark::RegisterBenchmark("ReferenceGrower", BM_ReferenceGrower)
          ->Args({frames, k})
          ->ArgNames({"frames", "k"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
