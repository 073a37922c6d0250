// Import throughput on the real CMU takes (../shared/data/mocap or $MOTIF_MOCAP_DIR; skipped when
// absent): parsing and converting BVH and ASF/AMC files (frames and source bytes per second), and
// the whole `import` pipeline into a fresh archive with 1 and 2 threads. The files are read from
// the page cache after the first iteration, so this measures parsing, not the disk.
//
// ImportScale/real/frames:N (scripts/bench.sh): import's work per take (parse, map onto the
// first take's skeleton, resample to 120 fps, convert to rows, append to the archive: the steps
// of ImportIntoArchive) over the 62 BVH takes cycled until N frames, one thread, into a fresh
// archive in $TMPDIR; N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES. ImportIntoArchive itself
// skips a take already in the archive (same content hash), so it cannot grow past the takes'
// 40,346 frames; the repeats here get new clip names and are otherwise the same clips.
// Items: frames; the memory counters of bench_util.h (one take in memory at a time: flat in N).
#include <unistd.h>

#include <filesystem>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/ingest/archive_import.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/resample.h"

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

// Appends the BVH takes, cycled, to a new archive at `path` until it holds `frames` frames (the
// last clip cut to fit). Returns the archive's size in bytes.
Result<uint64_t> ImportCycled(const std::vector<TakeSource>& sources, uint64_t frames,
                              const std::string& path) {
  std::error_code error;
  std::filesystem::remove(path, error);
  std::unique_ptr<FrameFileWriter> writer;
  Skeleton skeleton;
  uint64_t written = 0;
  for (uint64_t cycle = 0; written < frames; ++cycle) {
    for (size_t idx = 0; idx < sources.size() && written < frames; ++idx) {
      MOTIF_ASSIGN_OR_RETURN(Take take, ImportTake(sources[idx], ImportOptions()));
      if (!writer) {
        skeleton = take.skeleton;
        MOTIF_ASSIGN_OR_RETURN(writer, FrameFileWriter::Create(path, skeleton, 120.0));
      }
      if (!ConformToSkeleton(skeleton, &take).ok() || take.frame_count() == 0) continue;
      ClipFrames clip = TakeToClipFrames(ResampleTake(take, 120.0));
      const uint64_t stride = clip.rows.size() / clip.info.frame_count;
      if (written + clip.info.frame_count > frames) {
        clip.info.frame_count = frames - written;
        clip.rows.resize(clip.info.frame_count * stride);
      }
      if (cycle > 0) {  // two appends: GCC 12 warns (-Wrestrict, wrongly) on "~" + to_string
        clip.info.name += '~';
        clip.info.name += std::to_string(cycle + 1);
      }
      MOTIF_RETURN_IF_ERROR(writer->AppendClip(clip));
      written += clip.info.frame_count;
    }
  }
  MOTIF_RETURN_IF_ERROR(writer->Commit());
  return static_cast<uint64_t>(std::filesystem::file_size(path, error));
}

void BM_ImportScale(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const std::string mocap = bench::MocapDir();
  if (mocap.empty()) {
    state.SkipWithError("real CMU takes not found: set MOTIF_MOCAP_DIR");
    return;
  }
  auto sources = DiscoverTakes({mocap + "/bvh"}, ImportOptions());
  if (!sources.ok()) {
    state.SkipWithError(sources.status().ToString().c_str());
    return;
  }
  const std::string path = std::filesystem::temp_directory_path().string() +
                           "/motifmine-bench-import-scale-" + std::to_string(::getpid()) + ".mfs";
  uint64_t archive_bytes = 0;
  const double baseline = bench::StartMemoryMeasurement();
  for (auto _ : state) {
    Result<uint64_t> bytes = ImportCycled(*sources, frames, path);
    if (!bytes.ok()) {
      state.SkipWithError(bytes.status().ToString().c_str());
      break;
    }
    archive_bytes = *bytes;
  }
  std::error_code error;
  std::filesystem::remove(path, error);
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["archive_bytes_per_frame"] = static_cast<double>(archive_bytes) / frames;
}

const bool scale_registered = [] {
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames});
  if (auto* family = bench::RegisterRows("ImportScale/real", rows, BM_ImportScale)) {
    family->ArgName("frames")
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
