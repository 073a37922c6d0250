// Reindex: `motifmine reindex ARCHIVE --watch DIR --out OUTDIR`, the nightly job that keeps the
// mined output of a growing archive up to date (docs/guide.md, `motifmine reindex`).
// One run:
//   1. takes OUTDIR/.motifmine.lock (Busy at once if another run holds it: cron's overlapping
//      runs never collide) and removes what killed runs left (temporary files);
//   2. scans DIR (ScanWatchedFolder) and imports the new takes into ARCHIVE (created if
//      missing) in one commit; changed files are reported, not imported;
//   3. builds the next version of the output in OUTDIR/v<N+1>/:
//        * "full" at the first run, when a parameter of the trellis changes, or when the archive
//          is not an extension of the version the manifest records;
//        * "incremental" when takes were appended: UpdateTrellis from version N's trellis
//          (eps, K_max, the search and its LSH family are the recorded ones);
//        * "regrow" when only grow or clustering parameters changed (the trellis is shared);
//      then the paths and the motifs, and the report: MinePipeline runs the plan ReindexPlan
//      works out (reindex_plan.h), so the stages are mine's;
//   4. switches: OUTDIR/manifest.json is replaced atomically (WriteManifest), then
//      OUTDIR/motifs.json and OUTDIR/report.html (renamed into place from the version's);
//   5. removes versions older than the previous one (a reader of the previous version keeps it
//      for a whole run; one that still has older files open keeps reading them, as POSIX keeps
//      an unlinked file's data while it is open).
// With nothing new and no parameter changed, no version is made ("up to date").
// Every stage of a killed run is resumed or reused by the next: the archive append is atomic,
// the trellis resumes from its partial file, paths and motifs are reused when their inputs
// match (tests/engine/cli/reindex_interrupt_test.cc, scripts/crash_harness.py).
// Thread-safety: one run per OUTDIR (the lock); a process may run one at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "engine/reindex/reindex_manifest.h"
#include "formats/import/take_importer.h"
#include "motifmine/options.h"

namespace motif {

struct ReindexOptions {
  std::string archive_path;
  std::string watch_dir;
  std::string out_dir;
  // The run's options (include/motifmine/options.h, the option table's). At the first run they
  // are the version's; after it, only those named in `given` replace the recorded ones (a change
  // rebuilds what depends on it), while threads, write_report and skip_bad are always this
  // run's. An explicit eps > 0 overrides eps_rule and eps_angle_degrees; giving a rule or an
  // angle the recorded eps was not estimated by estimates eps again (a full build).
  motifmine::MineOptions mine;
  std::set<std::string> given;  // option-table names ("kmax", "min-length", ...)
  double min_age_seconds = 60;  // files modified more recently wait for the next run
  ImportOptions import;
  FileSystem* file_system = PosixFileSystem();  // manifest, trellis, archive writes
  // Progress: (stage, done, total, unit); a new stage name begins a stage.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total,
                     const std::string& unit)>
      progress;
  std::function<void(const std::string&)> note;
};

struct ReindexReport {
  bool up_to_date = false;   // nothing new: no version made
  // No archive yet and every take of the folder is younger than min_age (a first night while
  // they are being copied in): nothing made, the next run imports them. Implies up_to_date.
  bool waiting = false;
  ReindexManifest manifest;  // the current one after the run
  uint64_t takes_scanned = 0;
  uint64_t takes_known = 0;
  uint64_t takes_imported = 0;
  uint64_t frames_imported = 0;
  std::vector<std::string> changed;   // files changed since their import (not imported)
  std::vector<std::string> failed;    // takes that failed to import (skip_bad)
  std::vector<std::string> settling;  // too recent, left for the next run
  std::vector<std::string> notes;     // why the build was full, etc.
  // Problems after the switch (the new version is current): a failed sync of the folder, or
  // OUTDIR/motifs.json not replaced yet (the next run replaces it).
  std::vector<std::string> warnings;
  std::vector<uint64_t> removed_versions;
  double import_seconds = 0;
  double trellis_seconds = 0;
  double grow_seconds = 0;
  double cluster_seconds = 0;
  double report_seconds = 0;
  double total_seconds = 0;
};

// Busy if another run holds OUTDIR's lock; NotFound if DIR does not exist or there is neither
// an archive nor a take to make one; the errors of each stage (InvalidArgument for a malformed
// take without skip_bad, Corruption, IOError, ResourceExhausted on a full disk). On any error
// the current version (manifest.json and every file it names) is unchanged; a failure after
// the switch (the manifest renamed into place) is a warning of a successful run instead.
Result<ReindexReport> Reindex(const ReindexOptions& options);

}  // namespace motif
