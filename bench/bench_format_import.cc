// Import throughput on the real CMU takes (../shared/data/mocap or $MOTIF_MOCAP_DIR; skipped when
// absent): parsing and converting BVH and ASF/AMC files (frames and source bytes per second), and
// the whole `import` pipeline into a fresh archive with 1 and 2 threads. The files are read from
// the page cache after the first iteration, so this measures parsing, not the disk.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/ingest/archive_import.h"
#include "formats/import/take_importer.h"

namespace motif {
namespace {

void ParseFolder(benchmark::State& state, const std::string& folder) {
  const std::string mocap = bench::MocapDir();
  if (mocap.empty()) {
    state.SkipWithError("real CMU takes not found: set MOTIF_MOCAP_DIR");
    return;
  }
  ImportOptions options;
  auto sources = DiscoverTakes({mocap + "/" + folder}, options);
  if (!sources.ok()) {
    state.SkipWithError(sources.status().ToString().c_str());
    return;
  }
  uint64_t frames = 0;
  uint64_t bytes = 0;
  for (auto _ : state) {
    frames = 0;
    bytes = 0;
    for (const TakeSource& source : *sources) {
      auto take = ImportTake(source, options);
      if (!take.ok()) {
        state.SkipWithError(take.status().ToString().c_str());
        return;
      }
      frames += take->frame_count();
      bytes += std::filesystem::file_size(source.path);
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
  state.counters["frames"] = static_cast<double>(frames);
}

void BM_ImportParseBvh(benchmark::State& state) { ParseFolder(state, "bvh"); }
BENCHMARK(BM_ImportParseBvh)->Name("Import/Parse/bvh")->Unit(benchmark::kMillisecond);

void BM_ImportParseAmc(benchmark::State& state) { ParseFolder(state, "asfamc"); }
BENCHMARK(BM_ImportParseAmc)->Name("Import/Parse/asfamc")->Unit(benchmark::kMillisecond);

void BM_ImportIntoArchive(benchmark::State& state) {
  const std::string mocap = bench::MocapDir();
  if (mocap.empty()) {
    state.SkipWithError("real CMU takes not found: set MOTIF_MOCAP_DIR");
    return;
  }
  const std::string path = std::filesystem::temp_directory_path().string() +
                           "/motifmine-bench-import-" + std::to_string(::getpid()) + ".mfs";
  ArchiveImportOptions options;
  options.threads = static_cast<int>(state.range(0));
  uint64_t frames = 0;
  uint64_t archive_bytes = 0;
  for (auto _ : state) {
    std::filesystem::remove(path);
    auto result = ImportIntoArchive(path, {mocap + "/bvh", mocap + "/asfamc"}, options);
    if (!result.ok()) {
      state.SkipWithError(result.status().ToString().c_str());
      return;
    }
    frames = result->archive_frames;
    archive_bytes = std::filesystem::file_size(path);
  }
  std::filesystem::remove(path);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.counters["archive_bytes"] = static_cast<double>(archive_bytes);
}
BENCHMARK(BM_ImportIntoArchive)
    ->Name("Import/IntoArchive/bvh+asfamc")
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
