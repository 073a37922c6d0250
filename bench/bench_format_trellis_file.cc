// The trellis spill: writing a matching trellis of N columns to its file (TrellisFileWriter,
// docs/formats/trellis_file.md: varint-coded frames, quantised distances, zstd level 3, a
// checksum and an fsync per 4096-column block, then the block index), as BuildTrellis's writer
// thread does beside the column search, without the search.
//   SpillScale/walk/frames:N/k:256  N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES
//                                   (bench_util.h), one iteration each.
// Columns: the random-walk trellis of bench/bench_trellises.h with K = 256 (real trellises have
// a mean K of 150-250 with k_max 256) and pseudo-random distances in [0.3, 1.0) (a real
// column's distances are anything below eps). Eight distinct blocks are generated before the
// timed loop and written in turn, so the timing is the writer's alone. The file goes to
// $MOTIF_BENCH_DIR/spill (a real disk, fsynced, as a build's) and is removed after each run.
// Items: columns; counters: trellis_bytes_per_frame and the memory counters of bench_util.h (the
// writer holds one encoded block and the block index: flat in N but for 40 bytes a block).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_trellises.h"
#include "bench/bench_util.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {
namespace {

constexpr uint32_t kK = 256;
constexpr uint64_t kBlockColumns = 4096;
constexpr uint64_t kPoolBlocks = 8;

void BM_SpillScale(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  bench::RandomWalkTrellis walk(frames, kK);
  std::vector<std::vector<std::vector<Neighbour>>> pool(kPoolBlocks);
  uint64_t bits = 5;
  for (uint64_t idx = 0; idx < kPoolBlocks; ++idx) {
    const uint64_t first = (idx * kBlockColumns) % frames;
    walk.NextBlock(first, std::min(kBlockColumns, frames - first), &pool[idx]);
    for (std::vector<Neighbour>& column : pool[idx]) {
      for (Neighbour& neighbour : column) {
        bits = bits * 6364136223846793005ull + 1442695040888963407ull;
        neighbour.distance = 0.3f + 0.7f * static_cast<float>(bits >> 40) / (1 << 24);
      }
    }
  }
  const std::string dir = bench::WorkDir() + "/spill";
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  const std::string path = dir + "/spill-" + std::to_string(frames) + ".mtr";
  TrellisParams params;
  params.frame_count = frames;
  params.eps = 1.0f;
  params.k_max = kK;
  params.search_params = "bench spill";
  uint64_t file_bytes = 0;
  const double baseline = bench::StartMemoryMeasurement();
  for (auto _ : state) {
    std::filesystem::remove(path, error);
    auto writer = TrellisFileWriter::OpenOrResume(path, params);
    if (!writer.ok()) {
      state.SkipWithError(writer.status().ToString().c_str());
      return;
    }
    for (uint64_t first = 0, idx = 0; first < frames; first += kBlockColumns, ++idx) {
      std::vector<std::vector<Neighbour>>& block = pool[idx % kPoolBlocks];
      const uint64_t count = std::min(kBlockColumns, frames - first);
      if (block.size() != count) block.resize(count);  // the last block of a short archive
      if (Status status = (*writer)->AppendBlock(block); !status.ok()) {
        state.SkipWithError(status.ToString().c_str());
        return;
      }
    }
    if (Status status = (*writer)->Finish(); !status.ok()) {
      state.SkipWithError(status.ToString().c_str());
      return;
    }
    file_bytes = std::filesystem::file_size(path, error);
  }
  std::filesystem::remove(path, error);
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["trellis_bytes_per_frame"] = static_cast<double>(file_bytes) / frames;
}

const bool registered = [] {
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames, kK});
  if (auto* family = bench::RegisterRows("SpillScale/walk", rows, BM_SpillScale)) {
    family->ArgNames({"frames", "k"})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1)
        ->Complexity(benchmark::oN);
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
