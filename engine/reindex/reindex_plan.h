// ReindexPlan: how `motifmine reindex` makes the next version of its output, worked out from the
// manifest of the current one (docs/guide.md, "motifmine reindex"):
//   * the run's options: the recorded ones (the manifest's params, resolved: ε, the exclusion, λ
//     in frames, the LSH family as drawn), with those given on the command line in their place;
//     the first run's are `motifmine mine`'s defaults and those given;
//   * the kind of build: "full" at the first run, when a parameter of the trellis changes or
//     when the archive does not extend the version the manifest names; "incremental" when takes
//     were appended (the trellis updated from the previous one); "regrow" when only the grower's
//     or the clustering's parameters changed (the same trellis); none when nothing changed;
//   * the pipeline's stage plan for that kind (stage_plan.h).
// The pipeline then runs it; the result's resolved parameters become the next manifest's
// (RecordedParams).
// Thread-safety: pure functions.
#pragma once

#include <set>
#include <string>

#include "common/status.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/pipeline/stage_plan.h"
#include "engine/reindex/reindex_manifest.h"
#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/options.h"

namespace motif {

struct ReindexPlan {
  std::string kind;                // "full", "incremental", "regrow", or "" (up to date)
  std::string why;                 // for a full build after the first
  motifmine::MineOptions options;  // the run's (ε 0: estimated by the rule)
  bool eps_given = false;          // an explicit ε (> 0) on the command line
  StagePlan stages;
};

// The next version's plan. `given`: the option-table names the command line gave, whose values
// are in `options` (the others' values there are ignored after the first run, but for the
// run's own: threads, the report, skip-bad). `archive` is the archive as imported now;
// `current` the manifest (null at the first run); `out_dir` the output folder.
ReindexPlan PlanNextVersion(const motifmine::MineOptions& options,
                            const std::set<std::string>& given, const ReindexManifest* current,
                            const FrameFileReader& archive, const std::string& archive_path,
                            const std::string& out_dir);

// The parameters the new manifest records: the plan's, with what the run resolved (ε and how it
// was chosen, the exclusion, the search and its LSH family, the weights' hash).
MiningParams RecordedParams(const ReindexPlan& plan, const ReindexManifest* current,
                            const MinePipelineResult& result, double fps);

// The recorded parameters as a run's options (the run-only ones from `base`).
motifmine::MineOptions RecordedOptions(const MiningParams& params,
                                       const motifmine::MineOptions& base);

}  // namespace motif
