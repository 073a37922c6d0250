// SynthPlan: everything about a synthetic archive that is decided before any frame is made: the
// clip layout (lengths drawn uniformly from the clip length range, the last clip taking the
// remainder), the motifs' lengths and instance counts, each instance's time warp (uniform, or a
// smooth monotone non-uniform map with the same mean rate) and noise seed, and where every
// instance sits: in one clip, never across a boundary, with its blend-in and blend-out ramps
// (crossfade_frames each, outside the truth range) inside the clip and at least gap_frames of
// untouched background between neighbouring instances. The plan is O(clips + instances) in
// memory and placement costs O(instances * log(clips)); nothing grows with the frame count.
// The blend helpers below are shared by the procedural and re-sequencing generators.
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif {

struct PlannedInstance {
  PlantedInstance truth;
  uint64_t clip_idx = 0;
  uint64_t motif_frames = 0;  // the motif's own length (at warp 1)
  double warp_c1 = 0;         // non-uniform time map coefficients (0 for a uniform warp)
  double warp_c2 = 0;
  uint64_t noise_seed = 0;

  uint64_t frames() const { return truth.end - truth.start; }
  // The motif time (in motif frames, 0 .. motif_frames - 1 inside the instance) of instance
  // frame `offset` (0 = the instance's first frame). Outside [0, frames()) the map continues
  // linearly with its end slope, for the blend ramps.
  double MotifTime(double offset) const;
};

// Smooth 0 -> 1 step with zero first and second derivatives at both ends, for x in [0, 1].
inline double SmootherStep(double x) {
  x = x < 0 ? 0 : (x > 1 ? 1 : x);
  return x * x * x * (x * (6 * x - 15) + 10);
}

// The weight of a planted instance at instance frame `offset` (0 = its first frame): 1 inside
// [0, frames), ramping down to 0 over `crossfade` frames on both sides.
inline double InstanceBlendWeight(int64_t offset, int64_t frames, int64_t crossfade) {
  if (offset >= 0 && offset < frames) return 1.0;
  const double ramp = static_cast<double>(crossfade + 1);
  if (offset < 0) return SmootherStep(static_cast<double>(offset + crossfade + 1) / ramp);
  return SmootherStep(static_cast<double>(frames + crossfade - offset) / ramp);
}

// Checks the options that do not depend on the random draws; InvalidArgument naming the option.
Status ValidateSynthOptions(const SynthOptions& options);

class SynthPlan {
 public:
  // Draws the plan from options.seed. InvalidArgument (naming the option) when the planted
  // instances, with their blends and gaps, would take more than half of the frames, or cannot
  // be placed in the clips (instances longer than the clips).
  static Result<SynthPlan> Create(const SynthOptions& options);

  uint64_t crossfade_frames() const { return crossfade_frames_; }
  uint64_t gap_frames() const { return gap_frames_; }
  const std::vector<uint64_t>& clip_frames() const { return clip_frames_; }
  uint64_t clip_count() const { return clip_frames_.size(); }
  const std::vector<uint64_t>& motif_frames() const { return motif_frames_; }
  // Sorted by clip, then start.
  const std::vector<PlannedInstance>& instances() const { return instances_; }
  const std::vector<PlantedInstance>& truth() const { return truth_; }
  // The instances of clip `clip_idx`: instances()[first .. first + count).
  void ClipInstances(uint64_t clip_idx, size_t* first, size_t* count) const;

  static std::string ClipName(uint64_t clip_idx);

 private:
  uint64_t crossfade_frames_ = 0;
  uint64_t gap_frames_ = 0;
  std::vector<uint64_t> clip_frames_;
  std::vector<uint64_t> motif_frames_;
  std::vector<PlannedInstance> instances_;
  std::vector<PlantedInstance> truth_;
  std::vector<uint64_t> clip_first_instance_;  // clip_count() + 1 entries
};

}  // namespace motif
