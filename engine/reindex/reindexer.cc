#include "engine/reindex/reindexer.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <optional>
#include <sstream>

#include "common/byte_coding.h"
#include "common/file_lock.h"
#include "common/file_util.h"
#include "common/seconds_since.h"
#include "engine/ingest/archive_import.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/pipeline/option_table.h"
#include "engine/reindex/reindex_plan.h"
#include "engine/reindex/watched_takes.h"
#include "engine/trellis/search_cache.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr char kLockName[] = ".motifmine.lock";
const std::vector<std::string> kTopFiles = {"manifest.json", "motifs.json", "report.html"};
const std::vector<std::string> kVersionFiles = {"trellis.mtr",        "paths.mpa",   "motifs.json",
                                                "cluster_state.json", "report.html", "search.msc"};

std::string Join(const std::string& dir, const std::string& name) {
  return (fs::path(dir) / name).string();
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

ArchiveVersion VersionOf(const FrameFileReader& archive, const std::string& path) {
  const FrameFileSummary summary = archive.summary();
  ArchiveVersion version;
  version.path = WatchedPath(path);
  version.generation = summary.generation;
  version.committed_bytes = summary.file_bytes;
  version.identity = summary.identity;
  version.frames = archive.frame_count();
  version.clips = archive.clips().size();
  return version;
}

// XXH3-64 and size of a whole file.
Result<VersionFile> DescribeFile(const std::string& out_dir, const std::string& relative) {
  MOTIF_ASSIGN_OR_RETURN(std::string bytes, ReadFileToString(Join(out_dir, relative)));
  return VersionFile{relative, bytes.size(), Checksum64(bytes.data(), bytes.size())};
}

// Replaces OUTDIR/<name> with the version's file atomically: a hard link to it under a
// temporary name renamed over the target (a copy where links are refused).
Status Publish(const std::string& out_dir, const std::string& relative, const std::string& name,
               FileSystem* file_system) {
  const std::string source = Join(out_dir, relative);
  const std::string target = Join(out_dir, name);
  const std::string temp = TemporaryPathFor(target);
  std::error_code error;
  fs::create_hard_link(source, temp, error);
  if (error) {
    MOTIF_ASSIGN_OR_RETURN(std::string bytes, ReadFileToString(source));
    return AtomicWriteFile(target, bytes, file_system);
  }
  Status status = file_system->Rename(temp, target);
  if (status.ok()) status = file_system->SyncParentDir(target);
  // Best effort (the temporary may already be renamed): the error that matters is `status`.
  if (!status.ok()) (void)file_system->Remove(temp);
  return status;
}

// OUTDIR/<name> holds the bytes the manifest says the version's file has.
bool Published(const std::string& out_dir, const VersionFile& file, const std::string& name) {
  Result<std::string> bytes = ReadFileToString(Join(out_dir, name));
  return bytes.ok() && bytes->size() == file.bytes &&
         Checksum64(bytes->data(), bytes->size()) == file.checksum;
}

Status PublishCurrent(const std::string& out_dir, const ReindexManifest& manifest,
                      FileSystem* file_system) {
  if (!Published(out_dir, manifest.motifs, "motifs.json")) {
    MOTIF_RETURN_IF_ERROR(Publish(out_dir, manifest.motifs.path, "motifs.json", file_system));
  }
  if (!manifest.report.path.empty() && !Published(out_dir, manifest.report, "report.html")) {
    MOTIF_RETURN_IF_ERROR(Publish(out_dir, manifest.report.path, "report.html", file_system));
  }
  return Status::Ok();
}

// Version folders "v<digits>" in OUTDIR.
std::vector<uint64_t> ListVersions(const std::string& out_dir) {
  std::vector<uint64_t> versions;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(out_dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 2 || name[0] != 'v' || !entry.is_directory(error)) continue;
    char* end = nullptr;
    const uint64_t version = std::strtoull(name.c_str() + 1, &end, 10);
    if (*end == '\0' && name == VersionDirName(version)) versions.push_back(version);
  }
  std::sort(versions.begin(), versions.end());
  return versions;
}

// The previous version's search cache for a regrow's version (the same trellis). Best effort.
void LinkSearchCache(const std::string& out_dir, const ReindexManifest& current,
                     const std::string& version_path) {
  std::error_code error;
  const std::string cache = Join(version_path, kSearchCacheFileName);
  if (!fs::exists(cache, error)) {
    fs::create_hard_link(Join(Join(out_dir, current.dir), kSearchCacheFileName), cache, error);
  }
}

// What a run reports on as it goes: its notes, kept for the report, and its progress.
class RunLog {
 public:
  RunLog(const ReindexOptions& options, ReindexReport* report)
      : options_(options), report_(report) {}
  void Note(const std::string& message) const {
    report_->notes.push_back(message);
    if (options_.note) options_.note(message);
  }
  void Progress(const std::string& stage, uint64_t done, uint64_t total,
                const std::string& unit) const {
    if (options_.progress) options_.progress(stage, done, total, unit);
  }

 private:
  const ReindexOptions& options_;
  ReindexReport* report_;
};

// One run at a time per OUTDIR; what killed runs left is removed.
Status LockAndClean(const ReindexOptions& options, ExclusiveFileLock* lock) {
  const std::string& out_dir = options.out_dir;
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error) return Status::IOError("cannot create " + out_dir + ": " + error.message());
  MOTIF_RETURN_IF_ERROR(lock->Acquire(Join(out_dir, kLockName),
                                      "another motifmine run is working in this folder; nothing "
                                      "was changed (exit 17: it will be done next time)",
                                      /*create=*/true));
  RemoveStaleTemporaries(out_dir, kTopFiles);
  for (uint64_t version : ListVersions(out_dir)) {
    RemoveStaleTemporaries(Join(out_dir, VersionDirName(version)), kVersionFiles);
  }
  const std::string archive_dir =
      fs::path(WatchedPath(options.archive_path)).parent_path().string();
  RemoveStaleTemporaries(archive_dir, {fs::path(options.archive_path).filename().string()});
  return Status::Ok();
}

// The current version's manifest (none at the first run), and its files published again when a
// run was killed (or short of room) between the switch and their publication.
Result<std::optional<ReindexManifest>> ReadCurrent(const ReindexOptions& options) {
  Result<ReindexManifest> read = ReadManifest(options.out_dir);
  if (!read.ok()) {
    if (read.status().IsNotFound()) return std::optional<ReindexManifest>();
    return Status::Corruption(read.status().message() +
                              " (the output's manifest is damaged; move OUTDIR away to "
                              "rebuild from scratch)");
  }
  MOTIF_RETURN_IF_ERROR(PublishCurrent(options.out_dir, *read, options.file_system));
  return std::optional<ReindexManifest>(std::move(read.value()));
}

// The new takes of the watched folder, scanned against the archive's clips and imported in one
// commit; the counts into *report.
Status ImportNewTakes(const ReindexOptions& options, const RunLog& log, ReindexReport* report) {
  const Clock::time_point start = Clock::now();
  std::vector<ClipInfo> clips;
  std::error_code error;
  const bool archive_exists = fs::exists(options.archive_path, error);
  if (archive_exists) {
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> before,
                           FrameFileReader::Open(options.archive_path));
    clips = before->clips();
  }
  MOTIF_ASSIGN_OR_RETURN(WatchScan scan, ScanWatchedFolder(options.watch_dir, clips, options.import,
                                                           options.min_age_seconds));
  report->takes_scanned = scan.new_takes.size() + scan.known_takes + scan.changed.size();
  report->takes_known = scan.known_takes;
  report->changed = scan.changed;
  report->settling = scan.settling;
  for (const std::string& message : scan.changed) log.Note("changed: " + message);
  if (!scan.settling.empty()) {
    log.Note(std::to_string(scan.settling.size()) + " take(s) modified in the last " +
             std::to_string(options.min_age_seconds) +
             " s are left for the next run (still being copied?), e.g. " + scan.settling.front());
  }
  if (scan.new_takes.empty()) {
    report->import_seconds = SecondsSince(start);
    report->waiting = !archive_exists && !scan.settling.empty();
    if (archive_exists || report->waiting) return Status::Ok();
    return Status::NotFound(options.archive_path + " does not exist and " + options.watch_dir +
                            " holds no take to make it from");
  }
  ArchiveImportOptions import_options;
  import_options.import = options.import;
  import_options.skip_bad = options.mine.skip_bad;
  import_options.threads = options.mine.threads;
  import_options.file_system = options.file_system;
  import_options.note = [&](const std::string& message) { log.Note(message); };
  import_options.progress = [&](uint64_t done, uint64_t total) {
    log.Progress("import", done, total, "takes");
  };
  log.Progress("import", 0, scan.new_takes.size(), "takes");
  MOTIF_ASSIGN_OR_RETURN(
      ArchiveImportResult imported,
      ImportTakesIntoArchive(options.archive_path, scan.new_takes, import_options));
  report->takes_imported = imported.takes_imported;
  report->frames_imported = imported.frames_added;
  report->takes_known += imported.takes_already_present;
  report->failed = imported.failures;
  report->import_seconds = SecondsSince(start);
  return Status::Ok();
}

// The files of version `dir` (relative to OUTDIR) as the pipeline writes them.
RunFiles VersionFiles(const ReindexOptions& options, const std::string& dir) {
  const std::string version_path = Join(options.out_dir, dir);
  RunFiles files;
  files.dir = version_path;
  // Absolute: OUTDIR/motifs.json is a byte copy of this version's, one folder up.
  files.archive = fs::absolute(options.archive_path).lexically_normal().string();
  files.trellis = Join(version_path, "trellis.mtr");
  files.search_cache = Join(version_path, kSearchCacheFileName);
  files.paths = Join(version_path, "paths.mpa");
  files.motifs = Join(version_path, "motifs.json");
  files.cluster_state = Join(version_path, "cluster_state.json");
  files.report = Join(version_path, "report.html");
  return files;
}

// The pipeline run on the plan, in the version's folder (a killed run's files there are
// resumed or reused).
Result<MinePipelineResult> MineVersion(const ReindexOptions& options, const ReindexPlan& plan,
                                       const std::optional<ReindexManifest>& current,
                                       uint64_t version, std::unique_ptr<FrameFileReader> archive,
                                       const RunLog& log, ReindexReport* report) {
  const RunFiles files = VersionFiles(options, VersionDirName(version));
  std::error_code error;
  fs::create_directories(files.dir, error);
  if (error) return Status::IOError("cannot create " + files.dir + ": " + error.message());
  if (plan.kind == "regrow") LinkSearchCache(options.out_dir, *current, files.dir);
  RunHooks hooks;
  hooks.progress = [&log](const std::string& stage, uint64_t done, uint64_t total,
                          const std::string& unit) { log.Progress(stage, done, total, unit); };
  hooks.note = [&log](const std::string& message) { log.Note(message); };
  hooks.file_system = options.file_system;
  RunSession session(plan.options, {}, files, hooks);
  session.SetArchive(std::move(archive));
  session.earlier_stages.push_back({"import", report->import_seconds});
  const std::string kind = plan.kind;
  session.report_parameters = [version, kind](const TrellisReport& trellis) {
    std::ostringstream text;
    text << "reindex version " << version << " (" << kind << "); neighbour search: "
         << (trellis.search == TrellisSearchMode::kExact ? "exact" : "lsh");
    return text.str();
  };
  MOTIF_ASSIGN_OR_RETURN(MinePipelineResult result, MinePipeline(&session, plan.stages).Run());
  for (const MineStageTime& time : result.times) {
    if (time.stage == "trellis") report->trellis_seconds = time.seconds;
    if (time.stage == "grow") report->grow_seconds = time.seconds;
    if (time.stage == "cluster") report->cluster_seconds = time.seconds;
    if (time.stage == "report") report->report_seconds = time.seconds;
  }
  return result;
}

// The new version's manifest: the archive, the parameters recorded, the files, the build.
Result<ReindexManifest> DescribeVersion(const ReindexOptions& options, const ReindexPlan& plan,
                                        const std::optional<ReindexManifest>& current,
                                        uint64_t version, const ArchiveVersion& archive, double fps,
                                        const MinePipelineResult& result,
                                        const ReindexReport& report) {
  const std::string& out_dir = options.out_dir;
  ReindexManifest manifest;
  manifest.version = version;
  manifest.dir = VersionDirName(version);
  manifest.archive = archive;
  manifest.params = RecordedParams(plan, current ? &*current : nullptr, result, fps);
  manifest.build.kind = plan.kind;
  manifest.build.previous_version = plan.kind == "full" ? 0 : current->version;
  manifest.build.new_takes = report.takes_imported;
  manifest.build.new_frames =
      plan.kind == "incremental" ? archive.frames - current->archive.frames : 0;
  if (result.trellis.updated) {
    manifest.build.changed_columns = result.trellis.update.changed_columns;
    manifest.build.copied_blocks = result.trellis.update.copied_blocks;
    manifest.build.rewritten_blocks = result.trellis.update.rewritten_blocks;
  }
  const std::string trellis_path = Join(manifest.dir, "trellis.mtr");
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                         TrellisFileReader::Open(Join(out_dir, trellis_path)));
  manifest.trellis = {trellis_path, trellis->file_bytes(), trellis->identity()};
  MOTIF_ASSIGN_OR_RETURN(manifest.paths, DescribeFile(out_dir, Join(manifest.dir, "paths.mpa")));
  MOTIF_ASSIGN_OR_RETURN(manifest.motifs, DescribeFile(out_dir, Join(manifest.dir, "motifs.json")));
  if (!result.report_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(manifest.report,
                           DescribeFile(out_dir, Join(manifest.dir, "report.html")));
  }
  manifest.written = UtcNow();
  return manifest;
}

// The switch, then the files at their documented paths, then the old versions.
Status SwitchTo(const ReindexOptions& options, const ReindexManifest& manifest,
                ReindexReport* report) {
  const std::string& out_dir = options.out_dir;
  bool switched = false;
  Status status = WriteManifest(out_dir, manifest, options.file_system, &switched);
  if (!switched) return status;
  if (!status.ok()) {
    report->warnings.push_back(
        "version " + std::to_string(manifest.version) +
        " is current, but the folder could not be synced: " + status.message());
  }
  status = PublishCurrent(out_dir, manifest, options.file_system);
  if (!status.ok()) {
    report->warnings.push_back(
        Join(out_dir, "motifs.json") +
        " is still the previous version's (the next run replaces it): " + status.message());
  }
  std::error_code error;
  for (uint64_t old : ListVersions(out_dir)) {
    if (old + 1 >= manifest.version && old <= manifest.version) continue;  // current, previous
    fs::remove_all(Join(out_dir, VersionDirName(old)), error);
    if (!error) report->removed_versions.push_back(old);
  }
  report->manifest = manifest;
  return Status::Ok();
}

}  // namespace

Result<ReindexReport> Reindex(const ReindexOptions& options) {
  const Clock::time_point run_start = Clock::now();
  ReindexReport report;
  const RunLog log(options, &report);
  MOTIF_RETURN_IF_ERROR(CheckMineOptions(options.mine));
  ExclusiveFileLock lock;
  MOTIF_RETURN_IF_ERROR(LockAndClean(options, &lock));
  MOTIF_ASSIGN_OR_RETURN(std::optional<ReindexManifest> current, ReadCurrent(options));
  MOTIF_RETURN_IF_ERROR(ImportNewTakes(options, log, &report));
  if (report.waiting) {
    report.up_to_date = true;
    report.total_seconds = SecondsSince(run_start);
    return report;
  }
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> archive,
                         FrameFileReader::Open(options.archive_path));
  const ArchiveVersion archive_version = VersionOf(*archive, options.archive_path);
  const double fps = archive->fps();
  const ReindexPlan plan =
      PlanNextVersion(options.mine, options.given, current ? &*current : nullptr, *archive,
                      options.archive_path, options.out_dir);
  if (!plan.why.empty()) log.Note("full build: " + plan.why);
  if (plan.kind.empty()) {
    report.up_to_date = true;
    report.manifest = *current;
    report.total_seconds = SecondsSince(run_start);
    return report;
  }
  const uint64_t version = current ? current->version + 1 : 1;
  MOTIF_ASSIGN_OR_RETURN(MinePipelineResult result, MineVersion(options, plan, current, version,
                                                                std::move(archive), log, &report));
  MOTIF_ASSIGN_OR_RETURN(
      ReindexManifest manifest,
      DescribeVersion(options, plan, current, version, archive_version, fps, result, report));
  manifest.build.seconds = SecondsSince(run_start);
  MOTIF_RETURN_IF_ERROR(SwitchTo(options, manifest, &report));
  report.total_seconds = SecondsSince(run_start);
  return report;
}

}  // namespace motif
