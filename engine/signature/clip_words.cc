#include "engine/signature/clip_words.h"

#include <cmath>
#include <cstring>
#include <string>

#include "engine/signature/word_stream.h"

namespace motif {

Result<ClipWords> ClipWords::Read(const FrameFileReader& reader, size_t clip_idx,
                                  const std::vector<float>& joint_weights,
                                  const WordOptions& options) {
  const std::vector<ClipInfo>& clips = reader.clips();
  if (clip_idx >= clips.size()) {
    return Status::InvalidArgument("clip words: " + reader.path() + " has " +
                                   std::to_string(clips.size()) + " clips, no clip " +
                                   std::to_string(clip_idx));
  }
  MOTIF_RETURN_IF_ERROR(ValidateWordOptions(options));
  uint64_t first_word_id = 0;
  for (size_t before = 0; before < clip_idx; ++before) {
    first_word_id += ClipWordGrid(reader, before, options).word_count();
  }
  const ClipInfo& clip = clips[clip_idx];
  std::vector<float> rows;
  MOTIF_RETURN_IF_ERROR(reader.ReadFrames(clip.first_frame, clip.frame_count, &rows));
  return FromRows(std::move(rows), ClipFps(reader, clip), reader.layout(), joint_weights, options,
                  static_cast<uint32_t>(clip_idx), clip.first_frame, first_word_id);
}

Result<ClipWords> ClipWords::FromRows(std::vector<float> rows, double clip_fps, FrameLayout layout,
                                      const std::vector<float>& joint_weights,
                                      const WordOptions& options, uint32_t clip_idx,
                                      uint64_t first_frame, uint64_t first_word_id) {
  MOTIF_RETURN_IF_ERROR(ValidateWordOptions(options));
  if (!std::isfinite(clip_fps) || clip_fps <= 0) {
    return Status::InvalidArgument("clip words: the clip's rate must be finite and positive, not " +
                                   std::to_string(clip_fps));
  }
  if (rows.size() % layout.stride() != 0) {
    return Status::InvalidArgument("clip words: " + std::to_string(rows.size()) +
                                   " floats are not whole frames of " +
                                   std::to_string(layout.stride()));
  }
  ClipWords clip;
  MOTIF_ASSIGN_OR_RETURN(clip.resampler_, FrameResampler::Create(layout, joint_weights));
  clip.grid_ = WordGrid(rows.size() / layout.stride(), clip_fps, options);
  clip.rows_ = std::move(rows);
  clip.clip_idx_ = clip_idx;
  clip.first_frame_ = first_frame;
  clip.first_word_id_ = first_word_id;
  return clip;
}

std::vector<float> ClipWords::ResampledRows() const {
  const size_t stride = resampler_.layout().stride();
  std::vector<float> resampled(grid_.sample_count() * stride);
  for (uint64_t sample = 0; sample < grid_.sample_count(); ++sample) {
    const SourcePosition position = grid_.Sample(sample);
    resampler_.InterpolateRow(&rows_[position.lower * stride], &rows_[position.upper * stride],
                              position.alpha, &resampled[sample * stride]);
  }
  return resampled;
}

WordInfo ClipWords::Info(uint64_t word_idx) const {
  const FrameSpan source = grid_.SourceFrames(word_idx);
  WordInfo info;
  info.word_id = first_word_id_ + word_idx;
  info.clip_idx = clip_idx_;
  info.word_idx = word_idx;
  info.first_sample = grid_.FirstSample(word_idx);
  info.start_seconds = grid_.StartSeconds(word_idx);
  info.first_source_frame = first_frame_ + source.first;
  info.end_source_frame = first_frame_ + source.end;
  return info;
}

void ClipWords::AllWords(WordBatch* batch, bool keep_rows) const {
  const size_t stride = resampler_.layout().stride();
  const size_t feature_values = resampler_.feature_values();
  const uint32_t word_frames = grid_.options().word_frames;
  batch->Reset(word_frames, feature_values, keep_rows ? stride : 0);
  if (grid_.word_count() == 0) return;
  const std::vector<float> resampled = ResampledRows();
  std::vector<int16_t> features(grid_.sample_count() * feature_values);
  for (uint64_t sample = 0; sample < grid_.sample_count(); ++sample) {
    resampler_.RowFeatures(&resampled[sample * stride], &features[sample * feature_values]);
  }
  for (uint64_t word_idx = 0; word_idx < grid_.word_count(); ++word_idx) {
    const WordInfo info = Info(word_idx);
    const size_t word = batch->Append(info);
    std::memcpy(batch->mutable_word(word), &features[info.first_sample * feature_values],
                word_frames * feature_values * sizeof(int16_t));
    if (keep_rows) {
      std::memcpy(batch->mutable_rows(word), &resampled[info.first_sample * stride],
                  word_frames * stride * sizeof(float));
    }
  }
}

void ClipWords::WarpedWord(uint64_t word_idx, double speed, int16_t* features, float* rows) const {
  WarpWord(grid_, resampler_, rows_.data(), word_idx, speed, features, rows);
}

double ClipWords::RandomWarpedWord(uint64_t word_idx, uint64_t seed, const TimeWarpOptions& options,
                                   int16_t* features, float* rows) const {
  const double speed = DrawWarpSpeed(seed, options);
  WarpedWord(word_idx, speed, features, rows);
  return speed;
}

}  // namespace motif
