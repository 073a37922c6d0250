// ProceduralGenerator: makes one clip of the procedural mode as a Take. The background is a
// sequence of segments (segment_seconds_min..max long), each a perturbed copy of a random
// library activity plus its own smooth variation (a SmoothNoise of
// background_variation_degrees on every DOF: cycle-to-cycle and take-to-take variability, so
// the background does not repeat within eps for lambda frames), crossfaded into the next over
// 0.4 to 0.8 s. Planted instances replace the
// background inside their truth range and blend with it over crossfade_frames on both sides;
// an instance plays its motif through its time warp, plus its own smooth noise. All blending is
// done on the body parameters (raw DOF angles, speeds, turn rate) before the joint limits are
// applied, so the output stays smooth and within limits; heading and position are integrated
// from the blended turn rate and speeds, so they are continuous across every boundary and a
// motif's root motion is relative to the heading it starts with.
// Each clip draws from its own seed: clips can be generated independently, in any order.
// Thread-safety: immutable once built; GenerateClip may run on many threads at once.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/synth/activity_library.h"
#include "engine/synth/motif_template.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/synth_plan.h"
#include "formats/motion/take.h"

namespace motif {

class ProceduralGenerator {
 public:
  ProceduralGenerator(const SynthOptions& options, const SynthPlan& plan);

  // The clip's motion, on CmuBodyModel's skeleton, named SynthPlan::ClipName(clip_idx).
  Take GenerateClip(uint64_t clip_idx) const;

 private:
  SynthOptions options_;
  const SynthPlan& plan_;
  ActivityLibrary library_;
  std::vector<MotifTemplate> motifs_;
};

}  // namespace motif
