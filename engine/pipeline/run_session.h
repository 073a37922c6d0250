// RunSession: what one mining run opened once and its stages share (docs/design/algorithm.md,
// "A run"): the options as given (MineOptions, the option table's type), the inputs, the files of
// the output folder, the archive version every stage reads (opened once: takes imported during
// the run do not change what it mines), the trellis (opened once after its stage, read by the
// grower and the clustering), the ranks of a distributed run, and where progress and notes go.
// Thread-safety: one run, one thread; the readers it holds are safe for concurrent const use.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/rank_group.h"
#include "common/status.h"
#include "common/writable_file.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "motifmine/options.h"

namespace motif {

// The files of a run, each a path; empty: not written.
struct RunFiles {
  std::string dir;      // the output folder (its lock, its temporary files)
  std::string archive;  // as motifs.json records it
  std::string truth;    // a synthetic archive's planted motifs; empty otherwise
  std::string trellis;
  std::string search_cache;  // the next incremental update's (StagePlan::save_search_cache)
  std::string paths;
  std::string motifs;
  std::string instances;      // instances.csv beside motifs.json; empty: not written
  std::string cluster_state;  // the clustering's reuse key
  std::string report;
  std::string run_record;
};

// The layout of `motifmine mine --out DIR`: DIR/archive.mfs, DIR/trellis.mtr, ...
RunFiles MineFolderFiles(const std::string& dir);

struct RunHooks {
  // (stage, done, total, unit) as the run goes: stages "import", "synth", "trellis features",
  // "trellis eps", "trellis index", "trellis", "grow", "cluster" (an incremental update: "trellis
  // thresholds", "trellis new columns", "trellis merge"); not called for a stage that is reused.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total,
                     const std::string& unit)>
      progress;
  std::function<void(const std::string& message)> note;  // remarks that are not errors
  std::function<void(const std::string& message)> detail;  // for --verbose (TrellisOptions)
  // A distributed run (motifmine-mpi; docs/design/distributed.md): every rank runs the pipeline
  // with the group; rank 0 makes the archive, writes in the folder, grows, clusters and reports;
  // the others share the trellis's work. null: one process.
  RankGroup* ranks = nullptr;
  // A distributed run: called when this rank fails while the others may be waiting for it (in
  // the trellis); it should end every rank (motifmine-mpi: MPI_Abort) and not return.
  std::function<void(const Status&)> on_shared_failure;
  FileSystem* file_system = PosixFileSystem();  // the trellis update's and the cache's writes
};

class RunSession {
 public:
  RunSession(motifmine::MineOptions options, std::vector<std::string> inputs, RunFiles files,
             RunHooks hooks = {});

  const motifmine::MineOptions& options() const { return options_; }
  const std::vector<std::string>& inputs() const { return inputs_; }
  const RunFiles& files() const { return files_; }
  RunFiles& mutable_files() { return files_; }
  const RunHooks& hooks() const { return hooks_; }
  RankGroup* ranks() const { return hooks_.ranks; }
  // Rank 0 of a distributed run, or the one process.
  bool root() const { return hooks_.ranks == nullptr || hooks_.ranks->rank() == 0; }

  void Progress(const std::string& stage, uint64_t done, uint64_t total,
                const std::string& unit) const;
  void Note(const std::string& message) const;

  // Opens files().archive at `version` (default: the newest) as the run's archive.
  Status OpenArchive(const FrameFileVersion& version = {});
  // An archive the caller opened already (reindex, which read it to plan the run).
  void SetArchive(std::unique_ptr<FrameFileReader> archive);
  // The same, still the caller's (it must outlive the session).
  void UseArchive(const FrameFileReader* archive) { archive_ = archive; }
  bool has_archive() const { return archive_ != nullptr; }
  const FrameFileReader& archive() const { return *archive_; }

  // Opens files().trellis, once its stage has made it.
  Status OpenTrellis();
  const TrellisFileReader& trellis() const { return *trellis_; }

  // The report's parameter line from the trellis stage's report; empty: the pipeline's own (how
  // the radius was chosen, and the search).
  std::function<std::string(const TrellisReport&)> report_parameters;
  // Stage timings of work done before the pipeline ran (reindex's import), shown first.
  struct EarlierStage {
    std::string stage;
    double seconds = 0;
  };
  std::vector<EarlierStage> earlier_stages;

 private:
  motifmine::MineOptions options_;
  std::vector<std::string> inputs_;
  RunFiles files_;
  RunHooks hooks_;
  std::unique_ptr<FrameFileReader> owned_archive_;
  const FrameFileReader* archive_ = nullptr;
  std::unique_ptr<TrellisFileReader> trellis_;
};

}  // namespace motif
