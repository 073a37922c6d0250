#include "engine/synth/motion_synthesizer.h"

#include <tbb/info.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "common/file_util.h"
#include "engine/synth/cmu_body_model.h"
#include "engine/synth/procedural_generator.h"
#include "engine/synth/synth_plan.h"
#include "engine/synth/take_resequencer.h"

namespace motif {

class MotionSynthesizer::Impl {
 public:
  Impl(const SynthOptions& options, SynthPlan plan) : options_(options), plan_(std::move(plan)) {}

  const SynthOptions& options() const { return options_; }
  const SynthPlan& plan() const { return plan_; }
  const Skeleton& skeleton() const {
    return resequencer_ ? resequencer_->skeleton() : CmuBodyModel::Get().skeleton();
  }

  void UseProcedural() { procedural_ = std::make_unique<ProceduralGenerator>(options_, plan_); }
  Status UseSources(std::vector<Take> sources) {
    MOTIF_ASSIGN_OR_RETURN(resequencer_,
                           TakeResequencer::Create(options_, std::move(sources), plan_));
    return Status::Ok();
  }

  ClipFrames GenerateClip(uint64_t clip_idx) const {
    return TakeToClipFrames(resequencer_ ? resequencer_->GenerateClip(clip_idx)
                                         : procedural_->GenerateClip(clip_idx));
  }

 private:
  SynthOptions options_;
  SynthPlan plan_;  // the generators keep a reference: Impl never moves
  std::unique_ptr<ProceduralGenerator> procedural_;
  std::unique_ptr<TakeResequencer> resequencer_;
};

MotionSynthesizer::MotionSynthesizer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MotionSynthesizer::~MotionSynthesizer() = default;

Result<std::unique_ptr<MotionSynthesizer>> MotionSynthesizer::Create(const SynthOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(SynthPlan plan, SynthPlan::Create(options));
  auto impl = std::make_unique<Impl>(options, std::move(plan));
  impl->UseProcedural();
  return std::unique_ptr<MotionSynthesizer>(new MotionSynthesizer(std::move(impl)));
}

Result<std::unique_ptr<MotionSynthesizer>> MotionSynthesizer::CreateFromTakes(
    const SynthOptions& options, std::vector<Take> sources) {
  MOTIF_ASSIGN_OR_RETURN(SynthPlan plan, SynthPlan::Create(options));
  auto impl = std::make_unique<Impl>(options, std::move(plan));
  MOTIF_RETURN_IF_ERROR(impl->UseSources(std::move(sources)));
  return std::unique_ptr<MotionSynthesizer>(new MotionSynthesizer(std::move(impl)));
}

const Skeleton& MotionSynthesizer::skeleton() const { return impl_->skeleton(); }

const std::vector<PlantedInstance>& MotionSynthesizer::truth() const {
  return impl_->plan().truth();
}

uint64_t MotionSynthesizer::clip_count() const { return impl_->plan().clip_count(); }

Status MotionSynthesizer::Run(const std::function<Status(const ClipFrames&)>& sink) {
  const uint64_t clip_count = impl_->plan().clip_count();
  const int threads = impl_->options().threads > 0 ? static_cast<int>(impl_->options().threads)
                                                   : tbb::info::default_concurrency();
  if (threads <= 1 || clip_count <= 1) {
    for (uint64_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
      MOTIF_RETURN_IF_ERROR(sink(impl_->GenerateClip(clip_idx)));
    }
    return Status::Ok();
  }
  // Clips are generated in parallel (each from its own seed) and handed to the sink in order;
  // at most 2 * threads clips are in flight, so memory stays bounded by a few clips.
  Status status;
  std::atomic<bool> stop(false);
  uint64_t next_clip = 0;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        static_cast<size_t>(2 * threads),
        tbb::make_filter<void, uint64_t>(tbb::filter_mode::serial_in_order,
                                         [&](tbb::flow_control& control) -> uint64_t {
                                           if (next_clip >= clip_count || stop.load()) {
                                             control.stop();
                                             return 0;
                                           }
                                           return next_clip++;
                                         }) &
            tbb::make_filter<uint64_t, std::shared_ptr<ClipFrames>>(
                tbb::filter_mode::parallel,
                [&](uint64_t clip_idx) -> std::shared_ptr<ClipFrames> {
                  if (stop.load()) return nullptr;
                  return std::make_shared<ClipFrames>(impl_->GenerateClip(clip_idx));
                }) &
            tbb::make_filter<std::shared_ptr<ClipFrames>, void>(
                tbb::filter_mode::serial_in_order, [&](std::shared_ptr<ClipFrames> clip) {
                  if (!clip || !status.ok()) return;
                  status = sink(*clip);
                  if (!status.ok()) stop.store(true);
                }));
  });
  return status;
}

Status WriteTruthJson(const std::string& path, const std::string& archive_path, uint64_t frames,
                      const SynthOptions& options, const std::vector<PlantedInstance>& truth) {
  using Json = nlohmann::ordered_json;
  constexpr auto kReplace = Json::error_handler_t::replace;
  // One instance per line: the file stays readable (and diffable) with many instances.
  std::string text = "{\n";
  text += "  \"version\": 1,\n";
  text += "  \"archive\": " + Json(archive_path).dump(-1, ' ', false, kReplace) + ",\n";
  text += "  \"frames\": " + std::to_string(frames) + ",\n";
  text += "  \"seed\": " + std::to_string(options.seed) + ",\n";
  text += "  \"motifs\": " + std::to_string(options.motifs) + ",\n";
  text += "  \"instances\": [";
  for (size_t idx = 0; idx < truth.size(); ++idx) {
    const PlantedInstance& instance = truth[idx];
    Json entry;
    entry["clip"] = instance.clip;
    entry["start"] = instance.start;
    entry["end"] = instance.end;
    entry["motif"] = instance.motif;
    entry["warp"] = instance.warp;
    entry["nonuniform"] = instance.nonuniform;
    text += idx == 0 ? "\n    " : ",\n    ";
    text += entry.dump(-1, ' ', false, kReplace);
  }
  text += truth.empty() ? "]\n" : "\n  ]\n";
  text += "}\n";
  Status status = AtomicWriteFile(path, text);
  return status.ok() ? status : status.WithContext("truth file " + path);
}

}  // namespace motif
