// motifmine::Mine (include/motifmine/mine.h): the public options translated into the pipeline's,
// the pipeline run, and its result copied into the public types.
#include <utility>

#include "engine/api/public_status.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/pipeline/mine_pipeline.h"
#include "motifmine/mine.h"

namespace motifmine {

namespace {

// The pipeline's options for `options`; InvalidArgument for an unknown ε rule.
motif::Result<motif::MinePipelineOptions> PipelineOptions(const std::vector<std::string>& inputs,
                                                          const MineOptions& options) {
  motif::MinePipelineOptions pipeline = motif::DefaultMinePipelineOptions();
  pipeline.out_dir = options.out_dir;
  pipeline.inputs = inputs;
  pipeline.trellis.eps = static_cast<float>(options.eps);
  MOTIF_ASSIGN_OR_RETURN(pipeline.trellis.eps_rule, motif::ParseEpsilonRule(options.eps_rule));
  if (!(options.eps_angle_degrees > 0 && options.eps_angle_degrees <= 180)) {
    return motif::Status::InvalidArgument("eps_angle_degrees must be in (0, 180]");
  }
  pipeline.trellis.eps_joint_angle_degrees = options.eps_angle_degrees;
  pipeline.trellis.k_max = options.k_max;
  pipeline.paths.branch = options.branch;
  pipeline.paths.min_length_seconds = options.min_length_seconds;
  pipeline.paths.min_length_frames = options.min_length_frames;
  if (options.min_length_frames == 0 && !(options.min_length_seconds > 0)) {
    return motif::Status::InvalidArgument("min_length_seconds must be > 0");
  }
  pipeline.cluster.cut.groups = options.groups;
  pipeline.groups_text = options.groups == 0 ? "auto" : std::to_string(options.groups);
  pipeline.seed = options.seed;
  pipeline.threads = options.threads;
  if (options.threads < 0) return motif::Status::InvalidArgument("threads must be >= 0");
  pipeline.skip_bad = options.skip_bad;
  pipeline.write_report = options.write_report;
  pipeline.synth.frames = options.synth_frames;
  pipeline.synth.motifs = options.synth_motifs;
  if (options.progress) {
    pipeline.progress = [progress = options.progress](const std::string& stage, uint64_t done,
                                                      uint64_t total, const std::string&) {
      progress(stage, done, total);
    };
  }
  return pipeline;
}

void CopyResult(const motif::MinePipelineResult& run, MineResult* result) {
  *result = MineResult();
  for (size_t rank = 0; rank < run.document.motifs.size(); ++rank) {
    Motif motif;
    motif.id = static_cast<uint32_t>(rank);
    for (const motif::MotifsJsonInstance& instance : run.document.motifs[rank].instances) {
      motif.instances.push_back({instance.clip, instance.start, instance.end});
    }
    result->motifs.push_back(std::move(motif));
  }
  for (const motif::MotifsJsonClip& clip : run.document.clips) {
    result->clips.push_back({clip.name, clip.source, clip.first_frame, clip.frames, clip.fps});
  }
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

MineOptions::MineOptions() {
  const motif::MinePipelineOptions defaults = motif::DefaultMinePipelineOptions();
  eps = defaults.trellis.eps;
  eps_rule = defaults.trellis.eps_rule == motif::EpsilonRule::kPaper ? "paper" : "joint-angle";
  eps_angle_degrees = defaults.trellis.eps_joint_angle_degrees;
  k_max = defaults.trellis.k_max;
  branch = defaults.paths.branch;
  min_length_seconds = defaults.paths.min_length_seconds;
  min_length_frames = defaults.paths.min_length_frames;
  groups = defaults.cluster.cut.groups;
  seed = defaults.seed;
  threads = defaults.threads;
  skip_bad = defaults.skip_bad;
  write_report = defaults.write_report;
  synth_frames = defaults.synth.frames;
  synth_motifs = defaults.synth.motifs;
}

Status Mine(const std::vector<std::string>& inputs, const MineOptions& options,
            MineResult* result) {
  if (result == nullptr) return {Status::Code::kInvalidArgument, "no MineResult to fill"};
  motif::Result<motif::MinePipelineOptions> pipeline = PipelineOptions(inputs, options);
  if (!pipeline.ok()) return motif::ToPublicStatus(pipeline.status());
  motif::Result<motif::MinePipelineResult> run = motif::MinePipeline(std::move(*pipeline)).Run();
  if (!run.ok()) return motif::ToPublicStatus(run.status());
  CopyResult(*run, result);
  return {};
}

}  // namespace motifmine
