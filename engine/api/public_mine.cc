// motifmine::Mine (include/motifmine/mine.h): the pipeline run on the caller's MineOptions (the
// engine's own options type), and its result copied into the public types.
#include <utility>

#include "engine/api/public_motifs.h"
#include "engine/api/public_status.h"
#include "engine/pipeline/mine_pipeline.h"
#include "motifmine/mine.h"

namespace motifmine {

namespace {

void CopyResult(const motif::MinePipelineResult& run, MineResult* result) {
  *result = MineResult();
  motif::CopyMotifsDocument(run.document, result);
  result->parameters = {run.trellis.params.eps,      run.trellis.eps_how,
                        run.trellis.params.k_max,    run.paths.params.branch,
                        run.paths.params.min_length, run.trellis.params.seed};
  for (const motif::MineStageTime& time : run.times) {
    result->timings.push_back({time.stage, time.seconds, time.reused});
  }
  result->archive_path = run.archive_path;
  result->motifs_path = run.motifs_path;
  result->skipped_takes = run.skipped_takes;
}

}  // namespace

Status Mine(const std::vector<std::string>& inputs, const MineOptions& options,
            MineResult* result) {
  if (result == nullptr) return {Status::Code::kInvalidArgument, "no MineResult to fill"};
  motif::RunHooks hooks;
  if (options.progress) {
    hooks.progress = [progress = options.progress](const std::string& stage, uint64_t done,
                                                   uint64_t total, const std::string&) {
      progress(stage, done, total);
    };
  }
  motif::Result<motif::MinePipelineResult> run = motif::RunMine(options, inputs, std::move(hooks));
  if (!run.ok()) return motif::ToPublicStatus(run.status());
  CopyResult(*run, result);
  return {};
}

}  // namespace motifmine
