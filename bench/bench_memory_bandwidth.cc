// Memory bandwidth of this machine, the ceiling of every stage that streams bytes (the floor
// model of scripts/stage_floor.py; docs/benchmarks.md, "The floor"):
//   MemoryBandwidth/read/threads:T    each thread sums its own 512 MiB of 64-bit words
//   MemoryBandwidth/write/threads:T   each thread fills its own 512 MiB
// T = 1 and 2. Items: none; bytes_per_second is the whole machine's rate (every thread's bytes
// over the wall time). The buffers are 64 times a typical last-level cache, so this is DRAM,
// not cache; they are touched once before timing so page faults are not measured.
#include <cstdint>
#include <cstring>
#include <vector>

#include <benchmark/benchmark.h>

namespace motif {
namespace {

constexpr size_t kBytesPerThread = size_t{512} << 20;
constexpr size_t kWordsPerThread = kBytesPerThread / sizeof(uint64_t);

// One buffer per thread, kept across iterations and benchmarks (allocating 512 MiB each time
// would measure the kernel's page zeroing).
std::vector<uint64_t>& ThreadBuffer(int thread_index) {
  static std::vector<uint64_t> buffers[2];
  std::vector<uint64_t>& buffer = buffers[thread_index];
  if (buffer.empty()) buffer.assign(kWordsPerThread, 1);
  return buffer;
}

void MemoryBandwidthRead(benchmark::State& state) {
  const std::vector<uint64_t>& buffer = ThreadBuffer(state.thread_index());
  for (auto _ : state) {
    // Four sums, so the adds do not chain on one register and the loads set the pace.
    uint64_t sums[4] = {0, 0, 0, 0};
    for (size_t idx = 0; idx < kWordsPerThread; idx += 4) {
      for (int lane = 0; lane < 4; ++lane) sums[lane] += buffer[idx + lane];
    }
    benchmark::DoNotOptimize(sums);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * kBytesPerThread));
}

void MemoryBandwidthWrite(benchmark::State& state) {
  std::vector<uint64_t>& buffer = ThreadBuffer(state.thread_index());
  uint8_t value = 0;
  for (auto _ : state) {
    std::memset(buffer.data(), ++value, kBytesPerThread);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * kBytesPerThread));
}

BENCHMARK(MemoryBandwidthRead)->Name("MemoryBandwidth/read")->Threads(1)->Threads(2)
    ->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(MemoryBandwidthWrite)->Name("MemoryBandwidth/write")->Threads(1)->Threads(2)
    ->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
