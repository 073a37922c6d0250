// Path grower throughput: the streaming grower (GrowPaths: one block of the trellis file and one
// O(N) array in memory, O(N·K·B)) against the pairwise reference (GrowPathsReference: the whole
// trellis in memory, O(N·K²)), on synthetic trellis files with B = 5, lambda = 60.
//
// Three series:
// * StreamingGrowerScaling/frames:N/k:256: the streaming grower against N = 2^13, 2^15, 2^17,
//   2^20, 2^22 and 10^7 at a fixed K, with a complexity fit (oN). Sizes above
//   $MOTIF_BENCH_GROWER_MAX (default 2^17, so that a plain run stays quick; 10000000 or 1e7 for
//   the whole series) are not registered. K = 256: real trellises have a mean K of 150 to 250
//   with k_max 256, so 256 is the top of the real range, the most entries and the largest
//   decoded block per column: the throughput and memory measured are not flattered (128 would
//   sit below every real trellis).
// * StreamingGrowerKeepPages/...: the same sizes and loop, but without giving the pages of the
//   blocks read back to the kernel (GrowPaths before TrellisFileReader::ReleaseBlocks): its
//   peak RSS grows with the trellis file, not with N.
// * StreamingGrower and ReferenceGrower/frames:N/k:K: the K sweep, K = 32 .. 1024 at
//   N = 2^13, 2^15, 2^17, both growers on the same files. The reference runs only where it
//   fits: at most 2^25 entries in memory (~256 MB) and N·K² at most 2^33.
// Items are trellis entries per second (wall time). Counters: entries_per_cpu_s (the same per
// second of this thread's CPU: the machines are shared), grower_MB (the grower's own
// structures: the auxiliary array, two columns of leaves, the tree table, the candidates),
// peak_rss_MB (the process's peak resident set during the timed runs, VmHWM after a reset),
// base_rss_MB (the resident set when the timed runs start, after malloc_trim: the process and
// what earlier runs left, such as the block decoder's scratch), peak_rss_B_per_frame and
// grower_B_per_frame (per column of the trellis), file_MB, candidates.
// Trellises: random walks shaped like real ones: planted paths (runs of 8 consecutive frames
// around a walker that advances 0 to 2 frames a column and lives 100 to 500 columns) make up
// half of each column, uniform random noise nodes the rest; clips of 4096 frames. Each (N, K) is
// written once to $TMPDIR (or /tmp) outside the timed loop, with the next block generated on a
// second thread while the writer encodes the current one, and without fsync (throwaway data);
// the files are removed at exit. 10^7 columns at K = 256 are 2.56 billion entries, a 4.2 GB
// file (with 2^22, ~6 GB in $TMPDIR), read from the page cache where memory allows (the runs
// measure decoding and growing, not the disk).
// * GrowScale/streaming and GrowScale/reference/frames:N/k:256: the scaling series of
//   scripts/bench.sh, N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES (the reference up to
//   2^20), one iteration each, with the memory counters of bench_util.h.
// Run: bench/bench_engine_grower --benchmark_min_time=0.2 (the commands in docs/benchmarks.md).
#include <malloc.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_trellises.h"
#include "bench/bench_util.h"
#include "common/writable_file.h"
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

using bench::RandomWalkTrellis;

// Writes the synthetic trellis of N columns, about K nodes each (once per (N, K)).
std::string TrellisOf(uint64_t frame_count, uint32_t k) {
  static std::map<std::pair<uint64_t, uint32_t>, std::string> paths;
  auto it = paths.find({frame_count, k});
  if (it != paths.end()) return it->second;
  const std::string path =
      Files().dir + "/t_" + std::to_string(frame_count) + "_" + std::to_string(k) + ".mtr";
  TrellisParams params;
  params.frame_count = frame_count;
  params.eps = 1.0f;
  params.k_max = 2 * k;
  params.search_params = "bench random walk";
  TrellisFileWriterOptions options;
  options.file_system = NoSyncFileSystem();  // throwaway files
  auto writer = TrellisFileWriter::OpenOrResume(path, params, options);
  if (!writer.ok()) Die(writer.status());
  const uint64_t block_columns = (*writer)->block_columns();
  RandomWalkTrellis trellis(frame_count, k);
  // Two buffers: block b + 1 is generated on another thread while block b is encoded and
  // written (the generator is sequential, so only these two stages overlap).
  std::vector<std::vector<Neighbour>> buffers[2];
  trellis.NextBlock(0, std::min(block_columns, frame_count), &buffers[0]);
  for (uint64_t block_idx = 0; block_idx * block_columns < frame_count; ++block_idx) {
    const uint64_t next_first = (block_idx + 1) * block_columns;
    std::future<void> next;
    if (next_first < frame_count) {
      next = std::async(std::launch::async, [&, next_first, block_idx] {
        trellis.NextBlock(next_first, std::min(block_columns, frame_count - next_first),
                          &buffers[(block_idx + 1) % 2]);
      });
    }
    Status status = (*writer)->AppendBlock(buffers[block_idx % 2]);
    if (next.valid()) next.get();
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

// CPU seconds of the calling thread (the growers are single-threaded).
double ThreadCpuSeconds() {
  timespec now;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

// Gives freed heap (the generator's and earlier benchmarks' buffers) back to the kernel and
// resets the peak-RSS mark: returns the resident set the timed runs start from.
double StartPeakRss() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
  bench::ResetPeakRss();
  return bench::PeakRssBytes();
}

// GrowPaths as it was before TrellisFileReader::ReleaseBlocks: the same block loop, keeping the
// pages of the blocks read mapped.
Result<std::vector<PathCandidate>> GrowKeepingPages(const TrellisFileReader& trellis,
                                                    const std::vector<uint64_t>& clip_starts,
                                                    const GrowOptions& options, GrowStats* stats) {
  auto grower = PathGrower::Create(trellis.column_count(), clip_starts, options);
  if (!grower.ok()) return grower.status();
  TrellisBlock block;
  for (uint64_t block_idx = 0; block_idx < trellis.block_count(); ++block_idx) {
    MOTIF_RETURN_IF_ERROR(trellis.ReadBlock(block_idx, &block, /*decode_distances=*/false));
    for (uint32_t in_block = 0; in_block < block.column_count; ++in_block) {
      const uint32_t begin = block.offsets[in_block];
      MOTIF_RETURN_IF_ERROR((*grower)->AddColumn(block.neighbours.data() + begin,
                                                 block.offsets[in_block + 1] - begin));
    }
  }
  const uint64_t memory_bytes = (*grower)->memory_bytes();
  auto candidates = (*grower)->Finish();
  *stats = (*grower)->stats();
  stats->memory_bytes = memory_bytes;
  return candidates;
}

enum class Pages { kRelease, kKeep };

void RunStreaming(benchmark::State& state, Pages pages) {
  const uint64_t frame_count = static_cast<uint64_t>(state.range(0));
  const uint32_t k = static_cast<uint32_t>(state.range(1));
  const std::string path = TrellisOf(frame_count, k);
  auto reader = TrellisFileReader::Open(path);
  if (!reader.ok()) Die(reader.status());
  const std::vector<uint64_t> clips = ClipStarts(frame_count);
  GrowStats stats;
  size_t candidates = 0;
  const double base_rss_bytes = StartPeakRss();
  const double cpu_start = ThreadCpuSeconds();
  for (auto _ : state) {
    auto result = pages == Pages::kRelease ? GrowPaths(**reader, clips, Options(), nullptr, &stats)
                                           : GrowKeepingPages(**reader, clips, Options(), &stats);
    if (!result.ok()) Die(result.status());
    candidates = result->size();
    benchmark::DoNotOptimize(result->data());
  }
  const double cpu_seconds = ThreadCpuSeconds() - cpu_start;
  const double peak_rss_bytes = bench::PeakRssBytes();
  const double entries = static_cast<double>((*reader)->neighbour_count());
  const double frames = static_cast<double>(frame_count);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (*reader)->neighbour_count()));
  state.SetComplexityN(static_cast<int64_t>(frame_count));
  state.counters["mean_k"] = entries / frames;
  state.counters["entries_per_cpu_s"] =
      entries * static_cast<double>(state.iterations()) / cpu_seconds;
  state.counters["grower_MB"] = static_cast<double>(stats.memory_bytes) / 1e6;
  state.counters["grower_B_per_frame"] = static_cast<double>(stats.memory_bytes) / frames;
  state.counters["base_rss_MB"] = base_rss_bytes / 1e6;
  state.counters["peak_rss_MB"] = peak_rss_bytes / 1e6;
  state.counters["peak_rss_B_per_frame"] = peak_rss_bytes / frames;
  bench::SetMemoryCounters(state, peak_rss_bytes, base_rss_bytes, frame_count);
  state.counters["file_MB"] = static_cast<double>((*reader)->file_bytes()) / 1e6;
  state.counters["candidates"] = static_cast<double>(candidates);
}

void BM_StreamingGrower(benchmark::State& state) { RunStreaming(state, Pages::kRelease); }
void BM_StreamingGrowerKeepPages(benchmark::State& state) { RunStreaming(state, Pages::kKeep); }

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
  const double base_rss_bytes = StartPeakRss();
  const double cpu_start = ThreadCpuSeconds();
  for (auto _ : state) {
    auto result = GrowPathsReference(columns, clips, Options());
    if (!result.ok()) Die(result.status());
    candidates = result->size();
    benchmark::DoNotOptimize(result->data());
  }
  const double cpu_seconds = ThreadCpuSeconds() - cpu_start;
  const double entries = static_cast<double>((*reader)->neighbour_count());
  const double peak_rss_bytes = bench::PeakRssBytes();
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (*reader)->neighbour_count()));
  state.SetComplexityN(static_cast<int64_t>(frame_count));
  state.counters["mean_k"] = entries / static_cast<double>(frame_count);
  state.counters["entries_per_cpu_s"] =
      entries * static_cast<double>(state.iterations()) / cpu_seconds;
  state.counters["base_rss_MB"] = base_rss_bytes / 1e6;
  state.counters["peak_rss_MB"] = peak_rss_bytes / 1e6;
  bench::SetMemoryCounters(state, peak_rss_bytes, base_rss_bytes, frame_count);
  state.counters["candidates"] = static_cast<double>(candidates);
}

// $MOTIF_BENCH_GROWER_MAX: the largest N of the StreamingGrowerScaling series (default 2^17).
int64_t GrowerScalingMaxFrames() { return bench::FramesFromEnv("MOTIF_BENCH_GROWER_MAX", 1 << 17); }

constexpr int64_t kScalingK = 256;
constexpr int64_t kLargestScaleReference = 1 << 20;

const bool registered = [] {
  const int64_t max_frames = GrowerScalingMaxFrames();
  using Function = void (*)(benchmark::State&);
  const std::pair<const char*, Function> kScalingSeries[] = {
      {"StreamingGrowerScaling", BM_StreamingGrower},
      {"StreamingGrowerKeepPages", BM_StreamingGrowerKeepPages}};
  for (const auto& [name, function] : kScalingSeries) {
    benchmark::internal::Benchmark* scaling = benchmark::RegisterBenchmark(name, function);
    for (int64_t frames : {int64_t{1} << 13, int64_t{1} << 15, int64_t{1} << 17, int64_t{1} << 20,
                           int64_t{1} << 22, int64_t{10'000'000}}) {
      if (frames <= max_frames) scaling->Args({frames, kScalingK});
    }
    scaling->ArgNames({"frames", "k"})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Complexity(benchmark::oN);
  }
  // The scaling series of scripts/bench.sh (N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES,
  // K = 256): the streaming grower, and the reference while its input (the whole trellis, 8
  // bytes an entry: 2 GB at 2^20) is practical; scripts/bench.sh extrapolates it above.
  std::vector<std::vector<int64_t>> grow_rows, reference_rows;
  for (int64_t frames : bench::ScalingFrames()) {
    grow_rows.push_back({frames, kScalingK});
    if (frames <= kLargestScaleReference) reference_rows.push_back({frames, kScalingK});
  }
  for (auto [name, rows, function] :
       {std::tuple{"GrowScale/streaming", grow_rows, &BM_StreamingGrower},
        std::tuple{"GrowScale/reference", reference_rows, &BM_ReferenceGrower}}) {
    if (auto* family = bench::RegisterRows(name, rows, function)) {
      family->ArgNames({"frames", "k"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(1)
          ->Complexity(benchmark::oN);
    }
  }
  constexpr int64_t kSweepFrames[] = {int64_t{1} << 13, int64_t{1} << 15, int64_t{1} << 17};
  constexpr int64_t kSweepK[] = {32, 128, 256, 512, 1024};
  for (int64_t frames : kSweepFrames) {
    for (int64_t k : kSweepK) {
      benchmark::RegisterBenchmark("StreamingGrower", BM_StreamingGrower)
          ->Args({frames, k})
          ->ArgNames({"frames", "k"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (int64_t frames : kSweepFrames) {
    for (int64_t k : kSweepK) {
      const double entries = static_cast<double>(frames) * static_cast<double>(k);
      if (entries > static_cast<double>(1 << 25) ||
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
