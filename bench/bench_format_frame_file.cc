// Frame file (.mfs) throughput: writing column blocks (quantise, delta, shuffle, zstd, checksum),
// sequential decode through a FrameStream, and random access to short frame ranges. The archives
// are synthetic (MotionSynthesizer, fixed seed), made once per size outside the timed loops and
// kept in the page cache, so these numbers leave out cold-disk I/O. Counters: frames per second,
// compressed bytes per frame, and peak resident memory of the timed part (it must not grow with
// the number of frames when streaming).
//
// DecodeScale/<data>/frames:N (scripts/bench.sh): the sequential decode (FrameStream, one
// thread) of the archives of bench/bench_archives.h ("synth", "resequenced": real motion
// compresses less), N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES; the memory counters of
// bench_util.h (the stream releases the pages it has decoded: flat in N).
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>

#include <benchmark/benchmark.h>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"

namespace motif {
namespace {

std::string BenchDir() {
  static const std::string dir = [] {
    std::string path = std::filesystem::temp_directory_path().string() + "/motifmine-bench-" +
                       std::to_string(::getpid());
    std::filesystem::create_directories(path);
    return path;
  }();
  return dir;
}

struct CleanUp {
  ~CleanUp() {
    std::error_code error;
    std::filesystem::remove_all(BenchDir(), error);
  }
} clean_up;

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_format_frame_file: %s\n", status.ToString().c_str());
  std::exit(1);
}

// A synthetic archive of `frames` frames, written once per size.
const std::string& ArchiveOf(uint64_t frames) {
  static std::map<uint64_t, std::string> archives;
  auto it = archives.find(frames);
  if (it != archives.end()) return it->second;
  const std::string path = BenchDir() + "/synth-" + std::to_string(frames) + ".mfs";
  SynthOptions options;
  options.frames = frames;
  options.motifs = frames >= (1 << 17) ? 4 : 0;  // planting needs room
  options.seed = 7;
  auto synthesizer = MotionSynthesizer::Create(options);
  if (!synthesizer.ok()) Die(synthesizer.status());
  auto writer = FrameFileWriter::Create(path, (*synthesizer)->skeleton(), options.fps);
  if (!writer.ok()) Die(writer.status());
  Status status =
      (*synthesizer)->Run([&](const ClipFrames& clip) { return (*writer)->AppendClip(clip); });
  if (status.ok()) status = (*writer)->Commit();
  if (!status.ok()) Die(status);
  return archives[frames] = path;
}

void BM_FrameFileSequentialRead(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const std::string& path = ArchiveOf(frames);
  auto reader = FrameFileReader::Open(path);
  if (!reader.ok()) {
    state.SkipWithError(reader.status().ToString().c_str());
    return;
  }
  bench::ResetPeakRss();
  const double rss_before = bench::PeakRssBytes();
  for (auto _ : state) {
    auto stream = (*reader)->Stream();
    double checksum = 0;
    while (true) {
      Result<bool> more = stream->Next();
      if (!more.ok() || !*more) break;
      checksum += stream->rows()[0];
    }
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.counters["bytes_per_frame"] =
      static_cast<double>((*reader)->summary().compressed_bytes) / frames;
  state.counters["peak_rss_growth_MB"] = (bench::PeakRssBytes() - rss_before) / 1e6;
  state.SetComplexityN(static_cast<int64_t>(frames));
}
BENCHMARK(BM_FrameFileSequentialRead)
    ->Name("FrameFile/SequentialRead")
    ->RangeMultiplier(4)
    ->Range(1 << 14, 1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

void BM_DecodeScale(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  Result<std::string> path = bench::ArchiveFileOf(data, frames);
  if (!path.ok()) {
    state.SkipWithError(path.status().ToString().c_str());
    return;
  }
  auto reader = FrameFileReader::Open(*path);
  if (!reader.ok()) {
    state.SkipWithError(reader.status().ToString().c_str());
    return;
  }
  const double baseline = bench::StartMemoryMeasurement();
  for (auto _ : state) {
    auto stream = (*reader)->Stream();
    double checksum = 0;
    while (true) {
      Result<bool> more = stream->Next();
      if (!more.ok()) {
        state.SkipWithError(more.status().ToString().c_str());
        return;
      }
      if (!*more) break;
      checksum += stream->rows()[0];
    }
    benchmark::DoNotOptimize(checksum);
  }
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.counters["archive_bytes_per_frame"] =
      static_cast<double>((*reader)->summary().compressed_bytes) / frames;
  state.SetComplexityN(static_cast<int64_t>(frames));
}

const bool scale_registered = [] {
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames});
  for (const std::string data : {"synth", "resequenced"}) {
    if (auto* family = bench::RegisterRows("DecodeScale/" + data, rows, BM_DecodeScale, data)) {
      family->ArgName("frames")
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Complexity(benchmark::oN);
    }
  }
  return true;
}();

void BM_FrameFileRandomRead(benchmark::State& state) {
  const uint64_t frames = 1 << 20;
  const uint64_t range_frames = static_cast<uint64_t>(state.range(0));
  auto reader = FrameFileReader::Open(ArchiveOf(frames));
  if (!reader.ok()) {
    state.SkipWithError(reader.status().ToString().c_str());
    return;
  }
  std::mt19937_64 rng(3);
  std::vector<float> rows;
  for (auto _ : state) {
    const uint64_t first = rng() % (frames - range_frames);
    Status status = (*reader)->ReadFrames(first, range_frames, &rows);
    benchmark::DoNotOptimize(rows.data());
    if (!status.ok()) state.SkipWithError(status.ToString().c_str());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * range_frames));
}
BENCHMARK(BM_FrameFileRandomRead)
    ->Name("FrameFile/RandomRead/frames:1M")
    ->Arg(120)
    ->Arg(4096)
    ->Unit(benchmark::kMicrosecond);

void BM_FrameFileWrite(benchmark::State& state) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  // Generate the clips once; the timed loop only writes them.
  SynthOptions options;
  options.frames = frames;
  options.motifs = 0;
  options.seed = 11;
  auto synthesizer = MotionSynthesizer::Create(options);
  std::vector<ClipFrames> clips;
  Status generated = (*synthesizer)->Run([&](const ClipFrames& clip) {
    clips.push_back(clip);
    return Status::Ok();
  });
  if (!generated.ok()) Die(generated);
  const std::string path = BenchDir() + "/write.mfs";
  uint64_t bytes = 0;
  for (auto _ : state) {
    std::filesystem::remove(path);
    auto writer = FrameFileWriter::Create(path, (*synthesizer)->skeleton(), options.fps);
    for (const ClipFrames& clip : clips) {
      Status appended = (*writer)->AppendClip(clip);
      if (!appended.ok()) Die(appended);
    }
    Status committed = (*writer)->Commit();
    if (!committed.ok()) Die(committed);
    bytes = std::filesystem::file_size(path);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.counters["bytes_per_frame"] = static_cast<double>(bytes) / frames;
  state.counters["ratio_vs_float32"] =
      static_cast<double>(frames * (*synthesizer)->skeleton().joint_count() * 4 * 4 + frames * 16) /
      bytes;
}
BENCHMARK(BM_FrameFileWrite)
    ->Name("FrameFile/Write")
    ->Arg(1 << 16)
    ->Arg(1 << 18)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
