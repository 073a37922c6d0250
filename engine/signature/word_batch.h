// WordBatch: a run of motion words with where each comes from (WordInfo): the clip, the word's
// index in it, its start time and the archive frames it reads (word_grid.h defines them), and its
// frames as features (frame_resampler.h: W frames of 4 int16 per weighted joint, frame-major), plus
// optionally its resampled rows (all joints and the root, W rows of FrameLayout floats).
// WordStream fills one batch at a time; ClipWords fills one with a whole clip.
// Thread-safety: a value type; const methods are safe from many threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace motif {

struct WordInfo {
  uint64_t word_id = 0;             // the word's position in the archive's word order (clip
                                    // after clip, words in order within a clip)
  uint32_t clip_idx = 0;            // index into the archive's clip table
  uint64_t word_idx = 0;            // index of the word within its clip
  uint64_t first_sample = 0;        // first frame at the word rate, from the clip's start
  double start_seconds = 0;         // first_sample / word_fps
  uint64_t first_source_frame = 0;  // global archive frames the word reads: [first, end)
  uint64_t end_source_frame = 0;

  bool operator==(const WordInfo&) const = default;
};

class WordBatch {
 public:
  // Empties the batch and sets the shape of its words: `word_frames` frames of
  // `feature_values` int16 each, and `row_floats` floats a row (0: no rows kept).
  void Reset(uint32_t word_frames, size_t feature_values, size_t row_floats) {
    word_frames_ = word_frames;
    feature_values_ = feature_values;
    row_floats_ = row_floats;
    Clear();
  }
  // Empties the batch, keeping its shape and its memory.
  void Clear() {
    infos_.clear();
    features_.clear();
    rows_.clear();
  }

  size_t size() const { return infos_.size(); }
  bool empty() const { return infos_.empty(); }
  uint32_t word_frames() const { return word_frames_; }
  size_t feature_values() const { return feature_values_; }
  // int16 values of one word: word_frames() * feature_values().
  size_t word_values() const { return word_frames_ * feature_values_; }
  bool has_rows() const { return row_floats_ > 0; }
  size_t row_floats() const { return row_floats_; }

  const WordInfo& info(size_t word) const { return infos_[word]; }
  const std::vector<WordInfo>& infos() const { return infos_; }
  // Frame f of word `word` starts at word(word) + f * feature_values().
  const int16_t* word(size_t word) const { return &features_[word * word_values()]; }
  // Row f of word `word` starts at rows(word) + f * row_floats(). Only if has_rows().
  const float* rows(size_t word) const { return &rows_[word * word_frames_ * row_floats_]; }

  // Producers: appends a word with `info` and returns its index; fill its frames through
  // mutable_word (and mutable_rows if has_rows()).
  size_t Append(const WordInfo& info) {
    infos_.push_back(info);
    features_.resize(infos_.size() * word_values());
    rows_.resize(infos_.size() * word_frames_ * row_floats_);
    return infos_.size() - 1;
  }
  int16_t* mutable_word(size_t word) { return &features_[word * word_values()]; }
  float* mutable_rows(size_t word) { return &rows_[word * word_frames_ * row_floats_]; }

 private:
  uint32_t word_frames_ = 0;
  size_t feature_values_ = 0;
  size_t row_floats_ = 0;
  std::vector<WordInfo> infos_;
  std::vector<int16_t> features_;
  std::vector<float> rows_;
};

}  // namespace motif
