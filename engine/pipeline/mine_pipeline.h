// MinePipeline: the one place that puts the mining stages together (docs/design/algorithm.md):
// the archive (imported takes, an archive given, or a built-in synthetic one with planted motifs),
// the matching trellis, the paths, their clustering into motifs, the planted-motif score of a
// synthetic archive and the report, each written into one output folder.
//
// Resumable and incremental by stage: the trellis and the paths record the archive identity and
// their parameters and are reused when they match (an interrupted trellis resumes after its last
// block); clustering is reused when OUT/mine_state.json says it ran on the same paths with the same
// options; the synthetic archive when its truth has the same options; an import skips takes
// already in the archive. A run killed at any point and started again gives the same motifs.json;
// it first removes the temporary files a dead run left in OUT; last, it writes OUT/run.json (the
// timings, peak memory and parameters, for `motifmine report`: run_record.h). One run at a time per
// folder: OUT/.motifmine.lock (flock) is held for the whole run; a second run fails at once with
// Busy. Every stage reads the archive version opened first, whatever an import appends meanwhile.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/file_lock.h"
#include "common/rank_group.h"
#include "common/status.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/grow/paths_builder.h"
#include "engine/report/report_html.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/trellis/trellis_builder.h"

namespace motif {

// The defaults of a mining run, defined here once (the command line's and the library's).
struct MinePipelineOptions {
  std::string out_dir;
  // BVH / ASF+AMC takes and folders (imported into OUT/archive.mfs), one archive (.mfs), or none:
  // a synthetic archive with planted motifs (`synth`) is written to OUT/archive.mfs.
  std::vector<std::string> inputs;
  bool skip_bad = false;          // import: pass over takes that fail, and mine the others
  std::string descriptions_path;  // import: an index of take descriptions (take_descriptions.h)
  SynthOptions synth;             // no inputs; its seed and threads are set from the ones below
  TrellisOptions trellis;
  PathsOptions paths;
  ClusterOptions cluster;
  std::string groups_text = "auto";  // how the motif count was asked for, shown in the report
  uint64_t seed = 1;                 // every random choice (trellis, cluster, synth)
  int threads = 0;                   // 0: all cores
  bool write_report = true;          // OUT/report.html
  uint64_t report_playback_bytes = ReportOptions().playback_bytes;  // its player's data budget
  // (stage, done, total, unit) as the run goes: stages "import", "synth", "trellis features",
  // "trellis eps", "trellis", "grow", "cluster"; not called for a stage that is reused.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total,
                     const std::string& unit)>
      progress;
  std::function<void(const std::string& message)> note;  // remarks that are not errors
  // A distributed run (motifmine-mpi; docs/design/distributed.md): every rank runs the pipeline
  // with the group. Rank 0 does all that one process does; it makes the archive (import,
  // synth) and tells the others which to read; all share the trellis's work; only rank 0 writes
  // in out_dir, grows the paths, clusters and reports. Another rank's Run returns after the
  // trellis with its result's archive and trellis only. null: one process.
  RankGroup* ranks = nullptr;
  // A distributed run: called when this rank fails while the others may be waiting for it (in
  // the trellis); it should end every rank (motifmine-mpi: MPI_Abort) and not return.
  std::function<void(const Status&)> on_shared_failure;
};

MinePipelineOptions DefaultMinePipelineOptions();

struct MineStageTime {
  std::string stage;
  double seconds = 0;
  bool reused = false;
};

struct MinePipelineResult {
  std::string archive_path;
  std::string truth_path;  // the planted motifs of a synthetic archive; empty otherwise
  std::string motifs_path;
  std::string report_path;  // empty without a report
  MotifsDocument document;
  TrellisReport trellis;
  PathsReport paths;
  std::optional<PlantedMotifScore> score;  // against truth_path
  double fps = 0;
  uint64_t frames = 0;
  uint64_t clips = 0;
  std::vector<MineStageTime> times;        // in stage order
  std::vector<std::string> skipped_takes;  // skip_bad: the takes passed over, with the reason
  double total_seconds = 0;
  uint64_t peak_memory_bytes = 0;  // peak resident memory up to the report
};

class MinePipeline {
 public:
  explicit MinePipeline(MinePipelineOptions options);
  // Runs every stage. InvalidArgument for an impossible option (before any work); Busy when
  // another run holds the folder; the stages' errors otherwise, naming the file.
  Result<MinePipelineResult> Run();

 private:
  Status CheckOptions() const;
  // Rank 0 (or one process): the options, the folder and its lock, the archive.
  Status Prepare(ExclusiveFileLock* run_lock);
  // A distributed run: rank 0 tells the others the outcome of Prepare, and which archive (and
  // version) to read.
  Status ShareArchive(const Status& prepared);
  // The ranks other than 0: the archive rank 0 names, then their share of the trellis.
  Result<MinePipelineResult> RunOtherRank();
  // `failed`, after on_shared_failure in a distributed run.
  Status SharedFailure(const Status& failed) const;
  Status MakeArchive();
  Status BuildTrellisStage();
  Status MotifStages();
  Status ScoreStage();
  Status ReportStage();
  Status WriteRunStage();
  std::string ParametersText() const;
  void Progress(const std::string& stage, uint64_t done, uint64_t total, const std::string& unit);

  MinePipelineOptions options_;
  std::unordered_map<std::string, std::string> descriptions_;  // read before anything is made
  MinePipelineResult result_;
  std::unique_ptr<FrameFileReader> archive_;
};

}  // namespace motif
