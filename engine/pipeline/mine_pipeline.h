// MinePipeline: the one place that puts the mining stages together (docs/design/algorithm.md,
// "A run"). A run is a plan (stage_plan.h: what each stage does) over a session (run_session.h:
// the options, the files, the archive and the trellis opened once, the ranks, the progress).
// `motifmine mine`, `reindex`, `trellis`, `grow`, `cluster`, `graph`, motifmine-mpi, the library
// (motifmine::Mine), the Python module, the benchmarks and the study programs all run it; none
// of them strings the stages together again.
//
// Resumable and incremental by stage: the trellis and the paths record the archive identity and
// their parameters and are reused when they match (an interrupted trellis resumes after its last
// block); clustering is reused when its state file says it ran on the same paths with the same
// options; the synthetic archive when its truth has the same options; an import skips takes
// already in the archive. A run killed at any point and started again gives the same motifs.json;
// it first removes the temporary files a dead run left in its folder; last, it writes run.json
// (the timings, peak memory and parameters, for `motifmine report`: run_record.h). One run at a
// time per folder: DIR/.motifmine.lock (flock) is held for the whole run; a second run fails at
// once with Busy. Every stage reads the archive version opened first, whatever an import appends
// meanwhile.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/file_lock.h"
#include "common/status.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/grow/paths_builder.h"
#include "engine/pipeline/run_session.h"
#include "engine/pipeline/stage_plan.h"
#include "engine/trellis/trellis_builder.h"
#include "motifmine/options.h"

namespace motif {

struct MineStageTime {
  std::string stage;
  double seconds = 0;
  bool reused = false;
};

struct MinePipelineResult {
  std::string archive_path;
  std::string truth_path;  // the planted motifs of a synthetic archive; empty otherwise
  std::string motifs_path;
  std::string instances_path;  // empty when not written
  std::string report_path;     // empty without a report
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
  MinePipeline(RunSession* session, StagePlan plan = FullPlan());
  // Runs the plan. InvalidOption for an impossible option (before any work); Busy when another
  // run holds the folder; the stages' errors otherwise, naming the file. A distributed run's
  // ranks other than 0 return after the trellis, with the archive and the trellis only.
  Result<MinePipelineResult> Run();

 private:
  // Rank 0 (or one process): the options, the folder and its lock, the archive.
  Status Prepare(ExclusiveFileLock* run_lock);
  Status LockFolder(ExclusiveFileLock* run_lock);
  // A distributed run: rank 0 tells the others the outcome of Prepare, and which archive (and
  // version) to read.
  Status ShareArchive(const Status& prepared);
  Result<MinePipelineResult> RunOtherRank();
  Status SharedFailure(const Status& failed) const;
  Status MakeArchive();
  Status MakeSyntheticArchive();
  Status ImportInputs();
  Status ArchiveOpened();  // the stages' options resolved against it
  Status TrellisStage();
  Status LinkPreviousTrellis() const;
  Status GrowStage();
  Status ClusterStage();
  Status ScoreStage();
  Status ReportStage();
  Status WriteRunStage();
  std::string ParametersText() const;
  void TrellisProgress(const std::string& stage, uint64_t done, uint64_t total) const;

  RunSession* session_;
  StagePlan plan_;
  std::unordered_map<std::string, std::string> descriptions_;  // read before anything is made
  TrellisOptions trellis_options_;                             // resolved once the archive is open
  PathsOptions paths_options_;
  ClusterOptions cluster_options_;
  std::unique_ptr<StreamedPaths> streamed_paths_;  // fed by an incremental update
  MinePipelineResult result_;
};

// `motifmine mine`: the full plan over options.out_dir's files (MineFolderFiles).
Result<MinePipelineResult> RunMine(const motifmine::MineOptions& options,
                                   const std::vector<std::string>& inputs, RunHooks hooks = {});

}  // namespace motif
