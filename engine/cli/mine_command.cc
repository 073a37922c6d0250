// `motifmine mine [INPUT...] --out DIR`: the whole job, end to end, through MinePipeline
// (engine/pipeline/mine_pipeline.h: the stages, their reuse and resumption, the folder lock):
// reads the options, shows one progress display across the stages, and prints a one-screen
// summary.

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/pipeline/mine_pipeline.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// Standard output and error sent to /dev/null while it lives (the other ranks of a distributed
// run: their usage errors are rank 0's, printed once).
class SilencedOutput {
 public:
  SilencedOutput() {
    std::fflush(stdout);
    std::fflush(stderr);
    saved_out_ = dup(STDOUT_FILENO);
    saved_err_ = dup(STDERR_FILENO);
    const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
      close(null);
    }
  }
  ~SilencedOutput() {
    std::fflush(stdout);
    std::fflush(stderr);
    if (saved_out_ >= 0) dup2(saved_out_, STDOUT_FILENO), close(saved_out_);
    if (saved_err_ >= 0) dup2(saved_err_, STDERR_FILENO), close(saved_err_);
  }
  SilencedOutput(const SilencedOutput&) = delete;
  SilencedOutput& operator=(const SilencedOutput&) = delete;

 private:
  int saved_out_ = -1;
  int saved_err_ = -1;
};

// The stages' progress on one display: a stage begins when the pipeline first reports it.
class StageProgress {
 public:
  explicit StageProgress(ProgressReporter* reporter) : reporter_(reporter) {}
  ~StageProgress() { End(); }
  void Update(const std::string& stage, uint64_t done, uint64_t total, const std::string& unit) {
    if (stage != stage_) {
      End();
      reporter_->BeginStage(stage, total, unit);
      stage_ = stage;
    }
    reporter_->Update(done);
  }
  void End() {
    if (!stage_.empty()) reporter_->EndStage();
    stage_.clear();
  }

 private:
  ProgressReporter* reporter_;
  std::string stage_;
};

// A distributed run's ranks: the bytes each sent building the trellis (features, index shares,
// blocks), and how long rank 0 waited for the others' blocks.
void PrintRanks(const TrellisReport& trellis) {
  if (trellis.rank_bytes_sent.empty()) return;
  std::string sent;
  std::string searched;
  for (size_t rank = 0; rank < trellis.rank_bytes_sent.size(); ++rank) {
    sent += (rank ? ", " : "") + std::to_string(rank) + ": " +
            FormatBytes(trellis.rank_bytes_sent[rank]);
  }
  for (size_t rank = 0; rank < trellis.rank_search_seconds.size(); ++rank) {
    char part[32];
    std::snprintf(part, sizeof part, "%s%zu: %.1fs", rank ? ", " : "", rank,
                  trellis.rank_search_seconds[rank]);
    searched += part;
  }
  std::printf("  ranks        %zu; sent by rank %s; rank 0 waited %.1fs for blocks\n",
              trellis.rank_bytes_sent.size(), sent.c_str(), trellis.receive_wait_seconds);
  if (!searched.empty()) std::printf("  searching    by rank %s\n", searched.c_str());
  if (!trellis.reused) {
    std::printf("  trellis      features %.1fs, eps %.1fs, index %.1fs, columns %.1fs\n",
                trellis.features_seconds, trellis.eps_seconds, trellis.index_seconds,
                trellis.search_seconds);
  }
}

void PrintSummary(const MinePipelineResult& result) {
  const MotifsDocument& document = result.document;
  uint64_t instances = 0;
  uint64_t instance_frames = 0;
  for (const MotifsJsonMotif& motif : document.motifs) {
    instances += motif.instances.size();
    for (const MotifsJsonInstance& instance : motif.instances) instance_frames += instance.length();
  }
  const double fps = result.fps;
  const TrellisReport& trellis = result.trellis;
  std::printf("motifmine mine: %s\n", result.archive_path.c_str());
  std::printf("  archive      %s frames (%s at %g fps) in %s\n", WithCommas(result.frames).c_str(),
              FormatDuration(static_cast<double>(result.frames) / fps).c_str(), fps,
              CountOf(result.clips, "clip").c_str());
  std::printf("  radius       eps %.3f: %s (the paper's mu - 2 sigma would be %.3f)\n",
              trellis.params.eps, trellis.eps_how.c_str(), trellis.paper_eps);
  std::printf("  trellis      mean K %.1f of k_max %u, %s search\n", trellis.mean_k,
              trellis.params.k_max, TrellisSearchModeName(trellis.search));
  std::printf("  paths        %s candidates (B %u, min length %llu frames)\n",
              WithCommas(result.paths.candidates).c_str(), result.paths.params.branch,
              static_cast<unsigned long long>(result.paths.params.min_length));
  std::printf("  motifs       %s, %s, mean %.1f s, covering %s of the archive\n",
              CountOf(document.motifs.size(), "motif").c_str(),
              CountOf(instances, "instance").c_str(),
              instances ? static_cast<double>(instance_frames) / instances / fps : 0.0,
              Percent(document.covered_frames, result.frames).c_str());
  for (size_t rank = 0; rank < std::min<size_t>(5, document.motifs.size()); ++rank) {
    const MotifsJsonMotif& motif = document.motifs[rank];
    uint64_t length = 0;
    for (const MotifsJsonInstance& instance : motif.instances) length += instance.length();
    std::printf("    motif %-4zu %3zu instances, mean %.2f s, e.g. %s [%llu, %llu)\n", rank,
                motif.instances.size(),
                static_cast<double>(length) / static_cast<double>(motif.instances.size()) / fps,
                motif.instances.front().clip.c_str(),
                static_cast<unsigned long long>(motif.instances.front().start),
                static_cast<unsigned long long>(motif.instances.front().end));
  }
  std::string timing;
  for (const MineStageTime& time : result.times) {
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.1fs%s", timing.empty() ? "" : ", ", time.stage.c_str(),
                  time.seconds, time.reused ? " (reused)" : "");
    timing += part;
  }
  std::printf("  time         %s; total %.1fs\n", timing.c_str(), result.total_seconds);
  std::printf("  memory       peak resident %s\n", FormatBytes(PeakResidentBytes()).c_str());
  PrintRanks(trellis);
  if (result.score) {
    const PlantedMotifScore& score = *result.score;
    std::printf("  planted      %u motifs as %s instances (%s)\n", score.planted_motifs,
                WithCommas(score.planted).c_str(), result.truth_path.c_str());
    std::printf("  recall       %.3f  (%s of %s planted instances found)\n", score.recall,
                WithCommas(score.planted_hit).c_str(), WithCommas(score.planted).c_str());
    std::printf("  precision    %.3f  (%s of %s found instances are planted ones)\n",
                score.precision, WithCommas(score.found_hitting).c_str(),
                WithCommas(score.found).c_str());
    std::printf("  grouping     ARI %.3f  (found motif vs planted motif of the hit instances)\n",
                score.adjusted_rand_index);
  }
  std::printf("  wrote        %s", result.motifs_path.c_str());
  if (!result.instances_path.empty()) std::printf(", %s", result.instances_path.c_str());
  if (!result.report_path.empty()) {
    std::printf(", %s (open it in a browser)", result.report_path.c_str());
  }
  std::printf("\n");
}

}  // namespace

namespace {

// A rank of a distributed run other than rank 0, which reports for all.
bool IsOtherRank(const MineAcrossRanks& across) {
  return across.ranks != nullptr && across.ranks->rank() != 0;
}

const char kMineSummary[] =
    "Mines the recurring motions of an archive end to end: the matching trellis (eps-NN of\n"
    "every frame), the continuous paths through it, their clustering into motifs, and a\n"
    "report. INPUT is an archive (.mfs) or BVH / ASF+AMC takes and folders (imported into\n"
    "DIR/archive.mfs); with no INPUT a built-in synthetic archive with planted motifs is\n"
    "mined and the planted motifs are scored. Writes DIR/motifs.json, DIR/report.html and a\n"
    "summary. A second run reuses every stage whose inputs and parameters did not change.";

CommandSpec MineCommandSpec() {
  CommandSpec spec;
  spec.name = "mine";
  spec.usage = "motifmine mine [INPUT...] --out DIR [options]";
  spec.summary = kMineSummary;
  spec.options.add_options()("out", po::value<std::string>(), "output folder (created if missing)");
  AddTableFlags(spec, AllTableFlags());
  AddProgressOptions(spec);
  AddVerboseOption(spec);
  spec.positional = {{"input", -1}};
  return spec;
}

// The run's options and inputs from the command line; -1, or the exit code of a usage error.
int ReadMineCommand(const CommandSpec& spec, const po::variables_map& vm,
                    const MineAcrossRanks& across, motifmine::MineOptions* options,
                    std::vector<std::string>* inputs) {
  if (!vm.count("out")) {
    std::fprintf(stderr, "motifmine mine: error: --out DIR is required\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  ReadTableFlags(spec, vm, options);
  options->out_dir = vm["out"].as<std::string>();
  if (options->threads == 0) options->threads = across.default_threads;
  if (vm.count("input")) *inputs = vm["input"].as<std::vector<std::string>>();
  return -1;
}

// The summary, and the takes --skip-bad passed over: exit 3 when there were any.
int FinishMine(const MinePipelineResult& result, const po::variables_map& vm) {
  PrintSummary(result);
  if (result.skipped_takes.empty()) return kExitOk;
  std::printf("  skipped      %s (--skip-bad; named on stderr)\n",
              CountOf(result.skipped_takes.size(), "bad take").c_str());
  ReportSkippedTakes("mine", result.skipped_takes, ProgressModeFrom(vm));
  return kExitWarnings;  // mined the good takes
}

// `mine`, on one process or on a rank of a distributed run.
int RunMineCommand(const std::vector<std::string>& args, const MineAcrossRanks& across) {
  // Another rank of a distributed run prints nothing but an error of its own: rank 0 reports.
  const bool other_rank = IsOtherRank(across);
  std::optional<SilencedOutput> silenced;
  if (other_rank) silenced.emplace();
  CommandSpec spec = MineCommandSpec();
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  motifmine::MineOptions options;
  std::vector<std::string> inputs;
  if (int code = ReadMineCommand(spec, vm, across, &options, &inputs); code >= 0) return code;

  ProgressReporter progress(other_rank ? ProgressMode::kQuiet : ProgressModeFrom(vm));
  StageProgress stages(&progress);
  RunHooks hooks;
  hooks.ranks = across.ranks;
  hooks.on_shared_failure = [&](const Status& status) {
    silenced.reset();
    const int code = ReportError("mine", status);
    if (across.abort_all) across.abort_all(code);
  };
  hooks.progress = [&](const std::string& stage, uint64_t done, uint64_t total,
                       const std::string& unit) { stages.Update(stage, done, total, unit); };
  hooks.note = [&](const std::string& message) {
    if (!other_rank) progress.Note(message);
  };
  if (vm.count("verbose")) hooks.detail = hooks.note;
  Result<MinePipelineResult> result = RunMine(options, inputs, std::move(hooks));
  stages.End();
  if (!result.ok()) return ReportError("mine", result.status());
  return FinishMine(*result, vm);
}

}  // namespace

int RunMine(const std::vector<std::string>& args) { return RunMineAcrossRanks(args, {}); }

int RunMineAcrossRanks(const std::vector<std::string>& args, const MineAcrossRanks& across) {
  const int code = RunMineCommand(args, across);
  // Another rank's failures that reach here are rank 0's too (a usage error, or rank 0's own,
  // which it sent): rank 0's exit code is the job's, and it gets to print before mpirun ends
  // the job. A rank's own failures end the job on the spot (on_shared_failure).
  return IsOtherRank(across) ? kExitOk : code;
}

}  // namespace motif::cli
