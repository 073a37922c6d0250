// The whole `motifmine words` job (BuildWords, engine/words/words_builder.h) against the number
// of words, on synthetic archives of N frames: the training pool and its DTW neighbours, the
// triplet training, every word embedded (streamed from the archive), k-means into 100 motifs
// and the signatures, with the defaults of `motifmine words` (30 epochs, a pool of at most 30,000
// words with 2 warped copies each, k = 100, seed 1) on 2 threads.
//   WordsBuild/synth/frames:N/threads:2   N = 2^17, 2^19 (and 2^21, 10^7 with
//                                          MOTIF_BENCH_WORDS_MAX >= 10000000)
// The archives are what `motifmine synth ARCHIVE --frames N --motifs 20 --seed 7` writes
// (MotionSynthesizer, procedural motion at 120 fps, clips of 20 to 60 s), made once in
// $MOTIF_BENCH_DIR (default /tmp/motifmine-bench/words) as synth-<N>.mfs and reused; the words
// files are deleted before and after each run, so every run trains from scratch.
// At 120 fps a word starts every 20 frames: N / 20 words, minus each clip's tail.
//
// Counters (items per second = words per second of the whole job, wall time):
//   words, pool_words             the archive's words, and the words trained on (the pool)
//   pool_s, neighbours_s, train_s, embed_s, kmeans_s, signatures_s   the stages (wall)
//   cpu_s                         the process's CPU seconds for the job (user + system), which
//                                 a machine shared with other jobs disturbs far less than wall
//   peak_rss_mb                   the peak resident set (VmHWM, reset before the job); it
//                                 includes the baseline (baseline_rss_mb), so run one size per
//                                 process (scripts/bench_words.sh does)
//   peak_rss_bytes_per_word       peak_rss over words
// Left out: writing the synthetic archive (outside the timed loop), the disk (the archive is
// read from the page cache where memory allows).
// Run: scripts/bench_words.sh [quick|full] (the commands in docs/benchmarks.md).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/synthetic_archive.h"
#include "engine/words/words_builder.h"
#include "formats/frame_file/frame_file_writer.h"

namespace motif {
namespace {

uint64_t MaxFrames() {
  const char* text = std::getenv("MOTIF_BENCH_WORDS_MAX");
  return text && *text ? static_cast<uint64_t>(std::strtod(text, nullptr)) : (1u << 19);
}

std::string BenchDir() {
  const char* text = std::getenv("MOTIF_BENCH_DIR");
  return (text && *text ? std::string(text) : std::string("/tmp/motifmine-bench")) + "/words";
}

// The archive of `frames` frames, written once (as `motifmine synth --motifs 20 --seed 7` with
// clips of 20 to 60 s) and reused.
Result<std::string> Archive(uint64_t frames) {
  const std::string dir = BenchDir();
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/synth-" + std::to_string(frames) + ".mfs";
  if (std::filesystem::exists(path)) return path;
  SynthOptions options;
  options.frames = frames;
  options.motifs = 20;
  options.seed = 7;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 60;
  options.threads = 2;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         MotionSynthesizer::Create(options));
  MOTIF_RETURN_IF_ERROR(
      WriteSyntheticArchive(path, *synthesizer, options, FrameFileWriterOptions{}.block_frames)
          .status());
  return path;
}

void RemoveWordsFiles(const WordsPaths& paths) {
  for (const std::string& path : {paths.embedding, paths.motifs, paths.signatures,
                                  paths.embedding + ".checkpoint", paths.signatures + ".lock"}) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
}

void BM_WordsBuild(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Result<std::string> archive = Archive(frames);
  if (!archive.ok()) {
    state.SkipWithError(archive.status().ToString().c_str());
    return;
  }
  const WordsPaths paths = DefaultWordsPaths(*archive);
  WordsOptions options;
  options.threads = threads;
  Result<WordsReport> report = Status::InvalidArgument("not run");
  double cpu = 0, peak = 0, baseline = 0;
  for (auto _ : state) {
    RemoveWordsFiles(paths);
    bench::ResetPeakRss();
    baseline = bench::PeakRssBytes();
    const double cpu_start = bench::ProcessCpuSeconds();
    report = BuildWords(*archive, paths, options);
    cpu = bench::ProcessCpuSeconds() - cpu_start;
    peak = bench::PeakRssBytes();
    if (!report.ok()) {
      state.SkipWithError(report.status().ToString().c_str());
      return;
    }
  }
  RemoveWordsFiles(paths);
  const double words = static_cast<double>(report->words);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * report->words));
  state.SetComplexityN(static_cast<int64_t>(report->words));
  state.counters["words"] = words;
  state.counters["pool_words"] = static_cast<double>(report->pool_words);
  state.counters["pool_s"] = report->seconds_pool;
  state.counters["neighbours_s"] = report->seconds_neighbours;
  state.counters["train_s"] = report->seconds_train;
  state.counters["embed_s"] = report->seconds_embed;
  state.counters["kmeans_s"] = report->seconds_kmeans;
  state.counters["signatures_s"] = report->seconds_signatures;
  state.counters["cpu_s"] = cpu;
  state.counters["peak_rss_mb"] = peak / (1 << 20);
  state.counters["baseline_rss_mb"] = baseline / (1 << 20);
  state.counters["peak_rss_bytes_per_word"] = peak / words;
  state.counters["held_out_accuracy"] = report->accuracy.trained;
  state.counters["kmeans_iterations"] = report->kmeans_iterations;
}

const bool registered = [] {
  auto* entry = benchmark::RegisterBenchmark("WordsBuild/synth", BM_WordsBuild);
  for (int64_t frames : {int64_t{1} << 17, int64_t{1} << 19, int64_t{1} << 21, int64_t{10000000}}) {
    if (static_cast<uint64_t>(frames) <= MaxFrames()) entry->Args({frames, 2});
  }
  entry->ArgNames({"frames", "threads"})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
  entry->Complexity(benchmark::oN);
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
