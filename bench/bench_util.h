// Helpers shared by the benchmarks: peak resident memory as a counter, CPU time, where the real
// CMU takes are, and the N series of the scaling runs (scripts/bench.sh; docs/benchmarks.md,
// "Scaling"). Header-only: each benchmark is its own small program.
#pragma once

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "common/peak_memory.h"

namespace motif::bench {

// Resets the kernel's peak-RSS mark of this process (Linux: "5" to /proc/self/clear_refs), so
// PeakRssBytes() then reports the peak of what follows.
inline void ResetPeakRss() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
}

// A field of /proc/self/status in bytes ("VmHWM:", "VmRSS:"); 0 if absent.
inline double StatusBytes(const char* field) {
  return static_cast<double>(ProcessStatusBytes(field));
}

// Peak resident set size (VmHWM) in bytes.
inline double PeakRssBytes() {
  const double peak = StatusBytes("VmHWM:");
  if (peak > 0) return peak;
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// Resident set now (VmRSS), bytes, after handing freed heap memory back to the system (so that
// what an earlier run left in the allocator does not count as this run's).
inline double CurrentRssBytes() {
  malloc_trim(0);
  return StatusBytes("VmRSS:");
}

// Starts a memory measurement: trims the heap, resets the peak mark, returns the resident set
// the measured part starts from (the process, and whatever inputs are already held).
inline double StartMemoryMeasurement() {
  const double baseline = CurrentRssBytes();
  ResetPeakRss();
  return baseline;
}

// User + system CPU seconds of the whole process (every thread).
inline double ProcessCpuSeconds() {
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The memory counters every scaling benchmark reports, under the same names so scripts/bench.sh
// can plot them: peak_rss_bytes (the process's peak resident set during the measured part,
// VmHWM after a reset: everything resident, inputs included), peak_rss_bytes_per_frame, and
// baseline_rss_bytes (the resident set when the measurement started).
inline void SetMemoryCounters(benchmark::State& state, double peak_bytes, double baseline_bytes,
                              uint64_t frames) {
  state.counters["peak_rss_bytes"] = peak_bytes;
  state.counters["peak_rss_bytes_per_frame"] = peak_bytes / static_cast<double>(frames);
  state.counters["baseline_rss_bytes"] = baseline_bytes;
}

// A frame count from the environment: digits, or a float such as 1e7; `fallback` when unset.
inline int64_t FramesFromEnv(const char* name, int64_t fallback) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == 0) return fallback;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != 0 || !(value >= 1)) {
    std::fprintf(stderr, "%s=%s is not a frame count\n", name, text);
    std::exit(2);
  }
  return static_cast<int64_t>(value);
}

// The largest N of the scaling series: $MOTIF_BENCH_MAX_FRAMES (default 2^17, so that a plain run
// of a benchmark program stays quick; scripts/bench.sh sets it per mode).
inline int64_t ScalingMaxFrames() { return FramesFromEnv("MOTIF_BENCH_MAX_FRAMES", 1 << 17); }

// The scaling series: N = 2^14, 2^15, ... up to min(ScalingMaxFrames(), limit).
inline std::vector<int64_t> ScalingFrames(int64_t limit = INT64_MAX) {
  std::vector<int64_t> frames;
  const int64_t largest = std::min(ScalingMaxFrames(), limit);
  for (int64_t n = int64_t{1} << 14; n <= largest; n *= 2) frames.push_back(n);
  return frames;
}

// Registers `function` (with the extra arguments `extra`) under `name` with one row of
// arguments per entry of `rows`, its CPU time the whole process's (every thread; the machines
// are shared, so CPU time is the steadier figure); nullptr, and nothing registered, when `rows`
// is empty (a family without rows would run once without arguments).
template <class Function, class... Extra>
benchmark::internal::Benchmark* RegisterRows(const std::string& name,
                                             const std::vector<std::vector<int64_t>>& rows,
                                             Function function, Extra... extra) {
  if (rows.empty()) return nullptr;
  benchmark::internal::Benchmark* family =
      benchmark::RegisterBenchmark(name.c_str(), function, extra...);
  for (const std::vector<int64_t>& row : rows) family->Args(row);
  family->MeasureProcessCPUTime();
  return family;
}

// Where the benchmarks keep what they generate and reuse across runs (archives):
// $MOTIF_BENCH_DIR, default /tmp/motifmine-bench; created.
inline std::string WorkDir() {
  const char* from_env = std::getenv("MOTIF_BENCH_DIR");
  std::string dir = from_env && *from_env ? from_env : "/tmp/motifmine-bench";
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  return dir;
}

// The CMU takes: $MOTIF_MOCAP_DIR, else ../shared/data/mocap beside the source tree; "" if absent.
inline std::string MocapDir() {
  const char* from_env = std::getenv("MOTIF_MOCAP_DIR");
  std::string dir = from_env && *from_env ? from_env : MOTIF_DEFAULT_MOCAP_DIR;
  std::error_code error;
  return std::filesystem::is_directory(dir + "/bvh", error) ? dir : "";
}

}  // namespace motif::bench
