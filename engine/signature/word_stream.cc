#include "engine/signature/word_stream.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace motif {

double ClipFps(const FrameFileReader& reader, const ClipInfo& clip) {
  return std::isfinite(clip.fps) && clip.fps > 0 ? clip.fps : reader.fps();
}

WordGrid ClipWordGrid(const FrameFileReader& reader, size_t clip_idx, const WordOptions& options) {
  const ClipInfo& clip = reader.clips()[clip_idx];
  return WordGrid(clip.frame_count, ClipFps(reader, clip), options);
}

Result<std::unique_ptr<WordStream>> WordStream::Create(const FrameFileReader& reader,
                                                       const std::vector<float>& joint_weights,
                                                       const WordStreamOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateWordOptions(options.words));
  if (options.batch_words == 0) {
    return Status::InvalidArgument("word stream: batch_words must be at least 1");
  }
  MOTIF_ASSIGN_OR_RETURN(FrameResampler resampler,
                         FrameResampler::Create(reader.layout(), joint_weights));
  return std::unique_ptr<WordStream>(new WordStream(reader, std::move(resampler), options));
}

WordStream::WordStream(const FrameFileReader& reader, FrameResampler resampler,
                       const WordStreamOptions& options)
    : reader_(reader), resampler_(std::move(resampler)), options_(options) {
  const std::vector<ClipInfo>& clips = reader_.clips();
  stride_ = reader_.layout().stride();
  const uint64_t first_clip = std::min<uint64_t>(options_.first_clip, clips.size());
  end_clip_ = first_clip + std::min<uint64_t>(options_.clip_count, clips.size() - first_clip);
  for (uint64_t clip_idx = 0; clip_idx < end_clip_; ++clip_idx) {
    const uint64_t words = ClipWordGrid(reader_, clip_idx, options_.words).word_count();
    (clip_idx < first_clip ? first_word_id_ : word_count_) += words;
  }
  next_word_id_ = first_word_id_;
  clip_idx_ = first_clip;
  if (first_clip < end_clip_) {
    const ClipInfo& last = clips[end_clip_ - 1];
    frames_ = reader_.Stream(clips[first_clip].first_frame, last.first_frame + last.frame_count);
  } else {
    frames_ = reader_.Stream(0, 0);
  }
  const uint32_t word_frames = options_.words.word_frames;
  ring_features_.resize(word_frames * resampler_.feature_values());
  if (options_.keep_rows) ring_rows_.resize(word_frames * stride_);
  previous_row_.resize(stride_);
}

bool WordStream::StartNextClip() {
  for (; clip_idx_ < end_clip_; ++clip_idx_) {
    WordGrid grid = ClipWordGrid(reader_, clip_idx_, options_.words);
    if (grid.word_count() == 0) continue;
    grid_ = grid;
    clip_first_frame_ = reader_.clips()[clip_idx_].first_frame;
    next_sample_ = 0;
    sample_end_ = grid_.FirstSample(grid_.word_count() - 1) + options_.words.word_frames;
    in_clip_ = true;
    return true;
  }
  return false;
}

Status WordStream::EnsureFrame(uint64_t frame) {
  while (!have_block_ || frame >= block_end_) {
    if (have_block_ && block_end_ > block_first_) {
      // The next block's first sample may interpolate from this block's last frame.
      const float* last = frames_->rows() + (block_end_ - 1 - block_first_) * stride_;
      std::copy(last, last + stride_, previous_row_.begin());
      previous_frame_ = block_end_ - 1;
    }
    MOTIF_ASSIGN_OR_RETURN(bool more, frames_->Next());
    if (!more) {
      return Status::Corruption("word stream: " + reader_.path() + ": frames end at " +
                                std::to_string(block_end_) + ", before frame " +
                                std::to_string(frame) + " of clip " +
                                reader_.clips()[clip_idx_].name);
    }
    have_block_ = true;
    block_first_ = frames_->first_frame();
    block_end_ = block_first_ + frames_->frame_count();
  }
  return Status::Ok();
}

const float* WordStream::Row(uint64_t frame) const {
  if (have_block_ && frame >= block_first_ && frame < block_end_) {
    return frames_->rows() + (frame - block_first_) * stride_;
  }
  // A sample's two frames are adjacent, so the lower one is at worst the previous block's last.
  MOTIF_CHECK(frame == previous_frame_);
  return previous_row_.data();
}

Result<bool> WordStream::Next(WordBatch* batch) {
  const uint32_t word_frames = options_.words.word_frames;
  const uint32_t stride_frames = options_.words.stride_frames;
  const size_t feature_values = resampler_.feature_values();
  batch->Reset(word_frames, feature_values, options_.keep_rows ? stride_ : 0);
  while (batch->size() < options_.batch_words) {
    if (!in_clip_ && !StartNextClip()) break;
    if (next_sample_ >= sample_end_) {
      in_clip_ = false;
      ++clip_idx_;
      continue;
    }
    const uint64_t sample = next_sample_;
    if (stride_frames > word_frames && sample % stride_frames >= word_frames) {
      next_sample_ = (sample / stride_frames + 1) * stride_frames;  // in no word: skip
      continue;
    }
    const SourcePosition position = grid_.Sample(sample);
    MOTIF_RETURN_IF_ERROR(EnsureFrame(clip_first_frame_ + position.upper));
    const float* lower = Row(clip_first_frame_ + position.lower);
    const float* upper = Row(clip_first_frame_ + position.upper);
    const size_t slot = sample % word_frames;
    int16_t* features = &ring_features_[slot * feature_values];
    if (options_.keep_rows) {
      float* row = &ring_rows_[slot * stride_];
      resampler_.InterpolateRow(lower, upper, position.alpha, row);
      resampler_.RowFeatures(row, features);
    } else {
      resampler_.InterpolateFeatures(lower, upper, position.alpha, features);
    }
    next_sample_ = sample + 1;
    if (sample + 1 < word_frames || (sample + 1 - word_frames) % stride_frames != 0) continue;

    // Sample `sample` completes word word_idx: copy its W samples out of the ring, in order.
    const uint64_t word_idx = (sample + 1 - word_frames) / stride_frames;
    const FrameSpan source = grid_.SourceFrames(word_idx);
    WordInfo info;
    info.word_id = next_word_id_++;
    info.clip_idx = static_cast<uint32_t>(clip_idx_);
    info.word_idx = word_idx;
    info.first_sample = grid_.FirstSample(word_idx);
    info.start_seconds = grid_.StartSeconds(word_idx);
    info.first_source_frame = clip_first_frame_ + source.first;
    info.end_source_frame = clip_first_frame_ + source.end;
    const size_t word = batch->Append(info);
    int16_t* out = batch->mutable_word(word);
    float* out_rows = options_.keep_rows ? batch->mutable_rows(word) : nullptr;
    for (uint32_t frame = 0; frame < word_frames; ++frame) {
      const size_t from = (info.first_sample + frame) % word_frames;
      std::memcpy(out + frame * feature_values, &ring_features_[from * feature_values],
                  feature_values * sizeof(int16_t));
      if (out_rows != nullptr) {
        std::memcpy(out_rows + frame * stride_, &ring_rows_[from * stride_],
                    stride_ * sizeof(float));
      }
    }
  }
  return !batch->empty();
}

}  // namespace motif
