// WordGrid: where the motion words of one clip sit (Aristidou et al. 2018, "Deep motifs and motion
// signatures", section 4: words of W = 16 frames at 24 Hz, a new word every S = 4 frames). The
// clip's source frames (at its own rate, 120 fps for CMU) are resampled to the word rate; this
// class holds the arithmetic of that resampling and of the words over it, and nothing else: no
// frames, no I/O. docs/design/signatures.md, "Motion words", states the same definitions.
//
// For a clip of n source frames at rate f, word rate r (24 Hz), write u for a position in
// samples (frames at rate r) and t for a position in source frames (both from the clip's start):
//
//   t(u)     = u * f / r                     (exactly u when f and r agree within 0.1 %)
//   sample k sits at t(k), k = 0 .. M - 1,   M = floor((n - 1) * r / f) + 1
//              (the last sample is at or before the last source frame: no motion is invented)
//   sample k = slerp(source floor(t), source floor(t) + 1, t - floor(t))   (frame_resampler.h)
//   word w   = samples [w S, w S + W),  w = 0 .. count - 1,
//              count = (M - W) / S + 1 if M >= W, else 0  (a clip shorter than a word has none)
//   word w reads the source frames [floor(t(w S)), ceil(t(w S + W - 1))], both ends included.
//
// At 120 fps, W = 16, S = 4: M = floor((n - 1) / 5) + 1, word w covers source frames
// [20 w, 20 w + 75] (76 frames, 0.633 s), the first word needs n >= 76 and count =
// floor((floor((n - 1) / 5) - 15) / 4) + 1. Words never span two clips: a grid is one clip's.
// Thread-safety: a value type; const methods are safe from many threads.
#pragma once

#include <cstdint>

#include "common/status.h"

namespace motif {

// The word geometry (the paper's ablation chose 16 frames at 24 Hz with a stride of 4).
struct WordOptions {
  uint32_t word_frames = 16;   // W: samples in a word
  uint32_t stride_frames = 4;  // S: samples between the first samples of consecutive words
  double word_fps = 24.0;      // r: the rate words are sampled at
};

// The longest word accepted (the DTW keeps two rows of this many cells on the stack).
inline constexpr uint32_t kMaxWordFrames = 1024;

// InvalidArgument naming the option: word_frames 0 or above kMaxWordFrames, stride_frames 0,
// word_fps not finite or not positive.
Status ValidateWordOptions(const WordOptions& options);

// A position between two source frames of a clip (clip-relative indices): the sample is
// slerp(lower, upper, alpha). upper is lower + 1, or lower itself when alpha is 0 (the position
// falls on a source frame, which is then copied exactly).
struct SourcePosition {
  uint64_t lower = 0;
  uint64_t upper = 0;
  double alpha = 0;
};

// A range of frames [first, end).
struct FrameSpan {
  uint64_t first = 0;
  uint64_t end = 0;
  uint64_t count() const { return end - first; }
  bool operator==(const FrameSpan&) const = default;
};

class WordGrid {
 public:
  WordGrid() = default;
  // A clip of `source_frames` frames at `clip_fps`. Preconditions (checked, abort otherwise):
  // ValidateWordOptions(options) is OK, clip_fps finite and positive.
  WordGrid(uint64_t source_frames, double clip_fps, const WordOptions& options);

  uint64_t source_frames() const { return source_frames_; }
  double clip_fps() const { return clip_fps_; }
  const WordOptions& options() const { return options_; }
  // M: samples at the word rate.
  uint64_t sample_count() const { return sample_count_; }
  // Words in the clip (0 if sample_count() < word_frames).
  uint64_t word_count() const { return word_count_; }
  // The last sample position (in samples) that stays inside the clip: (n - 1) * r / f.
  double last_sample_position() const;

  // t(u): the source position (in source frames) of sample position u.
  double SourceTime(double sample_position) const;
  // The source frames around source position `source_time`, clamped to [0, n - 1].
  SourcePosition Locate(double source_time) const;
  // Locate(SourceTime(sample_idx)).
  SourcePosition Sample(uint64_t sample_idx) const { return Locate(SourceTime(sample_idx)); }

  // First sample of word `word_idx`: word_idx * S.
  uint64_t FirstSample(uint64_t word_idx) const { return word_idx * options_.stride_frames; }
  // The word's start from the clip's start, in seconds: FirstSample / r.
  double StartSeconds(uint64_t word_idx) const;
  // The source frames the word reads (clip-relative), as defined above.
  FrameSpan SourceFrames(uint64_t word_idx) const;
  // The words using source frame `frame_idx` (clip-relative): [first, end), maybe empty.
  FrameSpan WordsReading(uint64_t frame_idx) const;

 private:
  uint64_t source_frames_ = 0;
  double clip_fps_ = 0;
  bool same_rate_ = false;
  WordOptions options_;
  uint64_t sample_count_ = 0;
  uint64_t word_count_ = 0;
};

}  // namespace motif
