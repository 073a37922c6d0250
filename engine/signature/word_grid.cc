#include "engine/signature/word_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "formats/motion/resample.h"

namespace motif {

Status ValidateWordOptions(const WordOptions& options) {
  if (options.word_frames == 0 || options.word_frames > kMaxWordFrames) {
    return Status::InvalidArgument("motion words: word_frames must be 1 to " +
                                   std::to_string(kMaxWordFrames) + ", not " +
                                   std::to_string(options.word_frames));
  }
  if (options.stride_frames == 0) {
    return Status::InvalidArgument("motion words: stride_frames must be at least 1");
  }
  if (!std::isfinite(options.word_fps) || options.word_fps <= 0) {
    return Status::InvalidArgument("motion words: word_fps must be finite and positive, not " +
                                   std::to_string(options.word_fps));
  }
  return Status::Ok();
}

WordGrid::WordGrid(uint64_t source_frames, double clip_fps, const WordOptions& options)
    : source_frames_(source_frames), clip_fps_(clip_fps), options_(options) {
  MOTIF_CHECK(ValidateWordOptions(options).ok());
  MOTIF_CHECK(std::isfinite(clip_fps) && clip_fps > 0);
  // The importers' rule (ResampleTake): rates within 0.1 % are the same, so a BVH's rounded frame
  // time does not turn every sample into a blend of two frames.
  same_rate_ = SameFrameRate(clip_fps, options.word_fps);
  if (source_frames_ == 0) return;
  // (n - 1) * r / f in this order: exact whenever the true value is an integer (integral rates),
  // the 1e-9 absorbs the rounding of the others.
  sample_count_ = static_cast<uint64_t>(std::floor(last_sample_position() + 1e-9)) + 1;
  const uint64_t word_frames = options_.word_frames;
  if (sample_count_ >= word_frames) {
    word_count_ = (sample_count_ - word_frames) / options_.stride_frames + 1;
  }
}

double WordGrid::last_sample_position() const {
  if (source_frames_ == 0) return 0;
  const double last = static_cast<double>(source_frames_ - 1);
  return same_rate_ ? last : last * options_.word_fps / clip_fps_;
}

double WordGrid::SourceTime(double sample_position) const {
  // u * f / r in this order: for integral rates and integral u (the regular samples), the product
  // is exact and the quotient is exact whenever the true time falls on a source frame (all of
  // them at 120 -> 24 Hz), so such samples copy their source frame bit for bit.
  return same_rate_ ? sample_position : sample_position * clip_fps_ / options_.word_fps;
}

SourcePosition WordGrid::Locate(double source_time) const {
  SourcePosition position;
  if (source_frames_ == 0) return position;
  const uint64_t last = source_frames_ - 1;
  if (!(source_time > 0)) return position;  // also NaN: the first frame
  if (source_time >= static_cast<double>(last)) {
    position.lower = position.upper = last;
    return position;
  }
  const double lower = std::floor(source_time);
  position.lower = static_cast<uint64_t>(lower);
  position.alpha = source_time - lower;
  position.upper = position.alpha > 0 ? position.lower + 1 : position.lower;
  return position;
}

double WordGrid::StartSeconds(uint64_t word_idx) const {
  return static_cast<double>(FirstSample(word_idx)) / options_.word_fps;
}

FrameSpan WordGrid::SourceFrames(uint64_t word_idx) const {
  const SourcePosition first = Sample(FirstSample(word_idx));
  const SourcePosition last = Sample(FirstSample(word_idx) + options_.word_frames - 1);
  return FrameSpan{first.lower, last.upper + 1};
}

FrameSpan WordGrid::WordsReading(uint64_t frame_idx) const {
  // Both ends of SourceFrames(w) are non-decreasing in w: two binary searches.
  uint64_t low = 0;
  uint64_t high = word_count_;
  while (low < high) {  // first word whose range ends after frame_idx
    const uint64_t mid = low + (high - low) / 2;
    if (SourceFrames(mid).end <= frame_idx)
      low = mid + 1;
    else
      high = mid;
  }
  const uint64_t first = low;
  high = word_count_;
  while (low < high) {  // first word whose range starts after frame_idx
    const uint64_t mid = low + (high - low) / 2;
    if (SourceFrames(mid).first <= frame_idx)
      low = mid + 1;
    else
      high = mid;
  }
  return FrameSpan{first, low};
}

}  // namespace motif
