#include "engine/synth/procedural_generator.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "engine/synth/cmu_body_model.h"
#include "engine/synth/synth_random.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

// Length units per second (1.7 m/s): the root's vertical speed limit.
constexpr double kMaxVerticalSpeed = 30.0;

// The background of one clip: segments of perturbed library activities, generated lazily as
// the frames advance, each crossfaded into the next.
class BackgroundTrack {
 public:
  BackgroundTrack(const ActivityLibrary& library, const SynthOptions& options, SynthRandom* random)
      : library_(library), options_(options), random_(random) {
    current_ = Draw(0, 0);
    next_ = Draw(current_.start + current_.frames - current_.crossfade, current_.crossfade);
    scratch_.resize(CmuBodyModel::Get().param_count());
  }

  void Evaluate(int64_t frame, double* params) {
    while (frame >= current_.start + current_.frames) {
      current_ = std::move(next_);
      next_ = Draw(current_.start + current_.frames - current_.crossfade, current_.crossfade);
    }
    current_.Evaluate(frame, options_.fps, params);
    if (frame < next_.start) return;
    next_.Evaluate(frame, options_.fps, scratch_.data());
    const double weight = SmootherStep(static_cast<double>(frame - next_.start + 1) /
                                       static_cast<double>(current_.crossfade + 1));
    for (size_t param = 0; param < scratch_.size(); ++param) {
      params[param] += weight * (scratch_[param] - params[param]);
    }
  }

 private:
  struct Segment {
    ActivitySpec spec;
    int64_t start = 0;
    int64_t frames = 0;     // including the crossfade into the next segment
    int64_t crossfade = 0;  // frames shared with the next segment
    double time_offset_s = 0;
    std::shared_ptr<const SmoothNoise> variation;  // this segment's own variation, or null

    void Evaluate(int64_t frame, double fps, double* params) const {
      const double time_s = static_cast<double>(frame - start) / fps + time_offset_s;
      spec.Evaluate(time_s, params);
      if (variation) variation->Add(time_s, params);
    }
  };

  // A segment starting at `start`, whose first `overlap` frames are the previous segment's
  // crossfade: it lasts beyond that overlap and its own, so at most two segments ever overlap.
  Segment Draw(int64_t start, int64_t overlap) {
    Segment segment;
    const size_t activity_idx = random_->UniformInt(0, library_.size() - 1);
    segment.spec = library_.Perturb(activity_idx, random_);
    segment.start = start;
    const double fps = options_.fps;
    segment.frames = std::max<int64_t>(
        2, std::llround(
               random_->Uniform(options_.segment_seconds_min, options_.segment_seconds_max) * fps));
    segment.crossfade =
        std::clamp<int64_t>(std::llround(random_->Uniform(0.4, 0.8) * fps), 1, segment.frames / 2);
    segment.frames = std::max(segment.frames, overlap + segment.crossfade + 1);
    segment.time_offset_s = random_->Uniform(0, 1.0 / segment.spec.frequency_hz);
    if (options_.background_variation_degrees > 0) {
      segment.variation = std::make_shared<const SmoothNoise>(
          random_->Next(), CmuBodyModel::Get().dof_count(), options_.background_variation_degrees);
    }
    return segment;
  }

  const ActivityLibrary& library_;
  const SynthOptions& options_;
  SynthRandom* random_;
  Segment current_;
  Segment next_;
  std::vector<double> scratch_;
};

}  // namespace

ProceduralGenerator::ProceduralGenerator(const SynthOptions& options, const SynthPlan& plan)
    : options_(options),
      plan_(plan),
      library_(ActivityLibrary::Create(DeriveSeed(options.seed, SeedStream::kActivityLibrary, 0),
                                       options.activities)) {
  for (size_t motif_idx = 0; motif_idx < plan.motif_frames().size(); ++motif_idx) {
    motifs_.push_back(MotifTemplate::Create(
        library_, DeriveSeed(options.seed, SeedStream::kMotifTemplate, motif_idx),
        plan.motif_frames()[motif_idx], options.fps));
  }
}

Take ProceduralGenerator::GenerateClip(uint64_t clip_idx) const {
  const CmuBodyModel& body = CmuBodyModel::Get();
  const double fps = options_.fps;
  const size_t frame_count = plan_.clip_frames()[clip_idx];
  const size_t joint_count = body.joint_count();
  Take take;
  take.name = SynthPlan::ClipName(clip_idx);
  take.source_path = "synthetic";
  take.fps = fps;
  take.source_fps = fps;
  take.meters_per_unit = CmuBodyModel::kMetersPerUnit;
  take.skeleton = body.skeleton();
  take.root_positions.resize(frame_count);
  take.rotations.resize(frame_count * joint_count);

  SynthRandom random(DeriveSeed(options_.seed, SeedStream::kClip, clip_idx));
  double heading = random.Uniform(-kPi, kPi);
  Eigen::Vector3d position(random.Uniform(-100, 100), 0, random.Uniform(-100, 100));
  BackgroundTrack background(library_, options_, &random);

  size_t first_instance = 0;
  size_t instance_count = 0;
  plan_.ClipInstances(clip_idx, &first_instance, &instance_count);
  const int64_t crossfade = static_cast<int64_t>(plan_.crossfade_frames());
  size_t cursor = 0;  // the next instance whose blend has not ended
  std::unique_ptr<SmoothNoise> noise;
  size_t noise_owner = SIZE_MAX;

  std::vector<double> params(body.param_count());
  std::vector<double> motif_params(body.param_count());
  const double deg = kPi / 180.0;
  const double max_rise = kMaxVerticalSpeed / fps;
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const int64_t frame = static_cast<int64_t>(frame_idx);
    background.Evaluate(frame, params.data());
    while (cursor < instance_count) {
      const PlannedInstance& instance = plan_.instances()[first_instance + cursor];
      if (frame < static_cast<int64_t>(instance.truth.end) + crossfade) break;
      ++cursor;
    }
    if (cursor < instance_count) {
      const PlannedInstance& instance = plan_.instances()[first_instance + cursor];
      const int64_t offset = frame - static_cast<int64_t>(instance.truth.start);
      if (offset >= -crossfade) {
        if (noise_owner != cursor) {
          noise = std::make_unique<SmoothNoise>(instance.noise_seed, body.dof_count(),
                                                options_.noise_degrees);
          noise_owner = cursor;
        }
        const double time = static_cast<double>(offset);
        motifs_[instance.truth.motif].Evaluate(instance.MotifTime(time), motif_params.data());
        // A slowed-down motif covers the same path more slowly: root speeds and turn rate scale
        // with the local rate of the time map (motif frames per frame).
        const double rate = instance.MotifTime(time + 0.5) - instance.MotifTime(time - 0.5);
        motif_params[body.heading_rate_param()] *= rate;
        motif_params[body.forward_speed_param()] *= rate;
        motif_params[body.side_speed_param()] *= rate;
        noise->Add(time / fps, motif_params.data());
        const double weight =
            InstanceBlendWeight(offset, static_cast<int64_t>(instance.frames()), crossfade);
        for (size_t param = 0; param < params.size(); ++param) {
          params[param] += weight * (motif_params[param] - params[param]);
        }
      }
    }
    Eigen::Quaterniond* rotations = &take.rotations[frame_idx * joint_count];
    body.Pose(params.data(), rotations);
    if (frame_idx > 0) {
      heading += params[body.heading_rate_param()] * deg / fps;
      const Eigen::Vector3d local(params[body.side_speed_param()], 0,
                                  params[body.forward_speed_param()]);
      position += AxisRotation(Axis::kY, heading) * local / fps;
    }
    // The grounded height follows whichever foot is lowest, which can switch quickly (a swing
    // foot passing under the stance foot): its vertical speed is softly limited, as a body's is.
    const double target =
        body.GroundedRootHeight(rotations) + std::max(0.0, params[body.jump_param()]);
    position.y() = frame_idx == 0
                       ? target
                       : position.y() + max_rise * std::tanh((target - position.y()) / max_rise);
    take.root_positions[frame_idx] = position;
    rotations[0] = AxisRotation(Axis::kY, heading) * rotations[0];
  }
  return take;
}

}  // namespace motif
