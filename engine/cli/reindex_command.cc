// motifmine reindex ARCHIVE --watch DIR --out OUTDIR: the cron job. Imports the takes of DIR
// that are not yet in ARCHIVE, brings the matching trellis up to date incrementally, grows and
// clusters the paths again, and switches OUTDIR to the new version atomically (Reindex,
// engine/reindex/reindexer.h). Exit codes for cron: 0 done (or already up to date), 3 done but
// some files were not imported (changed since their import, or malformed with --skip-bad), 17
// another run holds OUTDIR (nothing changed), 2 usage, 10 + status code for failures (the
// current version is then unchanged).
#include <cmath>
#include <cstdio>
#include <mutex>

#include <nlohmann/json.hpp>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/reindex/reindexer.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// How the recorded eps was chosen, for the summary.
std::string EpsOrigin(const MiningParams& params) {
  if (!params.eps_estimated) return "given";
  if (params.eps_rule == "joint-angle") {
    char text[96];
    std::snprintf(text, sizeof text, "joint-angle rule, %g degrees", params.eps_angle_degrees);
    return text;
  }
  if (params.eps_rule == "paper") return "paper rule, mu - 2 sigma";
  return "estimated at the first build";
}

// The engine's (stage, done, total, unit) calls as ProgressReporter stages: a new stage name
// ends the previous stage and begins the next.
class StageProgress {
 public:
  explicit StageProgress(ProgressReporter* reporter) : reporter_(reporter) {}
  ~StageProgress() { End(); }

  void Update(const std::string& stage, uint64_t done, uint64_t total, const std::string& unit) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stage != stage_) {
      if (!stage_.empty()) reporter_->EndStage();
      stage_ = stage;
      reporter_->BeginStage(stage, total, unit);
    }
    reporter_->Update(done);
  }
  void End() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stage_.empty()) reporter_->EndStage();
    stage_.clear();
  }

 private:
  ProgressReporter* reporter_;
  std::mutex mutex_;
  std::string stage_;
};

// The JSON summary line (--progress=json) and its human form.
void PrintSummary(const ReindexReport& report, int exit_code, bool json) {
  const ReindexManifest& manifest = report.manifest;
  if (json) {
    nlohmann::json line = {{"event", "reindex"},
                           {"exit_code", exit_code},
                           {"up_to_date", report.up_to_date},
                           {"waiting", report.waiting},
                           {"version", manifest.version},
                           {"build", report.up_to_date ? "none" : manifest.build.kind},
                           {"takes_imported", report.takes_imported},
                           {"frames_imported", report.frames_imported},
                           {"takes_known", report.takes_known},
                           {"changed", report.changed},
                           {"failed", report.failed},
                           {"warnings", report.warnings},
                           {"settling", report.settling.size()},
                           {"archive_frames", manifest.archive.frames},
                           {"archive_clips", manifest.archive.clips},
                           {"changed_columns", manifest.build.changed_columns},
                           {"copied_blocks", manifest.build.copied_blocks},
                           {"rewritten_blocks", manifest.build.rewritten_blocks},
                           {"removed_versions", report.removed_versions},
                           {"seconds",
                            {{"import", report.import_seconds},
                             {"trellis", report.trellis_seconds},
                             {"grow", report.grow_seconds},
                             {"cluster", report.cluster_seconds},
                             {"report", report.report_seconds},
                             {"total", report.total_seconds}}},
                           {"motifs", manifest.motifs.path}};
    std::printf("%s\n", line.dump().c_str());
    return;
  }
  if (report.waiting) {
    std::printf(
        "motifmine reindex: waiting: no archive yet, and the %s take(s) found are younger than "
        "--min-age (still being copied?); the next run imports them\n",
        WithCommas(report.settling.size()).c_str());
  } else if (report.up_to_date) {
    std::printf(
        "motifmine reindex: up to date (version %llu, %s frames in %s clips; %s takes "
        "already imported)\n",
        static_cast<unsigned long long>(manifest.version),
        WithCommas(manifest.archive.frames).c_str(), WithCommas(manifest.archive.clips).c_str(),
        WithCommas(report.takes_known).c_str());
  } else {
    std::printf("motifmine reindex: version %llu (%s build)\n",
                static_cast<unsigned long long>(manifest.version), manifest.build.kind.c_str());
    std::printf("  takes        %s imported (%s frames), %s already in the archive\n",
                WithCommas(report.takes_imported).c_str(),
                WithCommas(report.frames_imported).c_str(), WithCommas(report.takes_known).c_str());
    std::printf("  archive      %s frames in %s clips (generation %llu)\n",
                WithCommas(manifest.archive.frames).c_str(),
                WithCommas(manifest.archive.clips).c_str(),
                static_cast<unsigned long long>(manifest.archive.generation));
    if (manifest.build.kind == "incremental") {
      std::printf(
          "  trellis      %s new frames; %s old columns changed; %s blocks copied, %s "
          "rewritten\n",
          WithCommas(manifest.build.new_frames).c_str(),
          WithCommas(manifest.build.changed_columns).c_str(),
          WithCommas(manifest.build.copied_blocks).c_str(),
          WithCommas(manifest.build.rewritten_blocks).c_str());
    }
    std::printf("  eps          %.6g (%s), k_max %u, %s search\n", manifest.params.eps,
                EpsOrigin(manifest.params).c_str(), manifest.params.k_max,
                manifest.params.exact ? "exact" : "lsh");
    std::printf(
        "  time         import %.1fs, trellis %.1fs, grow %.1fs, cluster %.1fs, report "
        "%.1fs; total %.1fs\n",
        report.import_seconds, report.trellis_seconds, report.grow_seconds, report.cluster_seconds,
        report.report_seconds, report.total_seconds);
    std::printf("  wrote        %s (current: manifest.json, motifs.json)\n", manifest.dir.c_str());
  }
  for (const std::string& changed : report.changed) {
    std::fprintf(stderr, "motifmine reindex: warning: %s\n", changed.c_str());
  }
  for (const std::string& failed : report.failed) {
    std::fprintf(stderr, "motifmine reindex: warning: not imported: %s\n", failed.c_str());
  }
  for (const std::string& warning : report.warnings) {
    std::fprintf(stderr, "motifmine reindex: warning: %s\n", warning.c_str());
  }
}

CommandSpec ReindexCommandSpec() {
  CommandSpec spec;
  spec.name = "reindex";
  spec.usage = "motifmine reindex ARCHIVE --watch DIR --out OUTDIR [options]";
  spec.summary =
      "The nightly job: imports the takes in DIR not yet in ARCHIVE (known by content hash; a\n"
      "file changed since its import is reported, not imported), updates the matching trellis\n"
      "incrementally (the new frames' columns and the old columns they enter), grows and\n"
      "clusters the paths again, and switches OUTDIR to the new version atomically\n"
      "(OUTDIR/manifest.json; OUTDIR/motifs.json is the current motifs). Parameters are recorded\n"
      "at the first run and reused; changing one rebuilds what depends on it. Exit codes: 0\n"
      "done or up to date, 3 done with files not imported, 17 another run holds OUTDIR.";
  spec.options.add_options()("watch", po::value<std::string>(),
                             "folder of BVH / ASF+AMC takes (searched recursively)")(
      "out", po::value<std::string>(), "output folder (created if missing)");
  for (const std::vector<std::string>* flags :
       {&kRadiusFlags, &kTrellisFlags, &kLshFlags, &kGrowFlags, &kClusterFlags}) {
    AddTableFlags(spec, *flags, TableDefaults::kRecorded);
  }
  AddTableFlags(spec, {"seed"}, TableDefaults::kRecorded);
  AddTableFlags(spec, {"threads", "skip-bad", "no-report"});
  spec.options.add_options()(
      "min-age", NumberWithDefault(60),
      "seconds since a take's last change before it is imported (files still being copied "
      "wait for the next run)")("fps", NumberWithDefault(0),
                                "frame rate of a NEW archive")(
      "first-frame", po::value<std::string>()->default_value("auto"),
      "auto: drop a first frame that is a converter's T-pose; keep; drop");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  return spec;
}

// The run's options from the command line; -1, or the exit code of a usage error or a failure.
int ReadReindexCommand(const CommandSpec& spec, const po::variables_map& vm,
                       ReindexOptions* options) {
  if (!vm.count("watch") || !vm.count("out")) {
    std::fprintf(stderr,
                 "motifmine reindex: error: --watch DIR and --out OUTDIR are required\n"
                 "usage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  options->archive_path = vm["archive"].as<std::string>();
  options->watch_dir = vm["watch"].as<std::string>();
  options->out_dir = vm["out"].as<std::string>();
  ReadTableFlags(spec, vm, &options->mine, &options->given);
  options->min_age_seconds = vm["min-age"].as<double>();
  if (Status status =
          ParseFirstFrame(vm["first-frame"].as<std::string>(), &options->import.first_frame);
      !status.ok()) {
    return ReportError("reindex", status);
  }
  return -1;
}

}  // namespace

int RunReindex(const std::vector<std::string>& args) {
  CommandSpec spec = ReindexCommandSpec();
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  ReindexOptions options;
  if (int code = ReadReindexCommand(spec, vm, &options); code >= 0) return code;
  const ProgressMode mode = ProgressModeFrom(vm);
  ProgressReporter reporter(mode);
  StageProgress stages(&reporter);
  options.progress = [&](const std::string& stage, uint64_t done, uint64_t total,
                         const std::string& unit) { stages.Update(stage, done, total, unit); };
  options.note = [&](const std::string& message) { reporter.Note(message); };
  Result<ReindexReport> report = Reindex(options);
  stages.End();
  if (!report.ok()) {
    const int code = ReportError("reindex", report.status());
    if (mode == ProgressMode::kJson) {
      nlohmann::json line = {
          {"event", "reindex"}, {"exit_code", code}, {"error", FlagMessage(report.status())}};
      std::printf("%s\n", line.dump().c_str());
    }
    return code;
  }
  const int code = report->changed.empty() && report->failed.empty() && report->warnings.empty()
                       ? kExitOk
                       : kExitWarnings;
  PrintSummary(*report, code, mode == ProgressMode::kJson);
  return code;
}

}  // namespace motif::cli
