#include "engine/pipeline/mine_pipeline.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

#include "common/byte_coding.h"
#include "common/file_lock.h"
#include "common/file_util.h"
#include "common/peak_memory.h"
#include "common/seconds_since.h"
#include "engine/ingest/archive_import.h"
#include "engine/pipeline/motif_stages.h"
#include "engine/pipeline/run_record.h"
#include "engine/report/report_html.h"
#include "engine/synth/synthetic_archive.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_descriptions.h"

namespace motif {

namespace {

using Clock = std::chrono::steady_clock;

// The file a run holds an exclusive flock on, in its output folder.
constexpr char kRunLockName[] = ".motifmine.lock";

// The files a run writes in its folder, whose temporary files a killed run may have left.
const std::vector<std::string> kOwnedFiles = {
    "archive.mfs", "archive.truth.json", "trellis.mtr", "paths.mpa",
    "motifs.json", "mine_state.json",    "report.html", "run.json"};

std::string Join(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}

bool IsArchivePath(const std::string& path) {
  return std::filesystem::path(path).extension() == ".mfs";
}

}  // namespace

MinePipelineOptions DefaultMinePipelineOptions() {
  MinePipelineOptions options;
  // Background that does not repeat within eps, so the planted motifs are the only long repeats
  // and precision against them means something (docs/guide.md, synth).
  options.synth.background_variation_degrees = kRecommendedBackgroundVariation;
  options.synth.frames = 120000;
  options.synth.motifs = 12;
  return options;
}

MinePipeline::MinePipeline(MinePipelineOptions options) : options_(std::move(options)) {
  options_.trellis.seed = options_.seed;
  options_.trellis.threads = options_.threads;
  options_.cluster.seed = options_.seed;
  options_.cluster.threads = options_.threads;
  options_.synth.seed = options_.seed;
  options_.synth.threads = options_.threads > 0 ? static_cast<uint32_t>(options_.threads) : 0;
}

void MinePipeline::Progress(const std::string& stage, uint64_t done, uint64_t total,
                            const std::string& unit) {
  if (options_.progress) options_.progress(stage, done, total, unit);
}

Status MinePipeline::CheckOptions() const {
  const ClusterOptions& cluster = options_.cluster;
  if (options_.out_dir.empty()) return Status::InvalidArgument("no output folder given");
  // Before the output folder is made: a mistyped input leaves nothing behind.
  for (const std::string& input : options_.inputs) {
    std::error_code error;
    if (!std::filesystem::exists(input, error)) {
      return Status::NotFound(input + ": no such file or folder");
    }
  }
  if (!(cluster.max_length_ratio == 0 || cluster.max_length_ratio >= 1) ||
      !std::isfinite(cluster.max_length_ratio)) {
    return Status::InvalidArgument("--max-length-ratio must be 0 (keep all) or >= 1");
  }
  if (options_.trellis.eps < 0 || !std::isfinite(options_.trellis.eps)) {
    return Status::InvalidArgument("--eps must be >= 0 (0: chosen by --eps-rule)");
  }
  if (options_.trellis.k_max == 0) return Status::InvalidArgument("--kmax must be > 0");
  if (options_.paths.branch == 0) return Status::InvalidArgument("--branch must be > 0");
  return ValidatePauseOptions(cluster.pauses);
}

Result<MinePipelineResult> MinePipeline::Run() {
  if (options_.ranks != nullptr && options_.ranks->rank() != 0) return RunOtherRank();
  const Clock::time_point job_start = Clock::now();
  ExclusiveFileLock run_lock;
  const Status prepared = Prepare(&run_lock);
  MOTIF_RETURN_IF_ERROR(ShareArchive(prepared));
  MOTIF_RETURN_IF_ERROR(prepared);
  if (Status built = BuildTrellisStage(); !built.ok()) return SharedFailure(built);
  MOTIF_RETURN_IF_ERROR(MotifStages());
  MOTIF_RETURN_IF_ERROR(ScoreStage());
  result_.total_seconds = SecondsSince(job_start);
  // The peak of the mining, before the report: the one figure the report, run.json and the
  // summary show, so that `report` run again writes the page `mine` wrote.
  result_.peak_memory_bytes = PeakResidentBytes();
  MOTIF_RETURN_IF_ERROR(ReportStage());
  result_.total_seconds = SecondsSince(job_start);
  MOTIF_RETURN_IF_ERROR(WriteRunStage());
  return std::move(result_);
}

Status MinePipeline::Prepare(ExclusiveFileLock* run_lock) {
  MOTIF_RETURN_IF_ERROR(CheckOptions());
  if (!options_.descriptions_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(descriptions_, ReadTakeDescriptions(options_.descriptions_path));
  }
  std::error_code error;
  std::filesystem::create_directories(options_.out_dir, error);
  if (error) {
    return Status::IOError("cannot create " + options_.out_dir + ": " + error.message());
  }
  // One run per folder: a second run (an overlapping cron job) leaves at once, before touching
  // anything. The lock goes with the process, even on kill -9.
  MOTIF_RETURN_IF_ERROR(run_lock->Acquire(
      Join(options_.out_dir, kRunLockName),
      "another motifmine run is working in this folder; nothing was changed (exit 17: try "
      "again when it has finished)",
      /*create=*/true));
  RemoveStaleTemporaries(options_.out_dir, kOwnedFiles);
  return MakeArchive();
}

Status MinePipeline::ShareArchive(const Status& prepared) {
  if (options_.ranks == nullptr) return Status::Ok();
  std::string message;
  if (prepared.ok()) {
    message = "0\n" + std::to_string(options_.trellis.archive_version.generation) + "\n" +
              std::to_string(options_.trellis.archive_version.committed_bytes) + "\n" +
              result_.archive_path;
  } else {
    message = std::to_string(static_cast<int>(prepared.code())) + "\n" + prepared.message();
  }
  return options_.ranks->Broadcast(&message);
}

Result<MinePipelineResult> MinePipeline::RunOtherRank() {
  std::string message;
  MOTIF_RETURN_IF_ERROR(options_.ranks->Broadcast(&message));
  std::istringstream in(message);
  int code = 0;
  in >> code;
  in.get();
  if (code != 0) {  // rank 0 failed before the trellis, and said why
    std::string why;
    std::getline(in, why, '\0');
    return Status::FromCode(static_cast<Status::Code>(code), why);
  }
  FrameFileVersion version;
  in >> version.generation >> version.committed_bytes;
  in.get();
  std::getline(in, result_.archive_path, '\0');
  // The archive at the same path on this rank's node: shared, or a copy.
  Result<std::unique_ptr<FrameFileReader>> archive =
      FrameFileReader::OpenVersion(result_.archive_path, version);
  if (!archive.ok()) {
    return SharedFailure(archive.status().WithContext(
        "the archive rank 0 opened (generation " + std::to_string(version.generation) + ", " +
        std::to_string(version.committed_bytes) + " bytes) does not open here"));
  }
  archive_ = std::move(*archive);
  options_.trellis.archive_version = version;
  options_.paths.archive_version = version;
  if (Status built = BuildTrellisStage(); !built.ok()) return SharedFailure(built);
  return std::move(result_);
}

Status MinePipeline::SharedFailure(const Status& failed) const {
  if (options_.ranks == nullptr) return failed;
  const Status named = failed.WithContext("rank " + std::to_string(options_.ranks->rank()));
  if (options_.on_shared_failure) options_.on_shared_failure(named);
  return named;
}

// Stage 1: the archive, then opened once; every later stage reads that version.
Status MinePipeline::MakeArchive() {
  const Clock::time_point start = Clock::now();
  const std::vector<std::string>& inputs = options_.inputs;
  std::string archive = Join(options_.out_dir, "archive.mfs");
  std::error_code error;
  if (inputs.empty()) {
    const std::string truth = TruthPathFor(archive);
    const SynthOptions& synth = options_.synth;
    bool reused = false;
    if (std::filesystem::exists(archive, error)) {
      Result<TruthFile> stored = ReadTruthJson(truth);
      reused = stored.ok() && stored->frames == synth.frames && stored->seed == synth.seed &&
               stored->motifs == synth.motifs && FrameFileReader::Open(archive).ok();
    }
    if (!reused) {
      MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                             MotionSynthesizer::Create(synth));
      MOTIF_RETURN_IF_ERROR(
          WriteSyntheticArchive(
              archive, *synthesizer, synth, FrameFileWriterOptions{}.block_frames,
              [&](uint64_t done, uint64_t total) { Progress("synth", done, total, "frames"); })
              .status());
    }
    result_.truth_path = truth;
    result_.times.push_back({"synth", SecondsSince(start), reused});
  } else if (inputs.size() == 1 && IsArchivePath(inputs[0])) {
    archive = inputs[0];
    if (std::filesystem::exists(TruthPathFor(archive), error)) {
      result_.truth_path = TruthPathFor(archive);
    }
  } else {
    ArchiveImportOptions import_options;
    import_options.import.descriptions = descriptions_;
    import_options.skip_bad = options_.skip_bad;
    import_options.threads = options_.threads;
    import_options.note = options_.note;
    import_options.progress = [&](uint64_t done, uint64_t total) {
      Progress("import", done, total, "takes");
    };
    MOTIF_ASSIGN_OR_RETURN(ArchiveImportResult imported,
                           ImportIntoArchive(archive, inputs, import_options));
    result_.times.push_back({"import", SecondsSince(start), imported.takes_imported == 0});
    result_.skipped_takes = imported.failures;
  }
  result_.archive_path = archive;
  MOTIF_ASSIGN_OR_RETURN(archive_, FrameFileReader::Open(archive));
  options_.trellis.archive_version = archive_->version();
  options_.paths.archive_version = archive_->version();
  result_.fps = archive_->fps();
  result_.frames = archive_->frame_count();
  result_.clips = archive_->clips().size();
  return Status::Ok();
}

// Stage 2: the matching trellis.
Status MinePipeline::BuildTrellisStage() {
  TrellisOptions trellis = options_.trellis;
  const PathsOptions& paths = options_.paths;
  trellis.min_length_seconds = paths.min_length_frames > 0
                                   ? static_cast<double>(paths.min_length_frames) / archive_->fps()
                                   : paths.min_length_seconds;
  trellis.progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    const bool columns = stage == "trellis";
    Progress(columns ? "trellis" : "trellis " + stage, done, total,
             stage == "eps" ? "pairs"
             : columns      ? "columns"
                            : "frames");
  };
  trellis.note = options_.note;
  trellis.ranks = options_.ranks;
  const Clock::time_point start = Clock::now();
  MOTIF_ASSIGN_OR_RETURN(
      result_.trellis,
      BuildTrellis(result_.archive_path, Join(options_.out_dir, "trellis.mtr"), trellis));
  result_.times.push_back({"trellis", SecondsSince(start), result_.trellis.reused});
  return Status::Ok();
}

// Stages 3 and 4: the paths, then the motifs (RunMotifStages, shared with reindex).
Status MinePipeline::MotifStages() {
  MotifStagesInput input;
  input.archive_path = result_.archive_path;
  input.archive = archive_.get();
  input.trellis_path = Join(options_.out_dir, "trellis.mtr");
  input.paths_path = Join(options_.out_dir, "paths.mpa");
  input.motifs_path = Join(options_.out_dir, "motifs.json");
  input.state_path = Join(options_.out_dir, "mine_state.json");
  input.paths = options_.paths;
  input.cluster = options_.cluster;
  input.progress = options_.progress;
  MOTIF_ASSIGN_OR_RETURN(MotifStagesResult stages, RunMotifStages(input));
  result_.paths = stages.paths;
  result_.document = std::move(stages.clustered.document);
  result_.motifs_path = input.motifs_path;
  result_.times.push_back({"grow", stages.grow_seconds, stages.paths.reused});
  result_.times.push_back({"cluster", stages.cluster_seconds, stages.clustered.reused});
  return Status::Ok();
}

// The planted motifs, when the archive is synthetic.
Status MinePipeline::ScoreStage() {
  if (result_.truth_path.empty()) return Status::Ok();
  MOTIF_ASSIGN_OR_RETURN(TruthFile truth, ReadTruthJson(result_.truth_path));
  result_.score = ScoreMotifsDocument(result_.document, truth.instances);
  return Status::Ok();
}

std::string MinePipeline::ParametersText() const {
  const TrellisReport& trellis = result_.trellis;
  // What motifs.json's params do not say: how the radius was chosen, and the search.
  std::ostringstream parameters;
  parameters << "radius: " << trellis.eps_how
             << "; neighbour search: " << TrellisSearchModeName(trellis.search);
  return parameters.str();
}

// OUT/run.json: what `report OUT` needs to show this run's overview again.
Status MinePipeline::WriteRunStage() {
  MOTIF_ASSIGN_OR_RETURN(std::string motifs, ReadFileToString(result_.motifs_path));
  RunRecord record;
  record.motifs_checksum = Checksum64(motifs.data(), motifs.size());
  record.parameters_text = ParametersText();
  for (const MineStageTime& time : result_.times) {
    record.timings.push_back({time.stage, time.seconds, time.reused});
  }
  record.total_seconds = result_.total_seconds;
  record.peak_memory_bytes = result_.peak_memory_bytes;
  if (!result_.truth_path.empty()) {
    std::error_code error;
    const std::filesystem::path truth =
        std::filesystem::relative(std::filesystem::absolute(result_.truth_path),
                                  std::filesystem::absolute(options_.out_dir), error);
    record.truth_path =
        error ? std::filesystem::absolute(result_.truth_path).string() : truth.string();
  }
  return WriteRunRecord(Join(options_.out_dir, "run.json"), record);
}

// Stage 5: the report.
Status MinePipeline::ReportStage() {
  if (!options_.write_report) return Status::Ok();
  const Clock::time_point start = Clock::now();
  ReportInfo info;
  info.archive_path = result_.archive_path;
  info.parameters_text = ParametersText();
  for (const MineStageTime& time : result_.times)
    info.timings.push_back({time.stage, time.seconds});
  info.peak_memory_bytes = result_.peak_memory_bytes;
  info.planted_score = result_.score;
  info.truth_path = result_.truth_path;
  result_.report_path = Join(options_.out_dir, "report.html");
  ReportOptions report_options;
  report_options.playback_bytes = options_.report_playback_bytes;
  MOTIF_RETURN_IF_ERROR(
      WriteReportHtml(result_.report_path, result_.document, *archive_, info, report_options));
  result_.times.push_back({"report", SecondsSince(start), false});
  return Status::Ok();
}

}  // namespace motif
