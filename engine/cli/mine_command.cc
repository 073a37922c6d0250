// `motifmine mine [INPUT...] --out DIR`: the whole job, end to end. INPUT is an archive (.mfs),
// or BVH / ASF+AMC takes and folders (imported into DIR/archive.mfs); with no INPUT, a built-in
// synthetic archive with planted motifs is written to DIR/archive.mfs (and its truth). Then the
// trellis (DIR/trellis.mtr), the paths (DIR/paths.mpa), the motifs (DIR/motifs.json) and the
// report (DIR/report.html), with one progress display across the stages and a one-screen
// summary.
//
// Resumable and incremental by stage: the trellis and the paths record the archive identity and
// their parameters and are reused when they match (an interrupted trellis resumes after its last
// block); clustering is reused when DIR/mine_state.json says it ran on the same paths file with
// the same options; the synthetic archive when its truth has the same options; an import skips
// takes already in the archive. Changing one parameter reruns only the stages after it. A run
// killed at any point (SIGKILL included) and started again gives the same motifs.json; it first
// removes the temporary files a dead run left in DIR (RemoveStaleTemporaries). One run at a time
// per DIR: DIR/.motifmine.lock (flock) is held for the whole run; a second run exits at once with
// exit code 17 (busy).

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/file_lock.h"
#include "common/file_util.h"
#include "common/seconds_since.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/synthetic_archive.h"
#include "engine/cluster/cluster_stage.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/cluster/planted_motif_score.h"
#include "engine/grow/paths_builder.h"
#include "engine/ingest/archive_import.h"
#include "engine/report/report_html.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/truth_json_reader.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/paths_file/paths_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

using Clock = std::chrono::steady_clock;

// The file a run holds an exclusive flock on, in its output folder.
constexpr char kRunLockName[] = ".motifmine.lock";

std::string Join(const std::filesystem::path& dir, const char* name) {
  return (dir / name).string();
}

struct StageTime {
  std::string stage;
  double seconds = 0;
  bool reused = false;
};

// The synthetic archive of a run with no INPUT: reused when its truth says it was made with the
// same options.
Status MakeSyntheticArchive(const std::string& archive, const SynthOptions& options,
                            ProgressReporter* progress, bool* reused) {
  const std::string truth_path = TruthPathFor(archive);
  std::error_code error;
  if (std::filesystem::exists(archive, error)) {
    Result<TruthFile> truth = ReadTruthJson(truth_path);
    if (truth.ok() && truth->frames == options.frames && truth->seed == options.seed &&
        truth->motifs == options.motifs && FrameFileReader::Open(archive).ok()) {
      *reused = true;
      return Status::Ok();
    }
  }
  *reused = false;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         MotionSynthesizer::Create(options));
  return WriteSyntheticArchive(archive, *synthesizer, options,
                               FrameFileWriterOptions{}.block_frames, progress)
      .status();
}

// The files this command writes in DIR, whose temporary files a killed run may have left.
const std::vector<std::string> kOwnedFiles = {
    "archive.mfs", "archive.truth.json", "trellis.mtr", "paths.mpa",
    "motifs.json", "mine_state.json",    "report.html"};

}  // namespace

int RunMine(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "mine";
  spec.usage = "motifmine mine [INPUT...] --out DIR [options]";
  spec.summary =
      "Mines the recurring motions of an archive end to end: the matching trellis (eps-NN of\n"
      "every frame), the continuous paths through it, their clustering into motifs, and a\n"
      "report. INPUT is an archive (.mfs) or BVH / ASF+AMC takes and folders (imported into\n"
      "DIR/archive.mfs); with no INPUT a built-in synthetic archive with planted motifs is\n"
      "mined and the planted motifs are scored. Writes DIR/motifs.json, DIR/report.html and a\n"
      "summary. A second run reuses every stage whose inputs and parameters did not change.";
  spec.options.add_options()("out", po::value<std::string>(), "output folder (created if missing)")(
      "eps", po::value<float>()->default_value(0), "pose distance threshold; 0: by --eps-rule")(
      "kmax", po::value<uint32_t>()->default_value(256), "neighbours kept per frame, nearest")(
      "exclusion", po::value<uint32_t>()->default_value(0),
      "same-clip exclusion radius in frames; 0: half the minimum length")(
      "search", po::value<std::string>()->default_value("auto"),
      "neighbour search: auto (exact on small archives), lsh or exact")(
      "tables", po::value<uint32_t>()->default_value(LshOptions{}.tables), "LSH hash tables")(
      "hashes", po::value<uint32_t>()->default_value(0),
      "LSH projections per table (0: from the archive's size)")(
      "width", po::value<float>()->default_value(0), "LSH bucket width (0: from the data)")(
      "branch", po::value<uint32_t>()->default_value(PathsOptions{}.branch),
      "branching factor B of the path grower")("min-length",
                                               po::value<std::string>()->default_value("0.5s"),
                                               "least motif length: frames (60) or seconds (0.5s)")(
      "groups", po::value<std::string>()->default_value("auto"), "number of motifs, or auto")(
      "similarity", po::value<std::string>()->default_value("warped"),
      "how instance pairs are weighted for the normalized cut: warped (the time-warped distance of "
      "their motions, each instance scaled by its nearest repetition) or shared (the similar "
      "frames they share, as in the paper)")(
      "max-length-ratio", po::value<double>()->default_value(ClusterOptions{}.max_length_ratio),
      "drop an instance from its motif when its length is more than this factor from the "
      "motif's median (0 keeps all)")("seed", po::value<uint64_t>()->default_value(1),
                                      "seed of every random choice")(
      "threads", po::value<int>()->default_value(0), "threads (0: all cores)")(
      "synth-frames", po::value<uint64_t>()->default_value(120000),
      "no INPUT: frames of the synthetic archive")(
      "synth-motifs", po::value<uint32_t>()->default_value(12),
      "no INPUT: planted motifs of the synthetic archive")(
      "skip-bad", "import: report malformed takes and import the others")(
      "no-report", "do not write report.html");
  AddEpsilonRuleOptions(spec);
  AddPauseOptions(spec);
  AddProgressOptions(spec);
  spec.positional = {{"input", -1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!vm.count("out")) {
    std::fprintf(stderr, "motifmine mine: error: --out DIR is required\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  const std::filesystem::path out_dir = vm["out"].as<std::string>();
  const std::vector<std::string> inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  const uint64_t seed = vm["seed"].as<uint64_t>();
  const int threads = vm["threads"].as<int>();
  const auto fail = [](const Status& status) { return ReportError("mine", status); };

  // Every parameter is checked before any work.
  TrellisOptions trellis_options;
  trellis_options.eps = vm["eps"].as<float>();
  trellis_options.k_max = vm["kmax"].as<uint32_t>();
  trellis_options.exclusion_frames = vm["exclusion"].as<uint32_t>();
  trellis_options.seed = seed;
  trellis_options.threads = threads;
  if (Status status = EpsilonRuleFrom(vm, &trellis_options); !status.ok()) return fail(status);
  Result<TrellisSearchMode> search = ParseTrellisSearchMode(vm["search"].as<std::string>());
  if (!search.ok()) return fail(search.status());
  trellis_options.search = *search;
  trellis_options.lsh.tables = vm["tables"].as<uint32_t>();
  trellis_options.lsh.hashes_per_table = vm["hashes"].as<uint32_t>();
  trellis_options.lsh.bucket_width = vm["width"].as<float>();
  PathsOptions paths_options;
  paths_options.branch = vm["branch"].as<uint32_t>();
  if (Status status =
          ParseMinLength(vm["min-length"].as<std::string>(), &paths_options.min_length_frames,
                         &paths_options.min_length_seconds);
      !status.ok()) {
    return fail(status);
  }
  ClusterOptions cluster_options;
  cluster_options.seed = seed;
  cluster_options.threads = threads;
  const std::string groups_text = vm["groups"].as<std::string>();
  if (Status status = ParseGroups(groups_text, &cluster_options.cut.groups); !status.ok()) {
    return fail(status);
  }
  if (Status status =
          ParseSimilarity(vm["similarity"].as<std::string>(), &cluster_options.warped.enabled);
      !status.ok()) {
    return fail(status);
  }
  if (Status status = PauseOptionsFrom(vm, &cluster_options.pauses); !status.ok()) {
    return fail(status);
  }
  cluster_options.max_length_ratio = vm["max-length-ratio"].as<double>();
  if (!(cluster_options.max_length_ratio == 0 || cluster_options.max_length_ratio >= 1) ||
      !std::isfinite(cluster_options.max_length_ratio)) {
    return fail(Status::InvalidArgument("--max-length-ratio must be 0 (keep all) or >= 1"));
  }
  if (trellis_options.eps < 0 || !std::isfinite(trellis_options.eps)) {
    return fail(Status::InvalidArgument("--eps must be >= 0 (0: chosen by --eps-rule)"));
  }
  if (trellis_options.k_max == 0) return fail(Status::InvalidArgument("--kmax must be > 0"));
  if (paths_options.branch == 0) return fail(Status::InvalidArgument("--branch must be > 0"));

  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) {
    return fail(Status::IOError("cannot create " + out_dir.string() + ": " + error.message()));
  }
  // One run per folder: a second run (an overlapping cron job) leaves at once, before touching
  // anything, with exit code 17. The lock goes with the process, even on kill -9.
  ExclusiveFileLock run_lock;
  if (Status status = run_lock.Acquire(
          Join(out_dir, kRunLockName),
          "another motifmine run is working in this folder; nothing was changed (exit 17: try "
          "again when it has finished)",
          /*create=*/true);
      !status.ok()) {
    return fail(status);
  }
  RemoveStaleTemporaries(out_dir.string(), kOwnedFiles);
  ProgressReporter progress(ProgressModeFrom(vm));
  std::vector<StageTime> times;
  const Clock::time_point job_start = Clock::now();

  // Stage 1: the archive.
  std::string archive = Join(out_dir, "archive.mfs");
  std::string truth_path;
  Clock::time_point start = Clock::now();
  std::vector<std::string> skipped_takes;  // --skip-bad: the takes passed over
  if (inputs.empty()) {
    SynthOptions synth;
    synth.frames = vm["synth-frames"].as<uint64_t>();
    synth.motifs = vm["synth-motifs"].as<uint32_t>();
    synth.seed = seed;
    synth.threads = threads > 0 ? static_cast<uint32_t>(threads) : 0;
    // Background that does not repeat within eps, so the planted motifs are the only long
    // repeats and precision against them means something (docs/guide.md, synth).
    synth.background_variation_degrees = kRecommendedBackgroundVariation;
    bool reused = false;
    if (Status status = MakeSyntheticArchive(archive, synth, &progress, &reused); !status.ok()) {
      return fail(status);
    }
    truth_path = TruthPathFor(archive);
    times.push_back({"synth", SecondsSince(start), reused});
  } else if (inputs.size() == 1 && std::filesystem::path(inputs[0]).extension() == ".mfs") {
    archive = inputs[0];
    if (std::filesystem::exists(TruthPathFor(archive), error)) truth_path = TruthPathFor(archive);
  } else {
    ArchiveImportOptions import_options;
    import_options.skip_bad = vm.count("skip-bad") > 0;
    import_options.threads = threads;
    import_options.note = [&](const std::string& message) { progress.Note(message); };
    bool began = false;
    import_options.progress = [&](uint64_t done, uint64_t total) {
      if (!began) progress.BeginStage("import", total, "takes");
      began = true;
      progress.Update(done);
    };
    Result<ArchiveImportResult> imported = ImportIntoArchive(archive, inputs, import_options);
    if (began) progress.EndStage();
    if (!imported.ok()) return fail(imported.status());
    times.push_back({"import", SecondsSince(start), imported->takes_imported == 0});
    skipped_takes = imported->failures;
  }
  Result<std::unique_ptr<FrameFileReader>> frames = FrameFileReader::Open(archive);
  if (!frames.ok()) return fail(frames.status());
  // Every stage reads the version opened here, whatever another import appends meanwhile.
  trellis_options.archive_version = (*frames)->version();
  paths_options.archive_version = (*frames)->version();

  // Stage 2: the matching trellis.
  const std::string trellis_path = Join(out_dir, "trellis.mtr");
  std::string trellis_stage;
  trellis_options.min_length_seconds =
      paths_options.min_length_frames > 0
          ? static_cast<double>(paths_options.min_length_frames) / (*frames)->fps()
          : paths_options.min_length_seconds;
  trellis_options.progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (stage != trellis_stage) {
      if (!trellis_stage.empty()) progress.EndStage();
      trellis_stage = stage;
      progress.BeginStage(stage == "trellis" ? "trellis" : "trellis " + stage, total,
                          stage == "eps"       ? "pairs"
                          : stage == "trellis" ? "columns"
                                               : "frames");
    }
    progress.Update(done);
  };
  trellis_options.note = [&](const std::string& message) { progress.Note(message); };
  start = Clock::now();
  Result<TrellisReport> trellis = BuildTrellis(archive, trellis_path, trellis_options);
  if (!trellis_stage.empty()) progress.EndStage();
  if (!trellis.ok()) return fail(trellis.status());
  times.push_back({"trellis", SecondsSince(start), trellis->reused});

  // Stage 3: the paths.
  const std::string paths_path = Join(out_dir, "paths.mpa");
  bool grow_began = false;
  paths_options.progress = [&](uint64_t done, uint64_t total) {
    if (!grow_began) progress.BeginStage("grow", total, "columns");
    grow_began = true;
    progress.Update(done);
  };
  start = Clock::now();
  Result<PathsReport> paths = BuildPaths(archive, trellis_path, paths_path, paths_options);
  if (grow_began) progress.EndStage();
  if (!paths.ok()) return fail(paths.status());
  times.push_back({"grow", SecondsSince(start), paths->reused});

  // Stage 4: clustering, reused when the same paths were clustered with the same options.
  const std::string motifs_path = Join(out_dir, "motifs.json");
  start = Clock::now();
  ClusterStageInput cluster_input;
  cluster_input.archive_path = archive;
  cluster_input.archive = frames->get();
  cluster_input.trellis_path = trellis_path;
  cluster_input.paths_path = paths_path;
  cluster_input.paths_params = paths->params;
  cluster_input.candidates = paths->candidates;
  cluster_input.motifs_path = motifs_path;
  cluster_input.state_path = Join(out_dir, "mine_state.json");
  bool cluster_began = false;
  cluster_options.progress = [&](const std::string&, uint64_t done, uint64_t total) {
    if (!cluster_began) progress.BeginStage("cluster", total, "columns");
    cluster_began = true;
    progress.Update(done);
  };
  Result<ClusterStageResult> clustered = RunClusterStage(cluster_input, cluster_options);
  if (cluster_began) progress.EndStage();
  if (!clustered.ok()) return fail(clustered.status());
  const MotifsDocument& document = clustered->document;
  const bool cluster_reused = clustered->reused;
  times.push_back({"cluster", SecondsSince(start), cluster_reused});

  // The planted motifs, when the archive is synthetic.
  std::optional<PlantedMotifScore> score;
  if (!truth_path.empty()) {
    Result<TruthFile> truth = ReadTruthJson(truth_path);
    if (!truth.ok()) return fail(truth.status());
    score = ScoreMotifsDocument(document, truth->instances);
  }

  // Stage 5: the report.
  const std::string report_path = Join(out_dir, "report.html");
  if (!vm.count("no-report")) {
    start = Clock::now();
    ReportInfo info;
    info.archive_path = archive;
    std::ostringstream parameters;
    parameters << "eps " << trellis->params.eps << " (" << trellis->eps_how << "), k_max "
               << trellis->params.k_max << ", B " << paths->params.branch << ", min length "
               << paths->params.min_length << " frames, groups " << groups_text << ", seed " << seed
               << ", search " << TrellisSearchModeName(trellis->search);
    info.parameters_text = parameters.str();
    for (const StageTime& time : times) info.timings.push_back({time.stage, time.seconds});
    info.peak_memory_bytes = PeakResidentBytes();
    info.planted_score = score;
    info.truth_path = truth_path;
    if (Status status = WriteReportHtml(report_path, document, **frames, info); !status.ok()) {
      return fail(status);
    }
    times.push_back({"report", SecondsSince(start), false});
  }

  // The summary.
  uint64_t instances = 0;
  uint64_t instance_frames = 0;
  for (const MotifsJsonMotif& motif : document.motifs) {
    instances += motif.instances.size();
    for (const MotifsJsonInstance& instance : motif.instances) instance_frames += instance.length();
  }
  const double fps = (*frames)->fps();
  const uint64_t total_frames = (*frames)->frame_count();
  std::printf("motifmine mine: %s\n", archive.c_str());
  std::printf("  archive      %s frames (%.1f min at %g fps) in %s clips\n",
              WithCommas(total_frames).c_str(), static_cast<double>(total_frames) / fps / 60.0, fps,
              WithCommas((*frames)->clips().size()).c_str());
  std::printf("  radius       eps %.3f: %s (the paper's mu - 2 sigma would be %.3f)\n",
              trellis->params.eps, trellis->eps_how.c_str(), trellis->paper_eps);
  std::printf("  trellis      mean K %.1f of k_max %u, %s search\n", trellis->mean_k,
              trellis->params.k_max, TrellisSearchModeName(trellis->search));
  std::printf("  paths        %s candidates (B %u, min length %llu frames)\n",
              WithCommas(paths->candidates).c_str(), paths->params.branch,
              static_cast<unsigned long long>(paths->params.min_length));
  std::printf("  motifs       %s motifs, %s instances, mean %.1f s, covering %s of the archive\n",
              WithCommas(document.motifs.size()).c_str(), WithCommas(instances).c_str(),
              instances ? static_cast<double>(instance_frames) / instances / fps : 0.0,
              Percent(document.covered_frames, total_frames).c_str());
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
  for (const StageTime& time : times) {
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.1fs%s", timing.empty() ? "" : ", ", time.stage.c_str(),
                  time.seconds, time.reused ? " (reused)" : "");
    timing += part;
  }
  std::printf("  time         %s; total %.1fs\n", timing.c_str(), SecondsSince(job_start));
  std::printf("  memory       peak resident %s\n", FormatBytes(PeakResidentBytes()).c_str());
  if (score) {
    std::printf("  planted      %u motifs as %s instances (%s)\n", score->planted_motifs,
                WithCommas(score->planted).c_str(), truth_path.c_str());
    std::printf("  recall       %.3f  (%s of %s planted instances found)\n", score->recall,
                WithCommas(score->planted_hit).c_str(), WithCommas(score->planted).c_str());
    std::printf("  precision    %.3f  (%s of %s found instances are planted ones)\n",
                score->precision, WithCommas(score->found_hitting).c_str(),
                WithCommas(score->found).c_str());
    std::printf("  grouping     ARI %.3f  (found motif vs planted motif of the hit instances)\n",
                score->adjusted_rand_index);
  }
  std::printf("  wrote        %s", motifs_path.c_str());
  if (!vm.count("no-report")) std::printf(", %s (open it in a browser)", report_path.c_str());
  std::printf("\n");
  if (skipped_takes.empty()) return kExitOk;
  std::printf("  skipped      %s bad takes (--skip-bad; named on stderr)\n",
              WithCommas(skipped_takes.size()).c_str());
  ReportSkippedTakes("mine", skipped_takes, ProgressModeFrom(vm));
  return kExitWarnings;  // mined the good takes
}

}  // namespace motif::cli
