// Mining quality on synthetic archives with planted motifs: the whole pipeline with the
// defaults of `motifmine mine` (the joint-angle eps at 12 degrees, lambda 0.5 s, B = 5, normalized
// cut with automatic G; docs/design/algorithm.md)
// on procedural archives from `motifmine synth` (10 to 20 motifs of 0.5 to 5 s, 3 to 6
// instances each, warps 0.7 to 1.4x, noise 1 degree), scored against the truth:
//   recall    planted instances hit by a found one (overlap >= half of the shorter),
//   precision found instances that hit a planted one,
//   ari       adjusted Rand index of found vs planted motif over the hit instances.
// Arguments: frames, motifs, seed. The stages run through MinePipeline, as `motifmine mine` runs
// them (the search exact below 90,000 frames, LSH above). Timed: one run of trellis + grow +
// cluster (the archive is written outside the timing). Other counters: planted and found instances,
// found motifs, path candidates, the trellis's eps. Files go to $TMPDIR and are removed afterwards.
// docs/benchmarks.md, "Mining quality on planted archives", has the figures and the commands.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_writer.h"

namespace motif {
namespace {

[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "bench_engine_planted: %s\n", status.ToString().c_str());
  std::exit(1);
}

template <typename T>
T Check(Result<T> result) {
  if (!result.ok()) Die(result.status());
  return std::move(*result);
}

void BM_PlantedMotifs(benchmark::State& state) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/bench_engine_planted." +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  SynthOptions options;
  options.frames = static_cast<uint64_t>(state.range(0));
  options.motifs = static_cast<uint32_t>(state.range(1));
  options.seed = static_cast<uint64_t>(state.range(2));
  options.background_variation_degrees = kRecommendedBackgroundVariation;  // as motifmine synth
  const std::string archive = dir + "/planted.mfs";
  auto synthesizer = Check(MotionSynthesizer::Create(options));
  {
    auto writer = Check(FrameFileWriter::Create(archive, synthesizer->skeleton(), options.fps));
    Status status =
        synthesizer->Run([&](const ClipFrames& clip) { return writer->AppendClip(clip); });
    if (!status.ok()) Die(status);
    if (Status commit = writer->Commit(); !commit.ok()) Die(commit);
  }
  PlantedMotifScore score;
  uint64_t candidates = 0;
  double eps = 0;
  for (auto _ : state) {
    std::filesystem::remove_all(dir + "/mined");
    motifmine::MineOptions mine;
    mine.out_dir = dir + "/mined";
    mine.write_report = false;
    MinePipelineResult run = Check(RunMine(mine, {archive}));
    eps = run.trellis.params.eps;
    candidates = run.paths.candidates;
    std::vector<FoundInstance> found;
    for (const MotifsJsonMotif& motif : run.document.motifs) {
      for (const MotifsJsonInstance& instance : motif.instances) {
        found.push_back({instance.clip, instance.start, instance.end, motif.id});
      }
    }
    score = ScorePlantedMotifs(found, synthesizer->truth());
  }
  state.counters["recall"] = score.recall;
  state.counters["precision"] = score.precision;
  state.counters["ari"] = score.adjusted_rand_index;
  state.counters["planted"] = static_cast<double>(score.planted);
  state.counters["found"] = static_cast<double>(score.found);
  state.counters["found_motifs"] = static_cast<double>(score.found_motifs);
  state.counters["candidates"] = static_cast<double>(candidates);
  state.counters["eps"] = eps;
  std::filesystem::remove_all(dir);
}

BENCHMARK(BM_PlantedMotifs)
    ->ArgNames({"frames", "motifs", "seed"})
    ->Args({60000, 10, 3})
    ->Args({60000, 10, 4})
    ->Args({60000, 10, 5})
    ->Args({120000, 12, 6})
    ->Args({200000, 20, 8})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
