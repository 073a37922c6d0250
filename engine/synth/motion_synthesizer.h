// MotionSynthesizer: synthetic motion archives with planted motifs, the project's ground truth.
// Writes plausible skeletal motion on the canonical CMU skeleton (smooth, joint-limited, built of
// varied activities, each background segment with its own variation so that the planted
// instances are the only long repeats; not white noise), cut into clips, in which `motifs`
// motifs of varied lengths (0.5 to 5 s) are planted several times each with uniform and
// non-uniform time warps (0.7x to 1.4x) and small noise. A second mode re-sequences real takes
// (random segments, warps and noise) into a large archive of realistic neighbour density, with
// motifs cut from the real takes planted the same way.
// Generation streams clip by clip: memory does not grow with the number of frames.
// Same options and seed give the same frames, bit for bit.
// Thread-safety: one thread at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/take.h"

namespace motif {

// The background variation `motifmine synth` uses (degrees): the smallest that kept precision
// >= 0.8 on every planted archive measured (docs/benchmarks_planted.md).
inline constexpr double kRecommendedBackgroundVariation = 12.0;

struct SynthOptions {
  uint64_t frames = 120 * 600;  // total frames in the archive
  uint32_t motifs = 8;          // planted motifs
  uint64_t seed = 1;
  double fps = 120.0;
  double clip_seconds_min = 20;  // clip lengths are drawn uniformly from this range
  double clip_seconds_max = 60;
  double motif_seconds_min = 0.5;
  double motif_seconds_max = 5.0;
  uint32_t instances_min = 3;  // planted instances per motif
  uint32_t instances_max = 6;
  double warp_min = 0.7;
  double warp_max = 1.4;
  double noise_degrees = 1.0;  // std dev of the smooth noise added to each instance
  // Further options (defaults are the intended behaviour):
  double crossfade_seconds = 0.5;   // an instance blends into the background over this, before
                                    // its start and after its end (outside the truth range)
  double gap_seconds = 0.5;         // at least this much untouched background between instances
  uint32_t activities = 16;         // procedural: size of the activity library
  double segment_seconds_min = 1;   // background segments: a perturbed activity (procedural) or
  double segment_seconds_max = 10;  // a piece of a source take (re-sequencing)
  // Procedural: std dev (degrees) of the smooth variation each background segment adds to every
  // DOF (its own realisation per segment, 0.3 to 2 Hz): cycle-to-cycle and take-to-take
  // variability, so the background does not repeat within eps for lambda frames and the planted
  // instances stay the only long repeats (docs/benchmarks_planted.md). `motifmine synth` uses
  // kRecommendedBackgroundVariation; the library default 0 keeps the archives every other
  // stage's tests were calibrated on (their LSH recall and density thresholds assume eps near
  // 1, and the variation raises eps = mu - 2 sigma to about 1.7).
  double background_variation_degrees = 0.0;
  double source_warp_min = 0.8;  // re-sequencing: uniform speed factor of background segments
  double source_warp_max = 1.25;
  // Clips generated in parallel (0: all cores); the output does not depend on it.
  uint32_t threads = 0;
};

struct PlantedInstance {
  std::string clip;    // clip name
  uint64_t start = 0;  // frame within the clip, 0-based
  uint64_t end = 0;    // exclusive
  uint32_t motif = 0;  // planted motif id
  double warp = 1.0;   // mean speed factor (instance length / motif length)
  bool nonuniform = false;
};

class MotionSynthesizer {
 public:
  // Procedural mode. InvalidArgument on impossible options (no frames, motifs that cannot fit,
  // min > max, ...), naming the option.
  static Result<std::unique_ptr<MotionSynthesizer>> Create(const SynthOptions& options);
  // Re-sequencing mode: `sources` are real takes of one skeleton family, already at options.fps.
  static Result<std::unique_ptr<MotionSynthesizer>> CreateFromTakes(const SynthOptions& options,
                                                                    std::vector<Take> sources);
  ~MotionSynthesizer();

  const Skeleton& skeleton() const;
  // The planted instances, known before generation starts (sorted by clip, then start).
  const std::vector<PlantedInstance>& truth() const;
  uint64_t clip_count() const;

  // Generates every clip in order and hands each to `sink` (which may write it); stops at the
  // first non-OK status from the sink and returns it.
  Status Run(const std::function<Status(const ClipFrames&)>& sink);

 private:
  class Impl;
  explicit MotionSynthesizer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Writes OUT.truth.json atomically: {"version": 1, "archive": ..., "frames": N, "seed": S,
// "motifs": M, "instances": [{"clip", "start", "end", "motif", "warp", "nonuniform"}, ...]}.
Status WriteTruthJson(const std::string& path, const std::string& archive_path, uint64_t frames,
                      const SynthOptions& options, const std::vector<PlantedInstance>& truth);

}  // namespace motif
