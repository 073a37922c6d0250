// Time-warped copies of a motion word: the augmentation of the triplet training (Aristidou et al.
// 2018, section 4.2: positives are "augmented with time-warped versions of themselves"). A copy
// shows the same moment of the same clip played at another speed: W samples taken from the
// clip's source frames (slerp, as every word frame: frame_resampler.h) at a spacing of `speed`
// samples instead of 1, centred on the word's centre.
//
// For word w of a grid (word_grid.h), in sample units (u: a position at the word rate):
//   c   = w S + (W - 1) / 2                            the word's centre
//   u_j = c + (j - (W - 1) / 2) * speed,   j = 0 .. W - 1
// then shifted by the least amount that brings [u_0, u_{W-1}] inside the clip, [0, (n - 1) r / f]
// (a copy played faster than 1 near a clip's ends would otherwise read past them; if the span
// is longer than the clip, the copy is centred on it and its ends are clamped to the first and
// last frames). Each u_j becomes a source time t(u_j) and a sample as in the grid. speed > 1 plays
// the motion faster (the copy spans more of the clip), speed < 1 slower. At speed 1 every u_j is
// w S + j exactly, so the copy is the word itself, bit for bit.
// Speeds are drawn log-uniformly in [min_speed, max_speed] (so 0.8 and 1.25 are equally likely
// to be approached), deterministically from a seed with SplitMix64 (fixed by its definition, the
// same on every platform): the caller derives the seed from its own seed and the word's id.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/signature/frame_resampler.h"
#include "engine/signature/word_grid.h"

namespace motif {

struct TimeWarpOptions {
  double min_speed = 0.8;
  double max_speed = 1.25;
};

// InvalidArgument: a speed not finite or not positive, min_speed > max_speed.
Status ValidateTimeWarpOptions(const TimeWarpOptions& options);

// A speed in [min_speed, max_speed], log-uniform, from `seed`. Precondition: valid options.
double DrawWarpSpeed(uint64_t seed, const TimeWarpOptions& options);

// The W sample positions u_0 .. u_{W-1} of word `word_idx` (< grid.word_count()) at `speed` (> 0),
// as defined above.
std::vector<double> WarpedSamplePositions(const WordGrid& grid, uint64_t word_idx, double speed);

// The warped copy of word `word_idx` of a clip whose source rows (grid.source_frames() rows of
// resampler.layout()) are `clip_rows`: W frames of features into `features`
// (W * resampler.feature_values() int16), and if `rows` is not null W resampled rows
// (W * stride floats).
void WarpWord(const WordGrid& grid, const FrameResampler& resampler, const float* clip_rows,
              uint64_t word_idx, double speed, int16_t* features, float* rows = nullptr);

}  // namespace motif
