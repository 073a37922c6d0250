#include "engine/pipeline/mine_pipeline.h"

#include <chrono>
#include <filesystem>
#include <sstream>
#include <utility>

#include "common/byte_coding.h"
#include "common/file_util.h"
#include "common/peak_memory.h"
#include "common/seconds_since.h"
#include "engine/cluster/cluster_stage.h"
#include "engine/cluster/instances_csv.h"
#include "engine/ingest/archive_import.h"
#include "engine/pipeline/option_table.h"
#include "engine/pipeline/run_record.h"
#include "engine/pipeline/stage_options.h"
#include "engine/report/report_html.h"
#include "engine/synth/synthetic_archive.h"
#include "engine/synth/truth_json_reader.h"
#include "engine/trellis/trellis_strategy.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_descriptions.h"

namespace motif {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The file a run holds an exclusive flock on, in its output folder.
constexpr char kRunLockName[] = ".motifmine.lock";

bool IsArchivePath(const std::string& path) { return fs::path(path).extension() == ".mfs"; }

// The names of the files a run writes in its folder, whose temporary files a killed run may
// have left.
std::vector<std::string> OwnedFileNames(const RunFiles& files) {
  std::vector<std::string> names;
  const std::string truth = TruthPathFor(files.archive);
  for (const std::string* path :
       {&files.archive, &truth, &files.trellis, &files.search_cache, &files.paths, &files.motifs,
        &files.instances, &files.cluster_state, &files.report, &files.run_record}) {
    if (!path->empty() && fs::path(*path).parent_path() == fs::path(files.dir)) {
      names.push_back(fs::path(*path).filename().string());
    }
  }
  return names;
}

// The unit of each trellis stage's progress.
const char* TrellisProgressUnit(const std::string& stage) {
  if (stage == "eps") return "pairs";
  if (stage == "features" || stage == "index") return "frames";
  if (stage == "thresholds" || stage == "merge") return "blocks";
  return "columns";
}

}  // namespace

MinePipeline::MinePipeline(RunSession* session, StagePlan plan)
    : session_(session), plan_(std::move(plan)) {}

Result<MinePipelineResult> MinePipeline::Run() {
  if (!session_->root()) return RunOtherRank();
  const Clock::time_point job_start = Clock::now();
  ExclusiveFileLock run_lock;
  const Status prepared = Prepare(&run_lock);
  MOTIF_RETURN_IF_ERROR(ShareArchive(prepared));
  MOTIF_RETURN_IF_ERROR(prepared);
  if (Status built = TrellisStage(); !built.ok()) return SharedFailure(built);
  MOTIF_RETURN_IF_ERROR(GrowStage());
  MOTIF_RETURN_IF_ERROR(ClusterStage());
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
  const RunFiles& files = session_->files();
  if (files.dir.empty()) return Status::InvalidArgument("no output folder given");
  // Before the output folder is made: a mistyped input leaves nothing behind.
  for (const std::string& input : session_->inputs()) {
    std::error_code error;
    if (!fs::exists(input, error)) return Status::NotFound(input + ": no such file or folder");
  }
  MOTIF_RETURN_IF_ERROR(CheckMineOptions(session_->options()));
  if (!session_->options().descriptions_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(descriptions_,
                           ReadTakeDescriptions(session_->options().descriptions_path));
  }
  if (plan_.lock_folder) MOTIF_RETURN_IF_ERROR(LockFolder(run_lock));
  if (plan_.archive == ArchiveStep::kFromInputs) {
    MOTIF_RETURN_IF_ERROR(MakeArchive());
  } else if (!session_->has_archive()) {
    MOTIF_RETURN_IF_ERROR(session_->OpenArchive());
  }
  return ArchiveOpened();
}

Status MinePipeline::LockFolder(ExclusiveFileLock* run_lock) {
  const RunFiles& files = session_->files();
  std::error_code error;
  fs::create_directories(files.dir, error);
  if (error) return Status::IOError("cannot create " + files.dir + ": " + error.message());
  // One run per folder: a second run (an overlapping cron job) leaves at once, before touching
  // anything. The lock goes with the process, even on kill -9.
  MOTIF_RETURN_IF_ERROR(run_lock->Acquire(
      (fs::path(files.dir) / kRunLockName).string(),
      "another motifmine run is working in this folder; nothing was changed (exit 17: try "
      "again when it has finished)",
      /*create=*/true));
  RemoveStaleTemporaries(files.dir, OwnedFileNames(files));
  return Status::Ok();
}

Status MinePipeline::ShareArchive(const Status& prepared) {
  if (session_->ranks() == nullptr) return Status::Ok();
  std::string message;
  if (prepared.ok()) {
    const FrameFileVersion version = session_->archive().version();
    message = "0\n" + std::to_string(version.generation) + "\n" +
              std::to_string(version.committed_bytes) + "\n" + result_.archive_path;
  } else {
    message = std::to_string(static_cast<int>(prepared.code())) + "\n" + prepared.message();
  }
  return session_->ranks()->Broadcast(&message);
}

Result<MinePipelineResult> MinePipeline::RunOtherRank() {
  std::string message;
  MOTIF_RETURN_IF_ERROR(session_->ranks()->Broadcast(&message));
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
  session_->mutable_files().archive = result_.archive_path;
  if (Status opened = session_->OpenArchive(version); !opened.ok()) {
    return SharedFailure(opened.WithContext(
        "the archive rank 0 opened (generation " + std::to_string(version.generation) + ", " +
        std::to_string(version.committed_bytes) + " bytes) does not open here"));
  }
  if (Status resolved = ArchiveOpened(); !resolved.ok()) return SharedFailure(resolved);
  if (Status built = TrellisStage(); !built.ok()) return SharedFailure(built);
  return std::move(result_);
}

Status MinePipeline::SharedFailure(const Status& failed) const {
  if (session_->ranks() == nullptr) return failed;
  const Status named = failed.WithContext("rank " + std::to_string(session_->ranks()->rank()));
  if (session_->hooks().on_shared_failure) session_->hooks().on_shared_failure(named);
  return named;
}

// Stage 1: the archive, then opened once; every later stage reads that version.
Status MinePipeline::MakeArchive() {
  const std::vector<std::string>& inputs = session_->inputs();
  if (inputs.empty()) {
    MOTIF_RETURN_IF_ERROR(MakeSyntheticArchive());
  } else if (inputs.size() == 1 && IsArchivePath(inputs[0])) {
    RunFiles& files = session_->mutable_files();
    files.archive = inputs[0];
    std::error_code error;
    if (fs::exists(TruthPathFor(files.archive), error)) files.truth = TruthPathFor(files.archive);
  } else {
    MOTIF_RETURN_IF_ERROR(ImportInputs());
  }
  return session_->OpenArchive();
}

Status MinePipeline::MakeSyntheticArchive() {
  const Clock::time_point start = Clock::now();
  RunFiles& files = session_->mutable_files();
  files.truth = TruthPathFor(files.archive);
  const SynthOptions synth = SynthOptionsFor(session_->options());
  bool reused = false;
  std::error_code error;
  if (fs::exists(files.archive, error)) {
    Result<TruthFile> stored = ReadTruthJson(files.truth);
    reused = stored.ok() && stored->frames == synth.frames && stored->seed == synth.seed &&
             stored->motifs == synth.motifs && FrameFileReader::Open(files.archive).ok();
  }
  if (!reused) {
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                           MotionSynthesizer::Create(synth));
    MOTIF_RETURN_IF_ERROR(WriteSyntheticArchive(files.archive, *synthesizer, synth,
                                                FrameFileWriterOptions{}.block_frames,
                                                [&](uint64_t done, uint64_t total) {
                                                  session_->Progress("synth", done, total,
                                                                     "frames");
                                                })
                              .status());
  }
  result_.times.push_back({"synth", SecondsSince(start), reused});
  return Status::Ok();
}

Status MinePipeline::ImportInputs() {
  const Clock::time_point start = Clock::now();
  ArchiveImportOptions import_options;
  import_options.import.descriptions = descriptions_;
  import_options.skip_bad = session_->options().skip_bad;
  import_options.threads = session_->options().threads;
  import_options.note = session_->hooks().note;
  import_options.progress = [&](uint64_t done, uint64_t total) {
    session_->Progress("import", done, total, "takes");
  };
  MOTIF_ASSIGN_OR_RETURN(
      ArchiveImportResult imported,
      ImportIntoArchive(session_->files().archive, session_->inputs(), import_options));
  result_.times.push_back({"import", SecondsSince(start), imported.takes_imported == 0});
  result_.skipped_takes = imported.failures;
  return Status::Ok();
}

Status MinePipeline::ArchiveOpened() {
  const FrameFileReader& archive = session_->archive();
  result_.archive_path = session_->files().archive;
  result_.truth_path = session_->files().truth;
  result_.fps = archive.fps();
  result_.frames = archive.frame_count();
  result_.clips = archive.clips().size();
  const motifmine::MineOptions& options = session_->options();
  MOTIF_ASSIGN_OR_RETURN(trellis_options_, TrellisOptionsFor(options, archive.fps()));
  trellis_options_.archive_version = archive.version();
  paths_options_ = PathsOptionsFor(options, archive.fps());
  paths_options_.archive_version = archive.version();
  MOTIF_ASSIGN_OR_RETURN(cluster_options_, ClusterOptionsFor(options));
  return Status::Ok();
}

void MinePipeline::TrellisProgress(const std::string& stage, uint64_t done, uint64_t total) const {
  session_->Progress(stage == "trellis" ? "trellis" : "trellis " + stage, done, total,
                     TrellisProgressUnit(stage));
}

// Stage 2: the matching trellis, built, updated, linked or taken as it is.
Status MinePipeline::TrellisStage() {
  TrellisStep step = plan_.trellis;
  if (step == TrellisStep::kSkip) return Status::Ok();
  const RunFiles& files = session_->files();
  if (step == TrellisStep::kAnyOfArchive) {
    step = IsTrellisOfArchive(files.trellis, session_->archive()) ? TrellisStep::kLink
                                                                : TrellisStep::kBuild;
  }
  const Clock::time_point start = Clock::now();
  if (step == TrellisStep::kLink) {
    MOTIF_RETURN_IF_ERROR(LinkPreviousTrellis());
    MOTIF_RETURN_IF_ERROR(session_->OpenTrellis());
    result_.trellis.trellis_path = files.trellis;
    result_.trellis.reused = true;
    result_.trellis.params = session_->trellis().params();
    result_.times.push_back({"trellis", SecondsSince(start), true});
    return Status::Ok();
  }
  TrellisStageInput input;
  input.archive = &session_->archive();
  input.trellis_path = files.trellis;
  input.options = trellis_options_;
  input.options.progress = [this](const std::string& stage, uint64_t done, uint64_t total) {
    TrellisProgress(stage, done, total);
  };
  input.options.note = session_->hooks().note;
  input.options.detail = session_->hooks().detail;
  input.options.ranks = session_->ranks();
  input.options.file_system = session_->hooks().file_system;
  if (plan_.save_search_cache) input.options.search_cache_path = files.search_cache;
  std::unique_ptr<TrellisStrategy> strategy;
  if (step == TrellisStep::kUpdate) {
    strategy =
        std::make_unique<IncrementalTrellisUpdate>(plan_.previous_trellis, plan_.previous_cache);
    if (plan_.grow) {
      MOTIF_ASSIGN_OR_RETURN(streamed_paths_,
                             StreamedPaths::Create(session_->archive(), paths_options_));
      input.on_block = [this](uint64_t first_column,
                              const std::vector<std::vector<Neighbour>>& columns) {
        return streamed_paths_->AddBlock(first_column, columns);
      };
    }
  } else {
    strategy = std::make_unique<FullTrellisBuild>();
  }
  MOTIF_ASSIGN_OR_RETURN(result_.trellis, strategy->Run(input));
  result_.times.push_back({"trellis", SecondsSince(start), result_.trellis.reused});
  if (!session_->root()) return Status::Ok();
  return session_->OpenTrellis();
}

// The previous version's trellis at files.trellis (a hard link; a copy where links are refused).
Status MinePipeline::LinkPreviousTrellis() const {
  const std::string& target = session_->files().trellis;
  std::error_code error;
  if (plan_.previous_trellis.empty() || fs::exists(target, error)) return Status::Ok();
  fs::create_hard_link(plan_.previous_trellis, target, error);
  if (error) fs::copy_file(plan_.previous_trellis, target, error);
  if (error) {
    return Status::IOError("cannot link " + plan_.previous_trellis + " to " + target + ": " +
                           error.message());
  }
  return Status::Ok();
}

// Stage 3: the paths (finished from the update's blocks when it streamed them all).
Status MinePipeline::GrowStage() {
  if (!plan_.grow) return Status::Ok();
  const RunFiles& files = session_->files();
  const Clock::time_point start = Clock::now();
  if (streamed_paths_) {
    MOTIF_RETURN_IF_ERROR(streamed_paths_->FinishIfComplete(session_->trellis(), files.paths));
  }
  PathsOptions paths = paths_options_;
  paths.progress = [this](uint64_t done, uint64_t total) {
    session_->Progress("grow", done, total, "columns");
  };
  MOTIF_ASSIGN_OR_RETURN(result_.paths,
                         BuildPaths(session_->archive(), session_->trellis(), files.paths, paths));
  result_.times.push_back({"grow", SecondsSince(start), result_.paths.reused});
  return Status::Ok();
}

// Stage 4: the motifs.
Status MinePipeline::ClusterStage() {
  if (!plan_.cluster) return Status::Ok();
  const RunFiles& files = session_->files();
  ClusterStageInput input;
  input.archive_path = files.archive;
  input.archive = &session_->archive();
  input.trellis_path = files.trellis;
  input.trellis = &session_->trellis();
  input.paths_path = files.paths;
  input.paths_params = result_.paths.params;
  input.candidates = result_.paths.candidates;
  input.motifs_path = files.motifs;
  input.state_path = files.cluster_state;
  ClusterOptions cluster = cluster_options_;
  cluster.progress = [this](const std::string&, uint64_t done, uint64_t total) {
    session_->Progress("cluster", done, total, "instance frames");  // overlapping instances
  };
  const Clock::time_point start = Clock::now();
  MOTIF_ASSIGN_OR_RETURN(ClusterStageResult clustered, RunClusterStage(input, cluster));
  result_.document = std::move(clustered.document);
  result_.motifs_path = files.motifs;
  if (!files.instances.empty()) {
    // Rewritten also when motifs.json was reused: it is derived, and cheap.
    MOTIF_RETURN_IF_ERROR(WriteInstancesCsv(files.instances, result_.document));
    result_.instances_path = files.instances;
  }
  result_.times.push_back({"cluster", SecondsSince(start), clustered.reused});
  return Status::Ok();
}

// The planted motifs, when the archive is synthetic.
Status MinePipeline::ScoreStage() {
  if (!plan_.score || !plan_.cluster || result_.truth_path.empty()) return Status::Ok();
  MOTIF_ASSIGN_OR_RETURN(TruthFile truth, ReadTruthJson(result_.truth_path));
  result_.score = ScoreMotifsDocument(result_.document, truth.instances);
  return Status::Ok();
}

std::string MinePipeline::ParametersText() const {
  const TrellisReport& trellis = result_.trellis;
  if (session_->report_parameters) return session_->report_parameters(trellis);
  // What motifs.json's params do not say: how the radius was chosen, and the search.
  std::ostringstream parameters;
  parameters << "radius: " << trellis.eps_how
             << "; neighbour search: " << TrellisSearchModeName(trellis.search);
  return parameters.str();
}

// OUT/run.json: what `report OUT` needs to show this run's overview again.
Status MinePipeline::WriteRunStage() {
  if (!plan_.run_record || !plan_.cluster) return Status::Ok();
  MOTIF_ASSIGN_OR_RETURN(std::string motifs, ReadFileToString(result_.motifs_path));
  RunRecord record;
  record.motifs_checksum = Checksum64(motifs.data(), motifs.size());
  record.parameters_text = ParametersText();
  for (const MineStageTime& time : result_.times) {
    record.timings.push_back({time.stage, time.seconds, time.reused});
  }
  record.total_seconds = result_.total_seconds;
  record.peak_memory_bytes = result_.peak_memory_bytes;
  record.descriptions.insert(descriptions_.begin(), descriptions_.end());
  if (!result_.truth_path.empty()) {
    std::error_code error;
    const fs::path truth =
        fs::relative(fs::absolute(result_.truth_path), fs::absolute(session_->files().dir), error);
    record.truth_path = error ? fs::absolute(result_.truth_path).string() : truth.string();
  }
  return WriteRunRecord(session_->files().run_record, record);
}

// Stage 5: the report.
Status MinePipeline::ReportStage() {
  if (!plan_.report || !plan_.cluster || !session_->options().write_report) return Status::Ok();
  const Clock::time_point start = Clock::now();
  ReportInfo info;
  info.archive_path = result_.archive_path;
  info.parameters_text = ParametersText();
  for (const RunSession::EarlierStage& earlier : session_->earlier_stages) {
    info.timings.push_back({earlier.stage, earlier.seconds});
  }
  for (const MineStageTime& time : result_.times) {
    info.timings.push_back({time.stage, time.seconds});
  }
  info.peak_memory_bytes = result_.peak_memory_bytes;
  info.planted_score = result_.score;
  info.truth_path = result_.truth_path;
  info.descriptions.insert(descriptions_.begin(), descriptions_.end());
  result_.report_path = session_->files().report;
  MOTIF_RETURN_IF_ERROR(WriteReportHtml(result_.report_path, result_.document, session_->archive(),
                                        info, ReportOptionsFor(session_->options())));
  result_.times.push_back({"report", SecondsSince(start), false});
  return Status::Ok();
}

Result<MinePipelineResult> RunMine(const motifmine::MineOptions& options,
                                   const std::vector<std::string>& inputs, RunHooks hooks) {
  RunSession session(options, inputs, MineFolderFiles(options.out_dir), std::move(hooks));
  return MinePipeline(&session).Run();
}

}  // namespace motif
