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
#include "engine/cluster/cluster_stage.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/grow/path_grower.h"
#include "engine/grow/paths_builder.h"
#include "engine/ingest/archive_import.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_search.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/pipeline/motif_stages.h"
#include "engine/reindex/search_cache.h"
#include "engine/reindex/watched_takes.h"
#include "engine/report/report_html.h"
#include "engine/trellis/trellis_update.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr char kLockName[] = ".motifmine.lock";
const std::vector<std::string> kTopFiles = {"manifest.json", "motifs.json", "report.html"};
const std::vector<std::string> kVersionFiles = {"trellis.mtr",        "paths.mpa",   "motifs.json",
                                                "cluster_state.json", "report.html", "search.msc"};
constexpr char kSearchCacheName[] = "search.msc";

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

// The trellis-determining part of the parameters.
bool SameTrellisParams(const MiningParams& a, const MiningParams& b) {
  return a.eps == b.eps && a.k_max == b.k_max && a.exclusion_frames == b.exclusion_frames &&
         a.exact == b.exact && (a.exact || SameLshFamily(a.lsh, b.lsh)) && a.seed == b.seed &&
         a.weights_path == b.weights_path && a.min_length == b.min_length;
}

// The rule eps is estimated by: as given, else the recorded one, else mine's default.
struct EpsRuleChoice {
  EpsilonRule rule = EpsilonRule::kJointAngle;
  double angle_degrees = kDefaultJointAngleDegrees;
};

EpsRuleChoice ChooseEpsRule(const ReindexOptions& options, const ReindexManifest* current) {
  EpsRuleChoice choice;
  if (current && current->params.eps_rule == "paper") choice.rule = EpsilonRule::kPaper;
  if (current && current->params.eps_angle_degrees > 0) {
    choice.angle_degrees = current->params.eps_angle_degrees;
  }
  if (options.eps_rule) choice.rule = *options.eps_rule;
  if (options.eps_angle_degrees) choice.angle_degrees = *options.eps_angle_degrees;
  return choice;
}

// A rule given on the command line that the recorded eps was not estimated by (an explicit
// eps overrides the rule, as in mine).
bool EpsRuleChanged(const ReindexOptions& options, const MiningParams& recorded,
                    const EpsRuleChoice& choice) {
  if (!options.eps_rule && !options.eps_angle_degrees) return false;
  if (options.eps && *options.eps > 0) return false;
  if (!recorded.eps_estimated || recorded.eps_rule != EpsilonRuleName(choice.rule)) return true;
  return choice.rule == EpsilonRule::kJointAngle &&
         recorded.eps_angle_degrees != choice.angle_degrees;
}

struct Plan {
  std::string kind;     // "full", "incremental", "regrow", or "" (up to date)
  std::string why;      // for a full build after the first
  MiningParams params;  // what the new version uses (eps may still be 0: to estimate)
  bool estimate_eps = false;
  EpsRuleChoice eps_rule;  // how, when estimate_eps
};

}  // namespace

Result<ReindexReport> Reindex(const ReindexOptions& options) {
  const Clock::time_point run_start = Clock::now();
  ReindexReport report;
  auto note = [&](const std::string& message) {
    report.notes.push_back(message);
    if (options.note) options.note(message);
  };
  auto progress = [&](const std::string& stage, uint64_t done, uint64_t total,
                      const std::string& unit) {
    if (options.progress) options.progress(stage, done, total, unit);
  };
  const std::string& out_dir = options.out_dir;
  const std::string& archive_path = options.archive_path;
  FileSystem* file_system = options.file_system;
  if (options.eps_angle_degrees &&
      !(*options.eps_angle_degrees > 0 && *options.eps_angle_degrees <= 180)) {
    return Status::InvalidArgument("--eps-angle must be in (0, 180] degrees, not " +
                                   std::to_string(*options.eps_angle_degrees));
  }

  // 1. One run at a time per OUTDIR; what killed runs left is removed.
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error) return Status::IOError("cannot create " + out_dir + ": " + error.message());
  ExclusiveFileLock lock;
  MOTIF_RETURN_IF_ERROR(lock.Acquire(Join(out_dir, kLockName),
                                     "another motifmine run is working in this folder; nothing "
                                     "was changed (exit 17: it will be done next time)",
                                     /*create=*/true));
  RemoveStaleTemporaries(out_dir, kTopFiles);
  for (uint64_t version : ListVersions(out_dir)) {
    RemoveStaleTemporaries(Join(out_dir, VersionDirName(version)), kVersionFiles);
  }
  const std::string archive_dir = fs::path(WatchedPath(archive_path)).parent_path().string();
  RemoveStaleTemporaries(archive_dir, {fs::path(archive_path).filename().string()});

  std::optional<ReindexManifest> current;
  {
    Result<ReindexManifest> read = ReadManifest(out_dir);
    if (read.ok()) {
      current = std::move(read.value());
    } else if (!read.status().IsNotFound()) {
      return Status::Corruption(read.status().message() +
                                " (the output's manifest is damaged; move OUTDIR away to "
                                "rebuild from scratch)");
    }
  }
  // A run killed (or short of room) between the switch and the publication of motifs.json.
  if (current) MOTIF_RETURN_IF_ERROR(PublishCurrent(out_dir, *current, file_system));

  // 2. New takes: scanned against the archive's clips, imported in one commit.
  Clock::time_point start = Clock::now();
  std::vector<ClipInfo> clips;
  const bool archive_exists = fs::exists(archive_path, error);
  if (archive_exists) {
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> before,
                           FrameFileReader::Open(archive_path));
    clips = before->clips();
  }
  MOTIF_ASSIGN_OR_RETURN(WatchScan scan, ScanWatchedFolder(options.watch_dir, clips, options.import,
                                                           options.min_age_seconds));
  report.takes_scanned = scan.new_takes.size() + scan.known_takes + scan.changed.size();
  report.takes_known = scan.known_takes;
  report.changed = scan.changed;
  report.settling = scan.settling;
  for (const std::string& message : scan.changed) note("changed: " + message);
  if (!scan.settling.empty()) {
    note(std::to_string(scan.settling.size()) + " take(s) modified in the last " +
         std::to_string(options.min_age_seconds) +
         " s are left for the next run (still being copied?), e.g. " + scan.settling.front());
  }
  if (!scan.new_takes.empty()) {
    ArchiveImportOptions import_options;
    import_options.import = options.import;
    import_options.skip_bad = options.skip_bad;
    import_options.threads = options.threads;
    import_options.file_system = file_system;
    import_options.note = [&](const std::string& message) { note(message); };
    import_options.progress = [&](uint64_t done, uint64_t total) {
      progress("import", done, total, "takes");
    };
    progress("import", 0, scan.new_takes.size(), "takes");
    Result<ArchiveImportResult> imported =
        ImportTakesIntoArchive(archive_path, scan.new_takes, import_options);
    if (!imported.ok()) return imported.status();
    report.takes_imported = imported->takes_imported;
    report.frames_imported = imported->frames_added;
    report.takes_known += imported->takes_already_present;
    report.failed = imported->failures;
  } else if (!archive_exists) {
    return Status::NotFound(archive_path + " does not exist and " + options.watch_dir +
                            " holds no take to make it from");
  }
  report.import_seconds = SecondsSince(start);
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> archive,
                         FrameFileReader::Open(archive_path));
  const ArchiveVersion archive_version = VersionOf(*archive, archive_path);
  const double fps = archive->fps();

  // 3. What to build: the parameters wanted, against the recorded ones.
  Plan plan;
  {
    MiningParams& wanted = plan.params;
    if (current) {
      wanted = current->params;
    } else {
      // The defaults of `motifmine mine`, defined once (DefaultMinePipelineOptions).
      const MinePipelineOptions defaults = DefaultMinePipelineOptions();
      wanted.k_max = defaults.trellis.k_max;
      wanted.seed = defaults.seed;
      wanted.branch = defaults.paths.branch;
      wanted.min_length = MinLengthFrames(defaults.paths.min_length_seconds, fps);
      wanted.max_ncut = defaults.cluster.cut.max_ncut;
      wanted.min_similarity = defaults.cluster.similarity.min_similarity;
      wanted.max_length_ratio = defaults.cluster.max_length_ratio;
      wanted.block_columns = TrellisOptions{}.block_columns;
    }
    if (options.k_max) wanted.k_max = *options.k_max;
    if (options.seed) wanted.seed = *options.seed;
    if (options.weights_path) wanted.weights_path = *options.weights_path;
    if (options.branch) wanted.branch = *options.branch;
    if (options.min_length_frames && *options.min_length_frames > 0) {
      wanted.min_length = *options.min_length_frames;
    } else if (options.min_length_seconds) {
      wanted.min_length = MinLengthFrames(*options.min_length_seconds, fps);
    }
    if (options.groups) wanted.groups = *options.groups;
    if (options.max_ncut) wanted.max_ncut = *options.max_ncut;
    if (options.min_similarity) wanted.min_similarity = *options.min_similarity;
    if (options.max_length_ratio) wanted.max_length_ratio = *options.max_length_ratio;
    // The trellis's own parameters: a change means a full build, which resolves them again.
    bool trellis_change = !current;
    if (options.eps && (*options.eps == 0 || !current || *options.eps != current->params.eps)) {
      trellis_change = true;
    }
    plan.eps_rule = ChooseEpsRule(options, current ? &*current : nullptr);
    const bool eps_rule_changed =
        current && EpsRuleChanged(options, current->params, plan.eps_rule);
    if (eps_rule_changed) trellis_change = true;
    if (options.exclusion && (!current || *options.exclusion != current->params.exclusion_frames)) {
      trellis_change = true;
    }
    if (options.search && current &&
        (*options.search == TrellisSearchMode::kAuto ||
         (*options.search == TrellisSearchMode::kExact) != current->params.exact)) {
      trellis_change = true;
    }
    if (current && !current->params.exact &&
        ((options.lsh_tables && *options.lsh_tables != current->params.lsh.tables) ||
         (options.lsh_hashes && *options.lsh_hashes != current->params.lsh.hashes_per_table) ||
         (options.lsh_width && *options.lsh_width != current->params.lsh.bucket_width))) {
      trellis_change = true;
    }
    if (current && !SameTrellisParams(wanted, current->params)) trellis_change = true;
    if (trellis_change) {
      plan.kind = "full";
      if (current) {
        plan.why = eps_rule_changed ? std::string("eps is estimated again, by the rule ") +
                                          EpsilonRuleName(plan.eps_rule.rule)
                                    : "a parameter of the trellis changed";
      }
    } else {
      // The archive must extend the version the manifest names: same file, that commit intact.
      Result<std::unique_ptr<FrameFileReader>> pinned = FrameFileReader::OpenCommit(
          archive_path, current->archive.generation, current->archive.committed_bytes);
      if (!pinned.ok() || (*pinned)->summary().identity != current->archive.identity) {
        plan.kind = "full";
        plan.why = "the archive is not an extension of the one version " +
                   std::to_string(current->version) + " was mined from" +
                   (pinned.ok() ? std::string() : " (" + pinned.status().message() + ")");
      } else if (archive_version.identity != current->archive.identity) {
        plan.kind = "incremental";
      } else if (!(wanted == current->params)) {
        plan.kind = "regrow";
      }
    }
    if (plan.kind == "full") {
      // eps: as given; else the recorded one; estimated at the first build, with --eps 0 or
      // when the rule changed.
      wanted.eps = options.eps                      ? *options.eps
                   : (current && !eps_rule_changed) ? current->params.eps
                                                    : 0.0f;
      plan.estimate_eps = wanted.eps == 0;
      if (plan.estimate_eps) {
        wanted.eps_estimated = true;
        wanted.eps_rule = EpsilonRuleName(plan.eps_rule.rule);
        wanted.eps_angle_degrees =
            plan.eps_rule.rule == EpsilonRule::kJointAngle ? plan.eps_rule.angle_degrees : 0.0;
      } else if (options.eps) {  // given: nothing was estimated
        wanted.eps_estimated = false;
        wanted.mu = 0;
        wanted.sigma = 0;
        wanted.eps_rule.clear();
        wanted.eps_angle_degrees = 0;
      }
      if (options.exclusion)
        wanted.exclusion_frames = *options.exclusion;
      else if (!current)
        wanted.exclusion_frames = 0;  // resolved by the build
    }
  }
  if (!plan.why.empty()) note("full build: " + plan.why);
  if (plan.kind.empty()) {
    report.up_to_date = true;
    report.manifest = *current;
    report.total_seconds = SecondsSince(run_start);
    return report;
  }

  // 4. The next version, in its own folder (a killed run's files there are resumed or reused).
  const uint64_t version = current ? current->version + 1 : 1;
  const std::string version_dir = VersionDirName(version);
  const std::string version_path = Join(out_dir, version_dir);
  fs::create_directories(version_path, error);
  if (error) return Status::IOError("cannot create " + version_path + ": " + error.message());
  const std::string trellis_path = Join(version_path, "trellis.mtr");
  MiningParams& params = plan.params;
  ReindexManifest manifest;
  manifest.version = version;
  manifest.dir = version_dir;
  manifest.archive = archive_version;
  manifest.build.kind = plan.kind;
  manifest.build.previous_version = plan.kind == "full" ? 0 : current->version;
  manifest.build.new_takes = report.takes_imported;
  manifest.build.new_frames =
      plan.kind == "incremental" ? archive_version.frames - current->archive.frames : 0;

  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(archive->skeleton(), params.weights_path));
  const uint64_t weights_hash = WeightsHash(weights);
  start = Clock::now();
  std::string trellis_stage;
  auto trellis_progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    const std::string name = stage == "trellis" ? "trellis" : "trellis " + stage;
    const std::string unit = stage == "eps"                              ? "pairs"
                             : stage == "features"                       ? "frames"
                             : stage == "thresholds" || stage == "merge" ? "blocks"
                                                                         : "columns";
    progress(name, done, total, unit);
  };
  if (plan.kind == "full") {
    TrellisOptions trellis;
    trellis.eps = params.eps;
    trellis.eps_rule = plan.eps_rule.rule;
    trellis.eps_joint_angle_degrees = plan.eps_rule.angle_degrees;
    trellis.k_max = params.k_max;
    trellis.exclusion_frames = params.exclusion_frames;
    trellis.min_length_seconds = static_cast<double>(params.min_length) / fps;
    trellis.search =
        options.search ? *options.search
        : current ? (current->params.exact ? TrellisSearchMode::kExact : TrellisSearchMode::kLsh)
                  : TrellisSearchMode::kAuto;
    trellis.threads = options.threads;
    trellis.seed = params.seed;
    trellis.weights_path = params.weights_path;
    trellis.block_columns = params.block_columns;
    if (current && !current->params.exact && trellis.search != TrellisSearchMode::kExact) {
      trellis.lsh = current->params.lsh;  // the recorded family, unless overridden below
    }
    if (options.lsh_tables) trellis.lsh.tables = *options.lsh_tables;
    if (options.lsh_hashes) trellis.lsh.hashes_per_table = *options.lsh_hashes;
    if (options.lsh_width) trellis.lsh.bucket_width = *options.lsh_width;
    trellis.progress = trellis_progress;
    trellis.note = note;
    trellis.archive_version = {archive_version.generation, archive_version.committed_bytes};
    // The features and the LSH tables, kept for the next run (not the thresholds: the next
    // update decodes the trellis once for them). Best effort: it is a cache.
    trellis.on_search_done = [&](const PoseFeatures& features, const NeighbourSearch& search) {
      const auto* lsh_search = dynamic_cast<const LshSearch*>(&search);
      SearchCacheKey key{archive_version.identity, weights_hash,
                         lsh_search ? DescribeLshOptions(lsh_search->options()) : ""};
      Status saved =
          WriteSearchCache(Join(version_path, kSearchCacheName), key, features,
                           lsh_search ? &lsh_search->index() : nullptr, 0, {}, file_system);
      if (!saved.ok())
        note("search cache not saved (the next run rebuilds it): " + saved.message());
    };
    MOTIF_ASSIGN_OR_RETURN(TrellisReport built, BuildTrellis(archive_path, trellis_path, trellis));
    params.eps = built.params.eps;
    if (plan.estimate_eps) {
      params.mu = built.params.mu;
      params.sigma = built.params.sigma;
    }
    params.exclusion_frames = built.params.exclusion_frames;
    params.exact = built.search == TrellisSearchMode::kExact;
    params.lsh = params.exact ? LshOptions{} : built.lsh_resolved;
    params.lsh.threads = 0;
    params.weights_hash = built.params.weights_hash;
  } else if (plan.kind == "incremental") {
    const std::string previous_path = Join(out_dir, current->trellis.path);
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> previous,
                           TrellisFileReader::Open(previous_path));
    TrellisParams trellis_params = previous->params();
    trellis_params.frame_count = archive->frame_count();
    trellis_params.archive_identity = archive_version.identity;
    trellis_params.mu = 0;  // eps is given from now on, as `mine --eps` gives it
    trellis_params.sigma = 0;
    LshOptions lsh = params.lsh;
    lsh.seed = params.seed;
    lsh.threads = options.threads;
    trellis_params.search_params = params.exact ? "exact" : DescribeLshOptions(lsh);
    const std::string family = params.exact ? "" : DescribeLshOptions(lsh);
    // Reused when a killed run finished it.
    bool reused = false;
    if (fs::exists(trellis_path, error)) {
      Result<std::unique_ptr<TrellisFileReader>> done = TrellisFileReader::Open(trellis_path);
      reused = done.ok() && (*done)->params() == trellis_params;
    }
    if (!reused) {
      // The previous version's features, LSH tables and thresholds, extended with the new
      // frames; computed from the whole archive when the cache is missing or stale.
      auto features_progress = [&](uint64_t done, uint64_t total) {
        progress("trellis features", done, total, "frames");
      };
      progress("trellis features", 0, archive->frame_count(), "frames");
      Result<SearchCache> cache =
          ReadSearchCache(Join(Join(out_dir, current->dir), kSearchCacheName));
      const SearchCacheKey previous_key{current->archive.identity, weights_hash, family};
      const bool cached = cache.ok() && cache->key == previous_key &&
                          cache->features.frame_count() == current->archive.frames &&
                          (params.exact || cache->tables.size() == lsh.tables);
      if (!cached) {
        note("no search cache of version " + std::to_string(current->version) +
             (cache.ok() ? std::string(" for these parameters") : ": " + cache.status().message()) +
             "; decoding the whole archive");
      }
      std::optional<PoseFeatures> features_holder;
      if (cached) {
        MOTIF_ASSIGN_OR_RETURN(features_holder,
                               PoseFeatures::ExtendFromArchive(std::move(cache->features), *archive,
                                                               weights, features_progress));
      } else {
        MOTIF_ASSIGN_OR_RETURN(features_holder,
                               PoseFeatures::FromArchive(*archive, weights, features_progress));
      }
      const PoseFeatures& features = *features_holder;
      NeighbourRules rules;
      rules.eps = params.eps;
      rules.k_max = params.k_max;
      rules.exclusion_frames = params.exclusion_frames;
      rules.clip_first_frames = features.clip_first_frames();
      std::unique_ptr<NeighbourSearch> search;
      const LshSearch* lsh_search = nullptr;
      if (params.exact) {
        ExactSearchOptions exact;
        exact.threads = options.threads > 0 ? static_cast<uint32_t>(options.threads) : 0;
        search = std::make_unique<ExactSearch>(features, rules, exact);
      } else {
        std::unique_ptr<LshSearch> made;
        if (cached) {
          MOTIF_ASSIGN_OR_RETURN(LshIndex index, LshIndex::FromTables(current->archive.frames,
                                                                      std::move(cache->tables),
                                                                      cache->position_codes));
          const HashFamily hash_family = HashFamily::Draw(
              features.weights(), lsh.tables, lsh.hashes_per_table, lsh.bucket_width, lsh.seed);
          MOTIF_RETURN_IF_ERROR(
              index.Extend(features, hash_family, lsh.shard_frames, options.threads));
          MOTIF_ASSIGN_OR_RETURN(
              made, LshSearch::CreateWithIndex(features, rules, lsh, std::move(index)));
        } else {
          MOTIF_ASSIGN_OR_RETURN(made, LshSearch::Create(features, rules, lsh));
        }
        lsh_search = made.get();
        search = std::move(made);
      }
      // The paths grow as the blocks are written (one pass over the new trellis, beside the
      // merge), unless the update resumes an interrupted one: BuildPaths grows them then.
      std::vector<uint64_t> clip_starts;
      for (const ClipInfo& clip : archive->clips()) clip_starts.push_back(clip.first_frame);
      GrowOptions grow;
      grow.branch = params.branch;
      grow.min_length = params.min_length;
      MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<PathGrower> grower,
                             PathGrower::Create(archive->frame_count(), clip_starts, grow));
      std::vector<float> next_thresholds;
      TrellisUpdateOptions update;
      update.threads = options.threads;
      update.file_system = file_system;
      update.progress = trellis_progress;
      const bool thresholds_cached = cached && cache->trellis_identity == previous->identity() &&
                                     cache->thresholds.size() == previous->column_count();
      if (thresholds_cached) update.thresholds = &cache->thresholds;
      update.next_thresholds = &next_thresholds;
      update.on_block = [&](uint64_t first_column,
                            const std::vector<std::vector<Neighbour>>& columns) -> Status {
        if (grower->next_column() != first_column) return Status::Ok();  // resumed: BuildPaths
        for (const std::vector<Neighbour>& column : columns) {
          MOTIF_RETURN_IF_ERROR(grower->AddColumn(column.data(), column.size()));
        }
        return Status::Ok();
      };
      MOTIF_ASSIGN_OR_RETURN(
          TrellisUpdateReport updated,
          UpdateTrellis(*previous, features, rules, *search, trellis_params, trellis_path, update));
      manifest.build.changed_columns = updated.changed_columns;
      manifest.build.copied_blocks = updated.copied_blocks;
      manifest.build.rewritten_blocks = updated.rewritten_blocks;
      note("trellis update: " + std::to_string(updated.new_columns) + " new columns, " +
           std::to_string(updated.changed_columns) + " of " + std::to_string(updated.old_columns) +
           " old columns changed; " + std::to_string(updated.copied_blocks) + " blocks copied, " +
           std::to_string(updated.rewritten_blocks) + " rewritten");
      MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> written,
                             TrellisFileReader::Open(trellis_path));
      if (grower->next_column() == archive->frame_count()) {
        MOTIF_ASSIGN_OR_RETURN(std::vector<PathCandidate> candidates, grower->Finish());
        PathsParams paths_params;
        paths_params.trellis_identity = written->identity();
        paths_params.archive_identity = archive_version.identity;
        paths_params.frame_count = archive->frame_count();
        paths_params.branch = grow.branch;
        paths_params.min_length = grow.min_length;
        MOTIF_RETURN_IF_ERROR(
            WritePathsFile(Join(version_path, "paths.mpa"), paths_params, candidates));
      }
      Status saved = WriteSearchCache(Join(version_path, kSearchCacheName),
                                      {archive_version.identity, weights_hash, family}, features,
                                      lsh_search ? &lsh_search->index() : nullptr,
                                      written->identity(), next_thresholds, file_system);
      if (!saved.ok())
        note("search cache not saved (the next run rebuilds it): " + saved.message());
    }
  } else {  // regrow: the same trellis, and the same search cache (best effort)
    const std::string previous_path = Join(out_dir, current->trellis.path);
    if (!fs::exists(trellis_path, error)) {
      fs::create_hard_link(previous_path, trellis_path, error);
      if (error) fs::copy_file(previous_path, trellis_path, error);
      if (error) {
        return Status::IOError("cannot link " + previous_path + " to " + trellis_path + ": " +
                               error.message());
      }
    }
    const std::string cache_path = Join(version_path, kSearchCacheName);
    if (!fs::exists(cache_path, error)) {
      fs::create_hard_link(Join(Join(out_dir, current->dir), kSearchCacheName), cache_path, error);
    }
  }
  report.trellis_seconds = SecondsSince(start);
  {
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                           TrellisFileReader::Open(trellis_path));
    manifest.trellis = {Join(version_dir, "trellis.mtr"), trellis->file_bytes(),
                        trellis->identity()};
  }

  // 5. Paths and motifs: the stages mine runs after its trellis (RunMotifStages).
  MotifStagesInput stages_input;
  // Absolute: OUTDIR/motifs.json is a byte copy of this version's, one folder up.
  stages_input.archive_path = fs::absolute(archive_path).lexically_normal().string();
  stages_input.archive = archive.get();
  stages_input.trellis_path = trellis_path;
  stages_input.paths_path = Join(version_path, "paths.mpa");
  stages_input.motifs_path = Join(version_path, "motifs.json");
  stages_input.state_path = Join(version_path, "cluster_state.json");
  stages_input.paths.branch = params.branch;
  stages_input.paths.min_length_frames = params.min_length;
  ClusterOptions& cluster = stages_input.cluster;
  cluster.seed = params.seed;
  cluster.threads = options.threads;
  cluster.cut.groups = params.groups;
  cluster.cut.max_ncut = params.max_ncut;
  cluster.similarity.min_similarity = params.min_similarity;
  cluster.max_length_ratio = params.max_length_ratio;
  stages_input.progress = [&](const std::string& stage, uint64_t done, uint64_t total,
                              const std::string& unit) { progress(stage, done, total, unit); };
  MOTIF_ASSIGN_OR_RETURN(MotifStagesResult stages, RunMotifStages(stages_input));
  const ClusterStageResult& clustered = stages.clustered;
  report.grow_seconds = stages.grow_seconds;
  report.cluster_seconds = stages.cluster_seconds;
  MOTIF_ASSIGN_OR_RETURN(manifest.paths, DescribeFile(out_dir, Join(version_dir, "paths.mpa")));
  MOTIF_ASSIGN_OR_RETURN(manifest.motifs, DescribeFile(out_dir, Join(version_dir, "motifs.json")));
  if (options.report) {
    start = Clock::now();
    progress("report", 0, 1, "files");
    ReportInfo info;
    info.archive_path = archive_path;
    std::ostringstream text;
    text << "reindex version " << version << " (" << plan.kind
         << "); neighbour search: " << (params.exact ? "exact" : "lsh");
    info.parameters_text = text.str();
    info.timings = {{"import", report.import_seconds},
                    {"trellis", report.trellis_seconds},
                    {"grow", report.grow_seconds},
                    {"cluster", report.cluster_seconds}};
    const std::string report_relative = Join(version_dir, "report.html");
    MOTIF_RETURN_IF_ERROR(
        WriteReportHtml(Join(out_dir, report_relative), clustered.document, *archive, info));
    MOTIF_ASSIGN_OR_RETURN(manifest.report, DescribeFile(out_dir, report_relative));
    progress("report", 1, 1, "files");
    report.report_seconds = SecondsSince(start);
  }

  // 6. The switch, then the files at their documented paths, then the old versions.
  params.lsh.threads = 0;
  manifest.params = params;
  manifest.written = UtcNow();
  manifest.build.seconds = SecondsSince(run_start);
  bool switched = false;
  Status status = WriteManifest(out_dir, manifest, file_system, &switched);
  if (!switched) return status;
  if (!status.ok()) {
    report.warnings.push_back(
        "version " + std::to_string(version) +
        " is current, but the folder could not be synced: " + status.message());
  }
  status = PublishCurrent(out_dir, manifest, file_system);
  if (!status.ok()) {
    report.warnings.push_back(
        Join(out_dir, "motifs.json") +
        " is still the previous version's (the next run replaces it): " + status.message());
  }
  for (uint64_t old : ListVersions(out_dir)) {
    if (old + 1 >= version && old <= version) continue;  // the current and the previous
    fs::remove_all(Join(out_dir, VersionDirName(old)), error);
    if (!error) report.removed_versions.push_back(old);
  }
  report.manifest = manifest;
  report.total_seconds = SecondsSince(run_start);
  return report;
}

}  // namespace motif
