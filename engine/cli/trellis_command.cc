// motifmine trellis ARCHIVE [...]: builds (or reuses, or resumes) the matching trellis, or
// audits it against exact eps-NN with --audit.
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/pipeline/stage_options.h"
#include "engine/trellis/trellis_audit.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

int RunAudit(const po::variables_map& vm, const std::string& archive, const std::string& trellis,
             const motifmine::MineOptions& mine, ProgressReporter* progress) {
  AuditOptions options;
  options.sample_columns = vm["sample"].as<uint64_t>();
  options.seed = mine.seed;
  options.threads = mine.threads;
  options.weights_path = mine.weights_path;
  Result<LshOptions> lsh = LshOptionsFor(mine);
  if (!lsh.ok()) return ReportError("trellis", lsh.status());
  options.lsh = *lsh;
  bool started = false;
  options.progress = [&](uint64_t done, uint64_t total) {
    if (!started) progress->BeginStage("audit", total, "columns");
    started = true;
    progress->Update(done);
  };
  Result<AuditReport> report = AuditTrellis(archive, trellis, options);
  if (started) progress->EndStage();
  if (!report.ok()) return ReportError("trellis", report.status());
  std::printf("audit of %s (%s)\n", trellis.c_str(), report->search_params.c_str());
  std::printf("  sampled columns       %s\n", WithCommas(report->sampled_columns).c_str());
  std::printf("  recall                %.4f  (%s of %s exact entries after the k_max cap)\n",
              report->recall, WithCommas(report->found_entries).c_str(),
              WithCommas(report->exact_entries).c_str());
  std::printf("  column recall         mean %.4f, min %.4f\n", report->mean_column_recall,
              report->min_column_recall);
  std::printf("  exact columns capped  %s (more than k_max within eps)\n",
              WithCommas(report->capped_exact_columns).c_str());
  auto share = [](uint64_t part, uint64_t whole) {
    return whole ? static_cast<double>(part) / static_cast<double>(whole) : 1.0;
  };
  std::printf("  recall, uncapped      %.4f  (%s of %s: every frame within eps)\n",
              share(report->uncapped_found_entries, report->uncapped_exact_entries),
              WithCommas(report->uncapped_found_entries).c_str(),
              WithCommas(report->uncapped_exact_entries).c_str());
  std::printf(
      "  recall, capped        %.4f  (%s of %s: the k_max nearest; %s of %s trellis "
      "columns full, with k_max verified frames within eps)\n",
      share(report->capped_found_entries, report->capped_exact_entries),
      WithCommas(report->capped_found_entries).c_str(),
      WithCommas(report->capped_exact_entries).c_str(),
      WithCommas(report->capped_columns_full).c_str(),
      WithCommas(report->capped_exact_columns).c_str());
  std::printf("  distance evaluations  %.0f per query (exact: %.0f)",
              report->lsh_evaluations_per_query, report->exact_evaluations_per_query);
  if (report->lsh_timed_columns > 0) {
    std::printf("  [LSH: over the %s columns of the chains of 16 sampled columns]",
                WithCommas(report->lsh_timed_columns).c_str());
  }
  std::printf("\n");
  if (report->lsh_seconds_per_query > 0) {
    std::printf("  time per query        %.3f ms (exact: %.3f ms, %.1fx)\n",
                1e3 * report->lsh_seconds_per_query, 1e3 * report->exact_seconds_per_query,
                report->exact_seconds_per_query / report->lsh_seconds_per_query);
  }
  return kExitOk;
}

CommandSpec TrellisCommandSpec() {
  CommandSpec spec;
  spec.name = "trellis";
  spec.usage =
      "motifmine trellis ARCHIVE [--eps X|auto] [--kmax K] [--exclusion F] "
      "[--search auto|lsh|exact] [--threads T] [--seed S] | --audit [--sample Q]";
  spec.summary =
      "Builds the matching trellis of ARCHIVE beside it (ARCHIVE.mtr): for every frame, the\n"
      "frames whose weighted pose distance is at most eps (at most K_max, the nearest), found\n"
      "with LSH (by exact brute force on archives below " +
      std::to_string(kAutoExactMaxFrames) +
      " frames, where it is faster),\n"
      "and written to disk block by block. A finished trellis with the same parameters is\n"
      "reused; an interrupted build resumes. --audit compares the trellis with exact eps-NN on\n"
      "sampled columns and prints the recall.";
  AddTableFlags(spec, kRadiusFlags);
  AddTableFlags(spec, kTrellisFlags);
  AddTableFlags(spec, {"min-length"});
  AddTableFlags(spec, kRunFlags);
  AddTableFlags(spec, kLshFlags);
  spec.options.add_options()("exact", "the same as --search exact")(
      "out", po::value<std::string>()->default_value(""), "trellis path (default ARCHIVE.mtr)")(
      "audit", "compare the existing trellis with exact eps-NN on sampled columns")(
      "sample", po::value<uint64_t>()->default_value(1000), "columns sampled by --audit");
  AddProgressOptions(spec);
  AddVerboseOption(spec);
  spec.positional = {{"archive", 1}};
  return spec;
}

// Each stage reports (0 or its resume point, total) first and (total, total) last.
class TrellisStageProgress {
 public:
  explicit TrellisStageProgress(ProgressReporter* progress) : progress_(progress) {}
  ~TrellisStageProgress() {
    if (!stage_.empty()) progress_->EndStage();
  }
  void Update(const std::string& name, uint64_t done, uint64_t total) {
    if (name != stage_) {
      if (!stage_.empty()) progress_->EndStage();
      stage_ = name;
      progress_->BeginStage(name, total, name == "trellis" ? "columns" : "frames");
    }
    progress_->Update(done);
    if (done == total) {
      progress_->EndStage();
      stage_.clear();
    }
  }

 private:
  ProgressReporter* progress_;
  std::string stage_;
};

void PrintTrellisReport(const std::string& trellis, const TrellisReport& report) {
  const TrellisParams& params = report.params;
  if (report.reused) {
    std::printf("%s is up to date (same archive and parameters): reused\n", trellis.c_str());
  } else {
    std::printf("wrote %s\n", trellis.c_str());
  }
  std::printf("  eps          %.4f  (%s; the paper's mu - 2 sigma: %.4f)\n", params.eps,
              report.eps_how.c_str(), report.paper_eps);
  std::printf("  columns      %s, %s entries, mean K %.1f (k_max %u)\n",
              WithCommas(report.columns).c_str(), WithCommas(report.neighbours).c_str(),
              report.mean_k, params.k_max);
  std::printf("  exclusion    %u frames of the same clip\n", params.exclusion_frames);
  std::printf("  search       %s\n", params.search_params.c_str());
  if (report.reused) return;
  std::printf("  capped       %s columns had more than k_max neighbours within eps\n",
              WithCommas(report.capped_columns).c_str());
  std::printf("  evaluations  %.0f exact distances per column\n",
              report.columns
                  ? static_cast<double>(report.distance_evaluations) /
                        std::max<uint64_t>(1, report.columns - report.resumed_from_column)
                  : 0.0);
  std::printf(
      "  time         features %.1fs, eps %.1fs, index %.1fs, columns %.1fs (writes "
      "%.1fs beside the search, %.1fs waited for)\n",
      report.features_seconds, report.eps_seconds, report.index_seconds, report.search_seconds,
      report.write_seconds, report.write_wait_seconds);
}

}  // namespace

int RunTrellis(const std::vector<std::string>& args) {
  CommandSpec spec = TrellisCommandSpec();
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string archive_path = vm["archive"].as<std::string>();
  std::string trellis = vm["out"].as<std::string>();
  if (trellis.empty()) trellis = DefaultTrellisPath(archive_path);
  motifmine::MineOptions mine;
  ReadTableFlags(spec, vm, &mine);
  if (vm.count("exact")) {
    if (mine.search == "lsh") {
      std::fprintf(stderr,
                   "motifmine trellis: --exact and --search lsh contradict each other\n"
                   "usage: %s\n",
                   spec.usage.c_str());
      return kExitUsage;
    }
    mine.search = "exact";
  }
  ProgressReporter progress(ProgressModeFrom(vm));
  if (vm.count("audit")) return RunAudit(vm, archive_path, trellis, mine, &progress);
  Result<std::unique_ptr<FrameFileReader>> archive = FrameFileReader::Open(archive_path);
  if (!archive.ok()) return ReportError("trellis", archive.status());
  Result<TrellisOptions> options = TrellisOptionsFor(mine, (*archive)->fps());
  if (!options.ok()) return ReportError("trellis", options.status());
  TrellisStageProgress stages(&progress);
  options->progress = [&](const std::string& name, uint64_t done, uint64_t total) {
    stages.Update(name, done, total);
  };
  options->note = [&](const std::string& message) { progress.Note(message); };
  if (vm.count("verbose")) options->detail = options->note;
  Result<TrellisReport> report = BuildTrellis(**archive, trellis, *options);
  if (!report.ok()) return ReportError("trellis", report.status());
  PrintTrellisReport(trellis, *report);
  return kExitOk;
}

}  // namespace motif::cli
