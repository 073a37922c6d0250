// StagePlan: what each stage of a run does (docs/design/algorithm.md, "A run"). `motifmine mine`
// runs FullPlan(); `motifmine reindex` works out an incremental plan from its manifest
// (engine/reindex/reindex_plan.h); `trellis`, `grow`, `cluster` and `graph` run the plan of the
// stages they are about. Whatever the plan, MinePipeline runs the stages, in order:
//
//   archive -> trellis -> grow -> cluster -> score -> report -> run record
//
// A stage asked to build first looks for its output already made from the same inputs with the
// same parameters and reuses it (or resumes it, for an interrupted trellis): so "build" on an
// unchanged folder costs nothing.
#pragma once

#include <string>

namespace motif {

// Where the archive comes from.
enum class ArchiveStep {
  kFromInputs,  // the run's inputs: takes imported into files.archive, an archive (.mfs) given,
                // or none (the built-in synthetic archive with planted motifs)
  kGiven,       // files.archive as it is, at the version the session names (a run that made it)
};

enum class TrellisStep {
  kBuild,   // FullTrellisBuild (reused when finished with the same parameters)
  kUpdate,  // IncrementalTrellisUpdate from previous_trellis and previous_cache
  kLink,    // files.trellis as it is (previous_trellis hard-linked or copied there first, when
            // given and files.trellis does not exist)
  kAnyOfArchive,  // a finished trellis of this archive version at files.trellis is used
                  // whatever its parameters (graph: eps is the user's choice); else kBuild
  kSkip,
};

struct StagePlan {
  ArchiveStep archive = ArchiveStep::kFromInputs;
  TrellisStep trellis = TrellisStep::kBuild;
  std::string previous_trellis;    // kUpdate, kLink
  std::string previous_cache;      // kUpdate: its search cache (missing: rebuilt, with a note)
  bool save_search_cache = false;  // files.search_cache written for the next update
  bool grow = true;
  bool cluster = true;
  bool score = true;       // a synthetic archive's planted motifs
  bool report = true;      // also off when the options say no report
  bool run_record = true;  // files.dir/run.json, for `motifmine report`
  // The folder's lock (files.dir/.motifmine.lock) and the removal of a dead run's temporary
  // files; off when the caller holds the lock of the folder above (reindex).
  bool lock_folder = true;
};

// `motifmine mine`: every stage.
inline StagePlan FullPlan() { return StagePlan(); }

}  // namespace motif
