// TakeResequencer: makes one clip of the re-sequencing mode as a Take, from real source takes
// (one skeleton family, already at the archive's rate). The background is a chain of random
// pieces of the sources (segment_seconds_min..max long, played at a uniform speed factor in
// source_warp_min..max, with small smooth rotation noise), each crossfaded into the next with
// slerp. Every motif is a piece of a source take, chosen once; the background never samples
// those pieces (nor a margin around them), so the motif's instances are its only exact repeats,
// and no piece contains a capture glitch (a joint turning more than 60 degrees in one frame,
// as in some converted CMU takes) when it can be avoided.
// Instances are planted as in the procedural mode: time-warped, noisy, blended in and out over
// crossfade frames outside the truth range.
// Root motion is carried as per-frame increments (heading change, displacement in the heading
// frame) plus height, which are blended and integrated, so heading and position are continuous
// at every segment and instance boundary and each piece moves relative to where it starts.
// A clip uses the bone offsets of the source its first segment comes from.
// Thread-safety: immutable once built; GenerateClip may run on many threads at once.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "common/status.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/synth_plan.h"
#include "engine/synth/synth_random.h"
#include "formats/motion/take.h"

namespace motif {

class TakeResequencer {
 public:
  // InvalidArgument when `sources` is empty, mixes skeletons, is at another rate than
  // options.fps, or is too short for the segments or the plan's motifs.
  static Result<std::unique_ptr<TakeResequencer>> Create(const SynthOptions& options,
                                                         std::vector<Take> sources,
                                                         const SynthPlan& plan);

  // The archive's skeleton: the first source's.
  const Skeleton& skeleton() const { return sources_[0].skeleton; }
  Take GenerateClip(uint64_t clip_idx) const;

 private:
  struct MotifSource {
    size_t take_idx = 0;
    double start = 0;  // source frame of the motif's first frame
  };
  struct FrameMotion;
  struct SourceSegment;
  class RotationNoise;
  class SegmentTrack;   // a clip's background segments, blended one into the next
  class InstanceTrack;  // a clip's planted instances, blended over the background

  TakeResequencer(const SynthOptions& options, std::vector<Take> sources, const SynthPlan& plan);

  void SampleRoot(size_t take_idx, double source_frame, double* heading,
                  Eigen::Vector3d* position) const;
  // The motion at fractional source frame `source_frame`, with the root increments from
  // `previous_frame`.
  void SampleMotion(size_t take_idx, double source_frame, double previous_frame,
                    FrameMotion* motion) const;
  // A random background segment starting at clip frame `start`, whose first `overlap` frames
  // are the previous segment's crossfade.
  SourceSegment DrawSegment(int64_t start, int64_t overlap, SynthRandom* random) const;
  // Clip `clip_idx` named and sized, in the skeleton of take `skeleton_take_idx`, its frames
  // still to fill.
  Take EmptyClipTake(uint64_t clip_idx, size_t skeleton_take_idx) const;
  // Where motif `motif_idx` comes from: a random start in a take drawn by its room for the motif
  // and `margin` frames either side, clear of what is reserved so far (a few draws), or the
  // longest take when none has room.
  MotifSource DrawMotifSource(size_t motif_idx, double margin) const;
  // Whether source frames [first, last] of take `take_idx` touch a motif's piece or a glitch.
  bool OverlapsReserved(size_t take_idx, double first, double last) const;
  // The source frame where the reserved range after `first` begins (the take's last frame if
  // none), or -1 if `first` is itself reserved.
  double ClearUntil(size_t take_idx, double first) const;

  SynthOptions options_;
  const SynthPlan& plan_;
  std::vector<Take> sources_;
  std::vector<std::vector<double>> headings_;  // per source frame, unwrapped
  std::vector<uint64_t> cumulative_frames_;    // prefix sums, for drawing takes by length
  std::vector<MotifSource> motif_sources_;
  // Per take, sorted: source frame ranges no background piece may use (motif pieces with their
  // margins, capture glitches).
  std::vector<std::vector<std::pair<double, double>>> reserved_;
};

}  // namespace motif
