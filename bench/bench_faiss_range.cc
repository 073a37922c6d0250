// The external baseline of the trellis search (docs/benchmarks.md, "External baseline: FAISS
// exact range search"): FAISS's exact range search
// (faiss::IndexFlatL2::range_search, Debian's libfaiss-dev 1.7.3 on the system BLAS) building the
// same trellis columns as ExactSearch, timed against ExactSearch on the same columns in the same
// process. Built only when FAISS is found (bench/CMakeLists.txt); the engine never needs it.
//
// How FAISS builds a column. Every frame is embedded with the LSH embedding (HashFamily::Embed,
// docs/design/lsh.md section 1: 10 floats per weighted joint, 120 for the CMU skeleton), which
// satisfies |e_i - e_j| <= D(i, j); the embeddings go into an IndexFlatL2. A column t is a range
// search of e_t with the squared radius kRadiusScale * eps^2 + kRadiusSlack (FAISS's L2 distances
// are squared; the small margin covers float rounding of |x|^2 + |y|^2 - 2 x.y in FAISS's BLAS
// path and the int16 quaternions' norms, which are 1 only to ~1e-4): every frame with D <= eps
// is returned, among others (a superset). Each returned frame is then checked with the trellis
// rules (not t, not within the exclusion radius in t's clip), verified with the exact distance
// (QueryDistance::ToBatch, engine/lsh: bit-identical to PoseDistance, eight candidates per AVX2
// instruction, the engine's own fastest verifier), kept if D <= eps, and the k_max nearest are
// kept (ties: lower frame first), sorted by frame (FinishColumn): ExactSearch's column
// definition (engine/distance/exact_search.h). After the timed region every column of the block
// is compared with ExactSearch's, frame and distance bit for bit; any difference is an error
// (SkipWithError).
//
//   FaissRange/<data>   <data> as in bench_engine_lsh (bench/bench_archives.h): "synth" or
//                       "resequenced" (skipped without ../shared/data/mocap); 2 and 1 threads.
//                       N = 2^14: every column (a full build, ~5 s). N = 2^16 .. 2^20 (a full
//                       build would take minutes to hours): kBlockColumns consecutive columns
//                       from the middle of the archive, and the full-archive time
//                       EXTRAPOLATED as (per-column time) x N (labelled so, like
//                       bench_engine_trellis's exact_extrapolated rows).
//                       Reported time (manual): embedding + index + column time for all N.
//   FaissRange/random64 an outside reference figure ("FAISS exact range search over 200,000
//                       random 64-dimensional vectors took about 90 s on 2 cores with
//                       OpenBLAS"): 200,000 vectors uniform in [0, 1)^64 (fixed seed), every
//                       vector queried against all of them, with the squared radius that
//                       returns ~1 % of the points per query (the 1 % quantile of 2,000,000
//                       squared distances, 100 sampled queries x 20,000 others, computed before
//                       the timed region; the share measured is the result_share counter).
//                       Queries go in batches of 4096 (FAISS's own BLAS query block) so that
//                       the results (~12 bytes x 2,000 per query) need not all be held at once;
//                       the work is the same as one call. Reported time: the whole search.
//                       20,000 vectors: the same at 1 % of the work, a quick check.
//
// Threads. FAISS parallelises with OpenMP and, in the BLAS path (>= 20 queries a call), through
// the BLAS's own threads (OpenBLAS pthreads): both are set to the row's thread count
// (omp_set_num_threads, openblas_set_num_threads through dlsym). The verification of the FAISS
// candidates runs on the same OpenMP threads (not a TBB arena: one thread pool on the FAISS side,
// so that TBB workers do not compete with OpenMP and OpenBLAS threads spinning after their
// parallel regions on a 2-core machine). ExactSearch gets the same count (its task_arena).
// Which BLAS was loaded at run time (the libblas.so.3 alternative) is reported in the context
// ("blas_library", "openblas_config") and checked by hand with update-alternatives (docs).
//
// Counters, per column of the timed block: faiss_us_per_column and faiss_cpu_us_per_column (range
// search + verification; CPU = process user + system time, all threads), range_search_us and
// verify_us (the two parts, wall), candidates_per_column (what the range search returned: the
// superset), within_eps_per_column (of those, D <= eps and allowed, before the k_max cap),
// mean_k, exact_us_per_column, exact_cpu_us_per_column, exact_over_faiss and
// exact_over_faiss_cpu (> 1: FAISS is faster than ExactSearch), embed_s, index_s (IndexFlatL2
// add), full_archive_s (embed + index + per-column x N; EXTRAPOLATED unless full_build = 1),
// peak_rss_mb and peak_rss_bytes_per_frame (VmHWM reset before the embedding: the index, the
// columns, and the PoseFeatures' 96 B/frame and the process baseline already resident).
// peak_rss_bytes and baseline_rss_bytes as in bench_util.h.
//   FaissScale/<data>   the same as FaissRange, 2 threads, N = 2^14, 2^15, ... up to
//                       $MOTIF_BENCH_MAX_FRAMES (bench_util.h) and 2^22: the scaling series of
//                       scripts/bench.sh, beside ExactScale and the LSH trellis.
// Left out: making the archive (in memory, before everything) and writing a trellis.
#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <faiss/IndexFlat.h>
#include <faiss/impl/AuxIndexStructures.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_archives.h"
#include "bench/bench_util.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/query_distance.h"

namespace motif {
namespace {

constexpr uint64_t kLargestFullBuild = 1 << 14;  // above: a block, extrapolated
constexpr uint64_t kBlockColumns = 1024;         // 4 of ExactSearch's 256-query tasks
// Queries per range_search call: kQueryFrameBudget / N, at most 1024 and at least 32 (FAISS
// takes its BLAS path from 20 queries). The results of a call are held at once (12 bytes each,
// and the range search returns up to ~60 % of the archive per column, docs/benchmarks.md), so
// the budget bounds them to a few hundred MB at any N.
constexpr uint64_t kQueryFrameBudget = uint64_t{1} << 26;
constexpr float kRadiusScale = 1.002f;  // squared radius = scale * eps^2 + slack
constexpr float kRadiusSlack = 1e-3f;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

using bench::ProcessCpuSeconds;

// OpenMP threads for FAISS, and the BLAS's own threads if the BLAS loaded is OpenBLAS (found by
// name at run time, so the benchmark links against any libblas.so.3).
void SetFaissThreads(int threads) {
  omp_set_num_threads(threads);
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) {
    set(threads);
  }
}

// The file that provides sgemm_ at run time (symlinks resolved: with Debian's alternatives,
// .../openblas-pthread/libblas.so.3 or .../blas/libblas.so.3), and OpenBLAS's build string.
std::string BlasLibrary() {
  Dl_info info;
  void* sgemm = dlsym(RTLD_DEFAULT, "sgemm_");
  if (!sgemm || !dladdr(sgemm, &info) || !info.dli_fname) return "unknown";
  std::error_code error;
  const std::filesystem::path path = std::filesystem::canonical(info.dli_fname, error);
  return error ? info.dli_fname : path.string();
}
std::string OpenBlasConfig() {
  using GetConfig = char* (*)();
  auto config = reinterpret_cast<GetConfig>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
  return config ? config() : "not OpenBLAS";
}

struct FaissArchiveIndex {
  std::unique_ptr<faiss::IndexFlatL2> index;
  double embed_seconds = 0;
  double index_seconds = 0;
};

// Every frame's embedding, added to an IndexFlatL2 in chunks (the index's own copy is the only
// full one; queries read it back with get_xb()).
FaissArchiveIndex BuildIndex(const PoseFeatures& features, int threads) {
  const HashFamily family = HashFamily::Draw(features.weights(), 1, 1, 1.0f, 1);
  const uint32_t dims = family.embedding_dims();
  const uint64_t frames = features.frame_count();
  FaissArchiveIndex built;
  built.index = std::make_unique<faiss::IndexFlatL2>(dims);
  constexpr uint64_t kChunk = 1 << 16;
  std::vector<float> chunk(kChunk * dims);
  for (uint64_t first = 0; first < frames; first += kChunk) {
    const int64_t count = static_cast<int64_t>(std::min(kChunk, frames - first));
    auto start = std::chrono::steady_clock::now();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int64_t frame_idx = 0; frame_idx < count; ++frame_idx) {
      family.Embed(features.frame(first + frame_idx), &chunk[frame_idx * dims]);
    }
    built.embed_seconds += Seconds(start);
    start = std::chrono::steady_clock::now();
    built.index->add(count, chunk.data());
    built.index_seconds += Seconds(start);
  }
  return built;
}

struct FaissBlockStats {
  uint64_t candidates = 0;  // returned by range_search
  uint64_t within_eps = 0;  // allowed and D <= eps, before the k_max cap
  uint64_t neighbours = 0;  // kept
  double range_search_seconds = 0;
  double verify_seconds = 0;
};

// Columns [first, first + count) with FAISS: range search, then the trellis rules and the exact
// distance on every returned frame.
void FaissColumns(const faiss::IndexFlatL2& index, const PoseFeatures& features,
                  const NeighbourRules& rules, int threads, uint64_t first, uint64_t count,
                  std::vector<std::vector<Neighbour>>* columns, FaissBlockStats* stats) {
  const uint64_t frames = features.frame_count();
  const float* embeddings = index.get_xb();
  const size_t dims = static_cast<size_t>(index.d);
  const float radius = kRadiusScale * rules.eps * rules.eps + kRadiusSlack;
  const uint64_t queries_per_call = std::clamp<uint64_t>(kQueryFrameBudget / frames, 32, 1024);
  columns->assign(count, {});
  for (uint64_t batch_first = 0; batch_first < count; batch_first += queries_per_call) {
    const int64_t batch = static_cast<int64_t>(std::min(queries_per_call, count - batch_first));
    const uint64_t first_query = first + batch_first;
    auto start = std::chrono::steady_clock::now();
    faiss::RangeSearchResult result(batch);
    index.range_search(batch, embeddings + first_query * dims, radius, &result);
    stats->range_search_seconds += Seconds(start);
    stats->candidates += result.lims[batch];
    start = std::chrono::steady_clock::now();
    uint64_t within_eps = 0;
    uint64_t neighbours = 0;
#pragma omp parallel num_threads(threads) reduction(+ : within_eps, neighbours)
    {
      QueryDistance distance(features);  // one per thread: it holds the query
      std::vector<uint32_t> allowed;
      std::vector<float> distances;
#pragma omp for schedule(dynamic, 8)
      for (int64_t query_idx = 0; query_idx < batch; ++query_idx) {
        const uint64_t column_frame = first_query + query_idx;
        const ExclusionRange excluded = ExclusionRangeOf(rules, column_frame, frames);
        allowed.clear();
        for (size_t entry = result.lims[query_idx]; entry < result.lims[query_idx + 1]; ++entry) {
          const uint64_t frame = static_cast<uint64_t>(result.labels[entry]);
          if (!excluded.Contains(frame)) allowed.push_back(static_cast<uint32_t>(frame));
        }
        distances.resize(allowed.size());
        distance.SetQuery(column_frame);
        distance.ToBatch(allowed.data(), static_cast<uint32_t>(allowed.size()), rules.eps,
                         distances.data());
        std::vector<Neighbour>& column = (*columns)[batch_first + query_idx];
        for (size_t idx = 0; idx < allowed.size(); ++idx) {
          if (distances[idx] <= rules.eps) {
            column.push_back(Neighbour{allowed[idx], distances[idx]});
          }
        }
        within_eps += column.size();
        FinishColumn(rules.k_max, &column);
        neighbours += column.size();
      }
    }
    stats->verify_seconds += Seconds(start);
    stats->within_eps += within_eps;
    stats->neighbours += neighbours;
  }
}

// First column that differs ("" if none): frames and distances, bit for bit.
std::string FirstDifference(const std::vector<std::vector<Neighbour>>& faiss_columns,
                            const std::vector<std::vector<Neighbour>>& exact_columns,
                            uint64_t first, uint64_t count) {
  for (uint64_t idx = 0; idx < count; ++idx) {
    const std::vector<Neighbour>& a = faiss_columns[idx];
    const std::vector<Neighbour>& b = exact_columns[idx];
    bool same = a.size() == b.size();
    for (size_t entry = 0; same && entry < a.size(); ++entry) {
      same = a[entry].frame == b[entry].frame && a[entry].distance == b[entry].distance;
    }
    if (!same) {
      return "column " + std::to_string(first + idx) + ": FAISS " + std::to_string(a.size()) +
             " neighbours, ExactSearch " + std::to_string(b.size());
    }
  }
  return "";
}

void BM_FaissRange(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bench::Archive& archive = bench::ArchiveOf(data, frames);
  if (!archive.error.empty()) {
    state.SkipWithError(archive.error.c_str());
    return;
  }
  const PoseFeatures& features = *archive.features;
  const bool full_build = frames <= kLargestFullBuild;
  const uint64_t count = full_build ? frames : std::min(frames, kBlockColumns);
  const uint64_t first = full_build ? 0 : (frames - count) / 2;
  SetFaissThreads(threads);

  std::vector<std::vector<Neighbour>> faiss_columns;
  FaissBlockStats stats;
  double embed_seconds = 0, index_seconds = 0, column_seconds = 0, column_cpu = 0, peak = 0;
  double baseline = 0;
  for (auto _ : state) {
    baseline = bench::StartMemoryMeasurement();
    FaissArchiveIndex built = BuildIndex(features, threads);
    embed_seconds = built.embed_seconds;
    index_seconds = built.index_seconds;
    stats = FaissBlockStats();
    const double cpu_start = ProcessCpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    FaissColumns(*built.index, features, archive.rules, threads, first, count, &faiss_columns,
                 &stats);
    column_seconds = Seconds(start);
    column_cpu = ProcessCpuSeconds() - cpu_start;
    peak = bench::PeakRssBytes();
    state.SetIterationTime(embed_seconds + index_seconds +
                           column_seconds / static_cast<double>(count) * frames);
  }

  // ExactSearch on the same columns, same thread count, then the columns compared.
  ExactSearchOptions exact_options;
  exact_options.threads = static_cast<uint32_t>(threads);
  const ExactSearch exact(features, archive.rules, exact_options);
  std::vector<std::vector<Neighbour>> exact_columns;
  SearchStats exact_stats;
  const double exact_cpu_start = ProcessCpuSeconds();
  const auto exact_start = std::chrono::steady_clock::now();
  Status status = exact.SearchColumns(first, count, &exact_columns, &exact_stats);
  const double exact_seconds = Seconds(exact_start);
  const double exact_cpu = ProcessCpuSeconds() - exact_cpu_start;
  if (!status.ok()) {
    state.SkipWithError(status.ToString().c_str());
    return;
  }
  const std::string difference = FirstDifference(faiss_columns, exact_columns, first, count);
  if (!difference.empty()) {
    state.SkipWithError(("FAISS columns differ from ExactSearch's: " + difference).c_str());
    return;
  }

  const double n = static_cast<double>(frames);
  const double columns = static_cast<double>(count);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["full_build"] = full_build ? 1 : 0;
  state.counters["timed_columns"] = columns;
  state.counters["queries_per_call"] =
      static_cast<double>(std::clamp<uint64_t>(kQueryFrameBudget / frames, 32, 1024));
  state.counters["full_archive_s"] = embed_seconds + index_seconds + column_seconds / columns * n;
  state.counters["faiss_us_per_column"] = 1e6 * column_seconds / columns;
  state.counters["faiss_cpu_us_per_column"] = 1e6 * column_cpu / columns;
  state.counters["range_search_us"] = 1e6 * stats.range_search_seconds / columns;
  state.counters["verify_us"] = 1e6 * stats.verify_seconds / columns;
  state.counters["candidates_per_column"] = static_cast<double>(stats.candidates) / columns;
  state.counters["within_eps_per_column"] = static_cast<double>(stats.within_eps) / columns;
  state.counters["mean_k"] = static_cast<double>(stats.neighbours) / columns;
  state.counters["exact_us_per_column"] = 1e6 * exact_seconds / columns;
  state.counters["exact_cpu_us_per_column"] = 1e6 * exact_cpu / columns;
  state.counters["exact_over_faiss"] = exact_seconds / column_seconds;
  state.counters["exact_over_faiss_cpu"] = exact_cpu / column_cpu;
  state.counters["embed_s"] = embed_seconds;
  state.counters["index_s"] = index_seconds;
  state.counters["peak_rss_mb"] = peak / (1 << 20);
  bench::SetMemoryCounters(state, peak, baseline, frames);
  state.counters["eps"] = archive.rules.eps;
  state.SetLabel(full_build ? "full build, all columns checked against ExactSearch"
                            : "EXTRAPOLATED from " + std::to_string(count) +
                                  " timed columns, all checked against ExactSearch");
}

// The reference: 200,000 random 64-d vectors, a full range search at ~1 % per query.
void BM_FaissRandom(benchmark::State& state) {
  const int64_t vectors = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  constexpr int kDims = 64;
  constexpr int64_t kBatch = 4096;
  std::vector<float> data(static_cast<size_t>(vectors) * kDims);
  uint64_t bits = 0x9e3779b97f4a7c15ull;
  for (float& value : data) {
    bits = bits * 6364136223846793005ull + 1442695040888963407ull;
    value = static_cast<float>(bits >> 40) / static_cast<float>(1 << 24);  // [0, 1)
  }
  // The 1 % quantile of the squared distance, from 100 sampled queries x 20,000 others.
  std::vector<float> sampled;
  const int64_t query_stride = std::max<int64_t>(vectors / 100, 1);
  const int64_t other_stride = std::max<int64_t>(vectors / 20000, 1);
  for (int64_t query_idx = 0; query_idx < vectors; query_idx += query_stride) {
    const float* query = &data[static_cast<size_t>(query_idx) * kDims];
    for (int64_t other = 0; other < vectors; other += other_stride) {
      const float* point = &data[static_cast<size_t>(other) * kDims];
      float squared = 0;
      for (int dim = 0; dim < kDims; ++dim) {
        squared += (query[dim] - point[dim]) * (query[dim] - point[dim]);
      }
      sampled.push_back(squared);
    }
  }
  const size_t quantile = sampled.size() / 100;
  std::nth_element(sampled.begin(), sampled.begin() + quantile, sampled.end());
  const float radius = sampled[quantile];
  sampled = {};

  SetFaissThreads(threads);
  faiss::IndexFlatL2 index(kDims);
  index.add(vectors, data.data());
  uint64_t results = 0;
  double cpu = 0;
  for (auto _ : state) {
    results = 0;
    const double cpu_start = ProcessCpuSeconds();
    for (int64_t first = 0; first < vectors; first += kBatch) {
      const int64_t batch = std::min(kBatch, vectors - first);
      faiss::RangeSearchResult result(batch);
      index.range_search(batch, &data[static_cast<size_t>(first) * kDims], radius, &result);
      results += result.lims[batch];
    }
    cpu = ProcessCpuSeconds() - cpu_start;
  }
  state.SetItemsProcessed(state.iterations() * vectors);
  state.counters["squared_radius"] = radius;
  state.counters["results_per_query"] = static_cast<double>(results) / vectors;
  state.counters["result_share"] = static_cast<double>(results) / vectors / vectors;
  state.counters["cpu_s"] = cpu;
}

const bool registered = [] {
  for (const std::string data : {"synth", "resequenced"}) {
    auto* entry = benchmark::RegisterBenchmark(("FaissRange/" + data).c_str(), BM_FaissRange, data);
    for (int64_t frames : {1 << 14, 1 << 16, 1 << 18, 1 << 20}) {
      entry->Args({frames, 2});
      entry->Args({frames, 1});  // a second row: cheap, the thread count is inner
    }
    entry->ArgNames({"frames", "threads"})
        ->Unit(benchmark::kSecond)
        ->Iterations(1)
        ->UseManualTime()
        ->Complexity(benchmark::oNSquared);
  }
  // The scaling series of scripts/bench.sh: 2 threads, N = 2^14, 2^15, ... up to
  // $MOTIF_BENCH_MAX_FRAMES and at most 2^22 (the index holds 480 bytes a frame: 2 GB at 2^22).
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames(int64_t{1} << 22)) rows.push_back({frames, 2});
  for (const std::string data : {"synth", "resequenced"}) {
    if (auto* family = bench::RegisterRows("FaissScale/" + data, rows, BM_FaissRange, data)) {
      family->ArgNames({"frames", "threads"})
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseManualTime()
          ->Complexity(benchmark::oNSquared);
    }
  }
  benchmark::RegisterBenchmark("FaissRange/random64", BM_FaissRandom)
      ->ArgNames({"vectors", "threads"})
      ->Args({20000, 2})
      ->Args({200000, 2})
      ->Unit(benchmark::kSecond)
      ->Iterations(1)
      ->UseRealTime();
  return true;
}();

}  // namespace
}  // namespace motif

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("blas_library", motif::BlasLibrary());
  benchmark::AddCustomContext("openblas_config", motif::OpenBlasConfig());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
