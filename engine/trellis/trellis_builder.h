// BuildTrellis: an archive's matching trellis (docs/design/algorithm.md steps 1-2). Streams the
// archive once into PoseFeatures (the weighted joints, 96 bytes a frame for CMU takes), chooses
// eps (explicit, or by EpsilonRule: the joint angle by default), finds every column with LSH or the
// exact brute force (by default the exact search below kAutoExactMaxFrames frames, where it is
// faster, LSH above), and spills the columns to the trellis file block by block as they are
// found, so the whole trellis is never in memory: peak memory is the features, the LSH index and
// two blocks of columns. The search of block b + 1 overlaps the compression and write (fsync)
// of block b on a writer thread, so the search threads never wait for the disk.
//
// Resumable and reusable: the trellis file records its parameters and the archive's identity.
// A finished file with equal parameters is reused as it is; an interrupted build resumes after
// its last complete block (TrellisFileWriter); changed parameters or a changed archive rebuild.
// The result is the same for any thread count (each column depends only on the data, the
// parameters and the seed).
// Thread-safety: one build per trellis file at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/rank_group.h"
#include "common/status.h"
#include "common/writable_file.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/distance/neighbour_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_options.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {

// How the columns are found. kAuto: exact below auto_exact_max_frames frames, LSH from there on.
enum class TrellisSearchMode { kAuto, kLsh, kExact };

// "auto", "lsh", "exact".
const char* TrellisSearchModeName(TrellisSearchMode mode);
// The inverse; InvalidArgument for anything else.
Result<TrellisSearchMode> ParseTrellisSearchMode(const std::string& name);

// Below this many frames kAuto uses the exact search (recall 1). Chosen where the exact and LSH
// builds crossed with the position-code ranking of an earlier engine (77,000-88,000 frames);
// with the default sort-value ranking they cross near 45,000 frames, and at 65,536 frames the
// exact build takes 1.5x the LSH one (docs/benchmarks.md, "Exact against LSH"). Rerun
// scripts/bench_trellis.sh after changing the LSH search.
inline constexpr uint64_t kAutoExactMaxFrames = 90000;

struct TrellisOptions {
  float eps = 0;                                    // > 0: explicit; 0: from eps_rule
  EpsilonRule eps_rule = EpsilonRule::kJointAngle;  // epsilon_estimator.h
  double eps_joint_angle_degrees = kDefaultJointAngleDegrees;
  uint64_t eps_sample_pairs = 200000;
  uint32_t k_max = NeighbourRules{}.k_max;  // 256
  // Trivial-match exclusion radius in frames; 0: half the default minimum motif length (0.5 s)
  // at the archive's rate. A run resolves it from its own λ (engine/pipeline/stage_options.h).
  uint32_t exclusion_frames = 0;
  TrellisSearchMode search = TrellisSearchMode::kAuto;
  uint64_t auto_exact_max_frames = kAutoExactMaxFrames;  // kAuto: exact when N < this
  bool exact = false;  // the same as search = kExact (kept for existing callers)
  int threads = 0;     // 0: all cores
  uint64_t seed = 1;
  FrameFileVersion archive_version;  // BuildTrellis by path: the version to read (the newest)
  std::string weights_path;          // per-joint weights file; empty: the skeleton's defaults
  LshOptions lsh;                    // lsh.seed and lsh.threads are set from seed and threads
  uint32_t block_columns = 4096;
  // Testing: stop with IOError after writing this many blocks (0: never), leaving the partial
  // file as an interruption would.
  uint64_t stop_after_blocks = 0;
  // Non-empty: once every column is written, the features and the LSH tables of this build are
  // written there (search_cache.h), for an incremental update later (motifmine reindex). Not
  // when a finished trellis is reused. A cache: a failure to write it is a note, not an error.
  std::string search_cache_path;
  FileSystem* file_system = PosixFileSystem();  // the search cache's writes
  // Stages: "features", "eps", "index", "trellis"; (done, total) in frames / pairs / columns.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total)> progress;
  std::function<void(const std::string&)> note;
  // Details for those who ask (the tool's --verbose): the search index's parameters.
  std::function<void(const std::string&)> detail;
  // A distributed run (motifmine-mpi, docs/design/distributed.md): every rank calls BuildTrellis
  // with the group. The ranks share the work of the features, the LSH index and the columns
  // (distributed_columns.h); rank 0 alone reads and writes trellis_path, and its report is the
  // one a single process gives (the others' is partial). null: one process.
  RankGroup* ranks = nullptr;
};

// What an incremental update did (trellis_update.h), for the reindex manifest.
struct TrellisUpdateCounts {
  uint64_t old_columns = 0;
  uint64_t new_columns = 0;
  uint64_t changed_columns = 0;  // old columns that gained a new neighbour
  uint64_t copied_blocks = 0;
  uint64_t rewritten_blocks = 0;
};

struct TrellisReport {
  std::string trellis_path;
  bool reused = false;               // an existing finished trellis had the same parameters
  uint64_t resumed_from_column = 0;  // > 0 when an interrupted build was continued
  TrellisParams params;              // eps, mu, sigma, k_max, exclusion, ...
  std::string eps_how;               // how eps was chosen, one line (EpsilonEstimate::how)
  double paper_eps = 0;              // mu - 2 sigma of the sample, whatever the rule
  TrellisSearchMode search = TrellisSearchMode::kLsh;  // the search used: kLsh or kExact
  // With LSH: the options as used, hashes_per_table and bucket_width resolved from the data
  // (LshSearch::options()); also when the trellis is reused. Passing them explicitly builds the
  // same hash family again (an incremental update does).
  LshOptions lsh_resolved;
  uint64_t columns = 0;
  uint64_t neighbours = 0;            // entries in the trellis
  double mean_k = 0;                  // achieved mean neighbours per column (after the k_max cap)
  uint64_t capped_columns = 0;        // columns that had more than k_max within eps
  uint64_t distance_evaluations = 0;  // of the columns built in this run
  double features_seconds = 0;
  double eps_seconds = 0;
  double index_seconds = 0;
  double search_seconds = 0;      // the column search and the writes (overlapped)
  double write_seconds = 0;       // compressing and writing (fsync) blocks, on the writer thread
  double write_wait_seconds = 0;  // time the search waited for the writer
  uint64_t feature_bytes = 0;
  // A distributed run, on rank 0: its time waiting for the other ranks' blocks, the bytes each
  // rank sent during the build and its time searching (index = rank).
  double receive_wait_seconds = 0;
  std::vector<uint64_t> rank_bytes_sent;
  std::vector<double> rank_search_seconds;  // each rank's time searching its blocks
  bool updated = false;                     // made by an incremental update, not a build
  TrellisUpdateCounts update;               // when updated
};

// The trellis file's weights_hash of per-joint distance weights (XXH3-64 of the floats).
uint64_t WeightsHash(const std::vector<float>& weights);

// "<archive without .mfs>.mtr": where `motifmine trellis` writes an archive's trellis.
std::string DefaultTrellisPath(const std::string& archive_path);

// Whether `path` is a finished trellis of exactly the archive version `archive` reads.
bool IsTrellisOfArchive(const std::string& path, const FrameFileReader& archive);

// Builds (or reuses, or resumes) the trellis of the archive version `archive` reads at
// `trellis_path`. InvalidOption for an impossible option (naming it: "kmax", "eps", "search");
// NotSupported for 2^32 frames or more; the errors of the reader, the weights file, the search
// and the writer pass through.
Result<TrellisReport> BuildTrellis(const FrameFileReader& archive, const std::string& trellis_path,
                                   const TrellisOptions& options);
// The same for the archive at `archive_path` (options.archive_version), opened here.
Result<TrellisReport> BuildTrellis(const std::string& archive_path, const std::string& trellis_path,
                                   const TrellisOptions& options);

}  // namespace motif
