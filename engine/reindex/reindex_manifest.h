// ReindexManifest: OUTDIR/manifest.json of `motifmine reindex`, the one file that says which
// version of the mined output is current (docs/formats/reindex_manifest.md). Every version lives
// in a folder of its own (OUTDIR/v000003/: trellis.mtr, paths.mpa, motifs.json, report.html);
// the manifest names it, the archive version (commit) it was mined from, the parameters recorded
// at the first build (eps, the LSH family, ...), and what each file must be (size, checksum or
// identity). A new version is switched in by writing the whole manifest to a temporary file and
// renaming it over manifest.json: a reader sees the old manifest or the new one, and both name
// complete files.
// Thread-safety: values and pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/status.h"
#include "common/writable_file.h"
#include "engine/lsh/lsh_options.h"
#include "motifmine/defaults.h"

namespace motif {

// The archive version a result was mined from (FrameFileSummary of a reader of it).
struct ArchiveVersion {
  std::string path;         // absolute
  uint64_t generation = 0;  // the commit
  uint64_t committed_bytes = 0;
  uint64_t identity = 0;  // the metadata checksum
  uint64_t frames = 0;
  uint64_t clips = 0;
  bool operator==(const ArchiveVersion&) const = default;
};

// One output file of a version, relative to OUTDIR, with what identifies its content.
struct VersionFile {
  std::string path;  // e.g. "v000003/motifs.json"; empty: not written
  uint64_t bytes = 0;
  uint64_t checksum = 0;  // XXH3-64 of the whole file (motifs.json, paths.mpa, report.html), or
                          // the trellis file's identity (its footer checksum)
  bool operator==(const VersionFile&) const = default;
};

// Everything that determines the result, recorded at the first build and reused by later ones
// unless the command line changes it (a change rebuilds everything after the archive).
struct MiningParams {
  float eps = 0;               // the eps every version uses
  bool eps_estimated = false;  // chosen by the first build's rule (not given)
  float mu = 0;                // of that estimate (0 if eps was given)
  float sigma = 0;
  // The rule that estimated eps ("joint-angle" or "paper", epsilon_estimator.h) and the joint
  // angle of "joint-angle"; "" and 0 when eps was given or the manifest predates the fields.
  std::string eps_rule;
  double eps_angle_degrees = 0;
  uint32_t k_max = 0;
  uint32_t exclusion_frames = 0;
  bool exact = false;  // the search: exact, or LSH with the family below
  LshOptions lsh;      // resolved (hashes_per_table and bucket_width as drawn)
  uint64_t seed = 0;
  std::string weights_path;  // empty: the skeleton's defaults
  uint64_t weights_hash = 0;
  uint32_t block_columns = 0;
  uint32_t branch = 0;
  uint64_t min_length = 0;  // lambda in frames
  uint32_t groups = 0;      // 0: auto
  double max_ncut = 0;
  double min_similarity = 0;
  double max_length_ratio = 0;
  // How instance pairs are weighted and the pauses instances are trimmed at; absent from
  // manifests written before they were recorded (2026-12-01), read as mine's defaults then.
  std::string similarity = motifmine::defaults::kSimilarity;
  double pause_speed = motifmine::defaults::kPauseSpeed;
  double pause_seconds = motifmine::defaults::kPauseSeconds;
  // Every field equal; the LSH options only when the search is LSH (threads never count).
  bool operator==(const MiningParams& other) const;
};

// The LSH options that determine the columns (all but the thread count) are equal.
bool SameLshFamily(const LshOptions& a, const LshOptions& b);

// What the build of a version did (informative).
struct BuildRecord {
  std::string kind;               // "full", "incremental" or "regrow" (same trellis)
  uint64_t previous_version = 0;  // 0 for a full build
  uint64_t new_takes = 0;
  uint64_t new_frames = 0;
  uint64_t changed_columns = 0;
  uint64_t copied_blocks = 0;
  uint64_t rewritten_blocks = 0;
  double seconds = 0;
};

struct ReindexManifest {
  uint64_t version = 0;  // 1 for the first build, then +1 per switch
  std::string dir;       // the version's folder, relative to OUTDIR: "v000003"
  std::string written;   // UTC, ISO 8601
  ArchiveVersion archive;
  MiningParams params;
  VersionFile trellis;
  VersionFile paths;
  VersionFile motifs;
  VersionFile report;  // path empty without a report
  BuildRecord build;
};

// "v000003" for version 3.
std::string VersionDirName(uint64_t version);
// OUTDIR/manifest.json.
std::string ManifestPath(const std::string& out_dir);

std::string ManifestText(const ReindexManifest& manifest);
// InvalidArgument naming the field for anything malformed, NotSupported for another format
// version.
Result<ReindexManifest> ParseManifest(const std::string& text, const std::string& name);
// NotFound if OUTDIR has no manifest (no version yet); as ParseManifest otherwise.
Result<ReindexManifest> ReadManifest(const std::string& out_dir);
// The switch: written whole to a temporary file, synced, renamed over OUTDIR/manifest.json (the
// commit point), directory synced. IOError / ResourceExhausted; *switched (if given) says
// whether the rename was done: a failure after it (the directory's sync) leaves the new
// manifest current, only not yet certain to survive a power loss.
Status WriteManifest(const std::string& out_dir, const ReindexManifest& manifest,
                     FileSystem* file_system = PosixFileSystem(), bool* switched = nullptr);

}  // namespace motif
