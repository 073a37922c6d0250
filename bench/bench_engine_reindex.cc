// The cost of a nightly `motifmine reindex`: 1 % new frames appended to an archive of
// N frames and the mined output brought up to date (Reindex, engine/reindex/reindexer.h: import,
// incremental trellis update, paths, motifs), against a full rebuild over the same archive: the
// trellis with the same eps, seed and LSH family, the paths and the motifs, what `motifmine
// mine ARCHIVE --eps E --hashes H --width W` does. Target: at most a tenth. Figures:
// docs/benchmarks.md, "Incremental reindexing".
//
// Setup, untimed, in $TMPDIR: a procedural archive of N frames (MotionSynthesizer, seed 7, the
// `motifmine synth` defaults), two batches of new takes of N/100 frames each (synthesizers of
// seeds 8 and 9, clips of 20 to 40 s, written as BVH files), Reindex's first (full) build, and
// the first batch imported by an incremental run, which leaves the search cache with its
// thresholds: the steady state of a nightly job.
// Timed (manual time, one iteration): the second batch's incremental run, import included.
// Then, untimed, the full rebuild over the archive as it now is; its time gives the ratio.
// Counters: incremental_s and full_s (wall), incremental_cpu_s and full_cpu_s (the process's
// user + system time over all threads), ratio_wall and ratio_cpu, new_frames, changed_columns,
// rewritten_blocks, shared_entries (the share of trellis entries the incremental and the full
// trellis have in common), incremental_{import,trellis,grow,cluster,report}_s (the incremental
// run's stages, wall). Arguments: frames, threads. Files are removed afterwards.
// docs/benchmarks.md, "Incremental reindexing", has the figures and the command.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/cli/clip_range_take.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/reindex/reindex_plan.h"
#include "engine/reindex/reindexer.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/export/bvh_writer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_reindex: %s\n", status.ToString().c_str());
  std::exit(1);
}

template <typename T>
T Check(Result<T> result) {
  if (!result.ok()) Die(result.status());
  return std::move(*result);
}

void Check(const Status& status) {
  if (!status.ok()) Die(status);
}

using bench::ProcessCpuSeconds;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A synthetic archive of `frames` frames at `path`.
void WriteArchive(const std::string& path, const SynthOptions& options) {
  auto synthesizer = Check(MotionSynthesizer::Create(options));
  auto writer = Check(FrameFileWriter::Create(path, synthesizer->skeleton(), options.fps));
  Check(synthesizer->Run([&](const ClipFrames& clip) { return writer->AppendClip(clip); }));
  Check(writer->Commit());
}

// `frames` frames of new takes as BVH files in `dir` (an archive of its own, exported).
void WriteTakes(const std::string& dir, uint64_t frames, uint64_t seed) {
  SynthOptions options;
  options.frames = frames;
  options.motifs = 0;
  options.seed = seed;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 40;
  options.background_variation_degrees = kRecommendedBackgroundVariation;
  const std::string archive = dir + ".mfs";
  WriteArchive(archive, options);
  auto reader = Check(FrameFileReader::Open(archive));
  fs::create_directories(dir);
  for (const ClipInfo& clip : reader->clips()) {
    const Take take = Check(ReadClipRangeAsTake(*reader, clip, 0, clip.frame_count));
    Check(WriteBvh(take, dir + "/" + std::to_string(seed) + "_" + clip.name + ".bvh"));
  }
}

// The share of entries (column, frame) two trellises of the same archive have in common, of
// the larger one's.
double SharedEntries(const std::string& a_path, const std::string& b_path) {
  auto a = Check(TrellisFileReader::Open(a_path));
  auto b = Check(TrellisFileReader::Open(b_path));
  uint64_t shared = 0;
  TrellisBlock a_block, b_block;
  for (uint64_t block_idx = 0; block_idx < a->block_count(); ++block_idx) {
    Check(a->ReadBlock(block_idx, &a_block, /*decode_distances=*/false));
    Check(b->ReadBlock(block_idx, &b_block, /*decode_distances=*/false));
    for (uint32_t column = 0; column < a_block.column_count; ++column) {
      auto x = a_block.neighbours.begin() + a_block.offsets[column];
      const auto x_end = a_block.neighbours.begin() + a_block.offsets[column + 1];
      auto y = b_block.neighbours.begin() + b_block.offsets[column];
      const auto y_end = b_block.neighbours.begin() + b_block.offsets[column + 1];
      while (x != x_end && y != y_end) {
        if (x->frame == y->frame) {
          ++shared;
          ++x;
          ++y;
        } else if (x->frame < y->frame) {
          ++x;
        } else {
          ++y;
        }
      }
    }
    Check(a->ReleaseBlocks(block_idx, block_idx + 1));
    Check(b->ReleaseBlocks(block_idx, block_idx + 1));
  }
  return static_cast<double>(shared) /
         static_cast<double>(std::max(a->neighbour_count(), b->neighbour_count()));
}

void BM_ReindexOnePercent(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const char* tmp = std::getenv("TMPDIR");
  const std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/bench_engine_reindex." +
                          std::to_string(::getpid());
  fs::create_directories(dir);
  SynthOptions base;
  base.frames = frames;
  base.motifs = 20;
  base.seed = 7;
  base.background_variation_degrees = kRecommendedBackgroundVariation;
  const std::string archive = dir + "/archive.mfs";
  WriteArchive(archive, base);
  WriteTakes(dir + "/first", frames / 100, 8);
  WriteTakes(dir + "/second", frames / 100, 9);
  fs::create_directories(dir + "/incoming");

  ReindexOptions options;
  options.archive_path = archive;
  options.watch_dir = dir + "/incoming";
  options.out_dir = dir + "/out";
  options.min_age_seconds = 0;
  options.mine.write_report = false;
  options.mine.threads = threads;
  Check(Reindex(options).status());  // the first, full build
  for (const auto& take : fs::directory_iterator(dir + "/first")) {
    fs::copy_file(take.path(), dir + "/incoming/" + take.path().filename().string());
  }
  Check(Reindex(options).status());  // the first night: thresholds into the cache

  for (auto _ : state) {
    for (const auto& take : fs::directory_iterator(dir + "/second")) {
      fs::copy_file(take.path(), dir + "/incoming/" + take.path().filename().string());
    }
    const double cpu_start = ProcessCpuSeconds();
    const Clock::time_point start = Clock::now();
    const ReindexReport night = Check(Reindex(options));
    const double incremental_s = SecondsSince(start);
    const double incremental_cpu_s = ProcessCpuSeconds() - cpu_start;
    state.SetIterationTime(incremental_s);
    if (night.manifest.build.kind != "incremental") {
      Die(Status::InvalidArgument("the second night was a " + night.manifest.build.kind +
                                  " build, not an incremental one"));
    }

    // The full rebuild over the same archive with the recorded parameters (untimed).
    const MiningParams& params = night.manifest.params;
    const double full_cpu_start = ProcessCpuSeconds();
    const Clock::time_point full_start = Clock::now();
    motifmine::MineOptions rebuild;
    rebuild.threads = threads;
    rebuild = RecordedOptions(params, rebuild);
    rebuild.out_dir = dir + "/full";
    rebuild.write_report = false;
    const MinePipelineResult full = Check(RunMine(rebuild, {archive}));
    const std::string full_trellis = dir + "/full/trellis.mtr";
    const double full_s = SecondsSince(full_start);
    const double full_cpu_s = ProcessCpuSeconds() - full_cpu_start;

    state.counters["incremental_s"] = incremental_s;
    state.counters["full_s"] = full_s;
    state.counters["incremental_cpu_s"] = incremental_cpu_s;
    state.counters["full_cpu_s"] = full_cpu_s;
    state.counters["ratio_wall"] = incremental_s / full_s;
    state.counters["ratio_cpu"] = incremental_cpu_s / full_cpu_s;
    state.counters["new_frames"] = static_cast<double>(night.manifest.build.new_frames);
    state.counters["changed_columns"] = static_cast<double>(night.manifest.build.changed_columns);
    state.counters["rewritten_blocks"] = static_cast<double>(night.manifest.build.rewritten_blocks);
    // Where the incremental run's time goes (wall seconds of Reindex's stages).
    state.counters["incremental_import_s"] = night.import_seconds;
    state.counters["incremental_trellis_s"] = night.trellis_seconds;
    state.counters["incremental_grow_s"] = night.grow_seconds;
    state.counters["incremental_cluster_s"] = night.cluster_seconds;
    state.counters["incremental_report_s"] = night.report_seconds;
    state.counters["shared_entries"] =
        SharedEntries(options.out_dir + "/" + night.manifest.trellis.path, full_trellis);
  }
  std::error_code error;
  fs::remove_all(dir, error);
}

BENCHMARK(BM_ReindexOnePercent)
    ->ArgNames({"frames", "threads"})
    ->Args({100000, 2})
    ->Args({1000000, 2})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
