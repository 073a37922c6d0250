// Clustering (engine/cluster: ClusterMotifs): the time and peak memory to turn path candidates
// into motifs, against the number of instances M = 2^8 .. 2^14.
// Input: a synthetic trellis file in which M / 4 planted motifs (60 to 150 frames, 4
// occurrences each) match each other frame for frame (each column: the same offset ±1 in the
// other 3 occurrences, plus 16 random noise frames), and the candidates a grower would give:
// every ordered pair of occurrences, with a shorter branch of the same tree (6 candidates per
// instance). Two shapes:
//  * separate: motifs share nothing, so each is its own connected component (the cheap case:
//    small dense eigenproblems);
//  * chained: every motif also resembles the next one on 20% of its columns (similarity 0.2,
//    kept), so all M instances form one connected component that normalized cut must take
//    apart recursively with the sparse (Lanczos) solver: the expensive case.
// Timed: ClusterMotifs (instances, streaming similarity from the trellis, normalized cut), with
// the trellis in the page cache. Counters: instances, edges, motifs found (should be M / 4),
// peak resident memory of the process during the timed runs (includes the trellis's mapped
// pages). Built once per size outside the timed loop, in $TMPDIR.
// ClusterScale/<shape>/frames:N/threads:2 (scripts/bench.sh): the same workloads with N / 1024
// instances spread over N frames (the gaps between motifs widened), N = 2^14, 2^15, ... up to
// $MOTIF_BENCH_MAX_FRAMES: every trellis block holds instance columns, so the similarity pass
// decodes the whole file (16-20 entries a column here against ~250 in a real trellis).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"
#include "engine/cluster/motif_clusterer.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {
namespace {

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_cluster: %s\n", status.ToString().c_str());
  std::exit(1);
}

uint64_t Mix(uint64_t* state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct Workload {
  std::string trellis_path;
  std::vector<PathCandidate> candidates;
  uint64_t frames = 0;
  uint64_t motifs = 0;
};

std::string TempRoot() {
  static const std::string root = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/bench_engine_cluster." +
                      std::to_string(::getpid());
    std::filesystem::create_directories(dir);
    return dir;
  }();
  return root;
}

// `frames` > 0: the gaps between motifs are widened so that the archive has about `frames`
// frames (the scaling series); 0: 40-frame gaps.
const Workload& WorkloadOf(uint64_t instances, bool chained, uint64_t target_frames = 0) {
  static std::map<std::tuple<uint64_t, bool, uint64_t>, Workload> workloads;
  auto found = workloads.find({instances, chained, target_frames});
  if (found != workloads.end()) return found->second;
  constexpr uint64_t kCopies = 4;
  constexpr uint32_t kNoise = 16;
  Workload workload;
  workload.motifs = instances / kCopies;
  uint64_t seed = 17;
  // Occurrence c of motif m lies in stripe c (stripes are the motifs laid end to end, with gaps).
  std::vector<uint64_t> lengths(workload.motifs);
  std::vector<uint64_t> offsets(workload.motifs);
  uint64_t lengths_sum = 0;
  for (uint64_t motif = 0; motif < workload.motifs; ++motif) {
    lengths[motif] = 60 + Mix(&seed) % 91;
    lengths_sum += lengths[motif];
  }
  uint64_t gap = 40;
  if (target_frames / kCopies > lengths_sum + gap * workload.motifs) {
    gap = (target_frames / kCopies - lengths_sum) / workload.motifs;
  }
  uint64_t stripe = 0;
  for (uint64_t motif = 0; motif < workload.motifs; ++motif) {
    offsets[motif] = stripe;
    stripe += lengths[motif] + gap;
  }
  workload.frames = kCopies * stripe;
  auto start_of = [&](uint64_t motif, uint64_t copy) { return copy * stripe + offsets[motif]; };
  // Column t's planted neighbours, computed on the fly (nothing of size N is kept).
  auto planted_frames = [&](uint64_t column, std::vector<uint32_t>* frames) {
    const uint64_t copy = column / stripe;
    const uint64_t in_stripe = column % stripe;
    const uint64_t motif = static_cast<uint64_t>(
        std::upper_bound(offsets.begin(), offsets.end(), in_stripe) - offsets.begin() - 1);
    const uint64_t k = in_stripe - offsets[motif];
    if (k >= lengths[motif]) return;  // a gap between motifs
    for (uint64_t other = 0; other < kCopies; ++other) {
      if (other == copy) continue;
      for (int64_t delta = -1; delta <= 1; ++delta) {
        const int64_t at = static_cast<int64_t>(k) + delta;
        if (at >= 0 && at < static_cast<int64_t>(lengths[motif])) {
          frames->push_back(static_cast<uint32_t>(start_of(motif, other) + uint64_t(at)));
        }
      }
    }
    // Chained: the first 20% of the columns also see the next motif's first copy.
    if (chained && motif + 1 < workload.motifs && k < lengths[motif] / 5) {
      frames->push_back(static_cast<uint32_t>(start_of(motif + 1, 0) + k));
    }
  };
  for (uint64_t motif = 0; motif < workload.motifs; ++motif) {
    for (uint64_t copy = 0; copy < kCopies; ++copy) {
      for (uint64_t other = 0; other < kCopies; ++other) {
        if (other == copy) continue;
        const uint64_t top = start_of(motif, copy);
        const uint64_t match = start_of(motif, other);
        PathCandidate full{top, top + lengths[motif], match, match + lengths[motif], top, match};
        PathCandidate branch = full;
        branch.top_end = top + lengths[motif] / 2;
        branch.match_end = match + lengths[motif] / 2;
        workload.candidates.push_back(full);
        workload.candidates.push_back(branch);
      }
    }
  }
  TrellisParams params;
  params.frame_count = workload.frames;
  params.eps = 1.0f;
  params.k_max = 64;
  params.search_params = "bench_engine_cluster";
  workload.trellis_path = TempRoot() + "/" + std::to_string(instances) +
                          (chained ? "_chained" : "_separate") + "_" +
                          std::to_string(workload.frames) + ".mtr";
  auto writer = TrellisFileWriter::OpenOrResume(workload.trellis_path, params);
  if (!writer.ok()) Die(writer.status());
  std::vector<std::vector<Neighbour>> block;
  std::vector<uint32_t> frames;
  for (uint64_t column = 0; column < workload.frames; ++column) {
    frames.clear();
    planted_frames(column, &frames);
    for (uint32_t idx = 0; idx < kNoise; ++idx) {
      frames.push_back(static_cast<uint32_t>(Mix(&seed) % workload.frames));
    }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    block.emplace_back();
    for (uint32_t frame : frames) block.back().push_back({frame, 0.5f});
    if (block.size() == (*writer)->block_columns() || column + 1 == workload.frames) {
      if (Status status = (*writer)->AppendBlock(block); !status.ok()) Die(status);
      block.clear();
    }
  }
  if (Status status = (*writer)->Finish(); !status.ok()) Die(status);
  return workloads[{instances, chained, target_frames}] = std::move(workload);
}

void RunCluster(benchmark::State& state, const Workload& workload, int threads) {
  auto trellis = TrellisFileReader::Open(workload.trellis_path);
  if (!trellis.ok()) Die(trellis.status());
  ClusterOptions options;
  options.threads = threads;
  ClusterResult result;
  const double baseline = bench::StartMemoryMeasurement();
  for (auto _ : state) {
    Result<ClusterResult> clustered = ClusterMotifs(workload.candidates, **trellis, options);
    if (!clustered.ok()) Die(clustered.status());
    result = std::move(clustered).value();
  }
  state.counters["peak_rss_MB"] = bench::PeakRssBytes() / 1e6;
  bench::SetMemoryCounters(state, bench::PeakRssBytes(), baseline, workload.frames);
  state.counters["frames"] = static_cast<double>(workload.frames);
  state.counters["instances"] = static_cast<double>(result.instances.size());
  state.counters["edges"] = static_cast<double>(result.report.similarity_stats.edges);
  state.counters["motifs"] = static_cast<double>(result.motifs.size());
  state.counters["planted"] = static_cast<double>(workload.motifs);
  state.counters["eigen_solves"] = static_cast<double>(result.report.cut_stats.eigen_solves);
  state.counters["sparse_solves"] = static_cast<double>(result.report.cut_stats.sparse_solves);
  state.counters["similarity_s"] = result.report.similarity_stats.seconds;
  state.counters["cut_s"] = result.report.cut_seconds;
}

void BM_ClusterMotifs(benchmark::State& state, bool chained) {
  const uint64_t instances = static_cast<uint64_t>(state.range(0));
  RunCluster(state, WorkloadOf(instances, chained), static_cast<int>(state.range(1)));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * instances));
  state.SetComplexityN(static_cast<int64_t>(instances));
}

// The scaling series: N frames, N / 1024 instances (at least 16; a mined archive has about one
// found instance per 1,000-1,500 frames, docs/benchmarks.md "Mining quality"). Items: frames.
void BM_ClusterScale(benchmark::State& state, bool chained) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const uint64_t instances = std::max<uint64_t>(16, frames / 1024 / 4 * 4);
  const Workload& workload = WorkloadOf(instances, chained, frames);
  RunCluster(state, workload, static_cast<int>(state.range(1)));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * workload.frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
}

const bool registered = [] {
  for (bool chained : {false, true}) {
    benchmark::RegisterBenchmark(chained ? "ClusterMotifs/chained" : "ClusterMotifs/separate",
                                 BM_ClusterMotifs, chained)
        ->ArgNames({"instances", "threads"})
        ->ArgsProduct({benchmark::CreateRange(1 << 8, 1 << 14, 4), {1, 2}})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MeasureProcessCPUTime();
  }
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames, 2});
  for (bool chained : {false, true}) {
    if (auto* family =
            bench::RegisterRows(chained ? "ClusterScale/chained" : "ClusterScale/separate", rows,
                                BM_ClusterScale, chained)) {
      family->ArgNames({"frames", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MeasureProcessCPUTime()
          ->Iterations(1)
          ->Complexity(benchmark::oN);
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code error;
  std::filesystem::remove_all(motif::TempRoot(), error);
  return 0;
}
