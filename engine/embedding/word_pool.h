// WordPool: the motion words the embedding is trained on, held compactly in memory: for each word
// its features and root motion (word_input.h), and the same for `warp_copies` time-warped copies
// of it (time_warp.h, the paper's augmentation), drawn once from seeds when the pool is built.
// One version (the word or a copy) takes W (8 J_w + 16) bytes: 1,792 at W = 16, J_w = 12.
//
// The pool is made of whole clips (a clip's words are consecutive, so the temporal positives of
// a word are its clip neighbours), all of the archive's when it has at most `max_words` words,
// otherwise clips in a seeded random order until the budget is spent (the last one possibly
// cut short: its first words only). So the training's memory and time do not grow with the
// archive; the other words are embedded by the trained network but not trained on.
// A seeded fraction of the pool's clips is held out: their words are never anchors, positives or
// negatives in training, and measure the embedding on words it did not see (held-out triplet
// accuracy, embedding_trainer.h).
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/status.h"
#include "engine/signature/clip_words.h"
#include "engine/signature/time_warp.h"
#include "engine/signature/word_grid.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct WordPoolOptions {
  WordOptions words;
  uint64_t max_words = 30000;  // the budget, at least 1
  uint32_t warp_copies = 2;    // time-warped copies kept per word
  TimeWarpOptions warp;
  double held_out_fraction = 0.1;  // of the pool's clips, in [0, 1)
  uint64_t seed = 1;
  int threads = 0;                                   // 0: all cores
  std::function<void(uint64_t, uint64_t)> progress;  // (clips done, clips)
};

// InvalidArgument naming the option.
Status ValidateWordPoolOptions(const WordPoolOptions& options);

struct PoolClip {
  uint32_t archive_clip = 0;   // index in the archive's clip table (or the caller's numbering)
  uint64_t first_word = 0;     // the pool index of its first word
  uint64_t word_count = 0;     // words of the clip in the pool (its first ones)
  uint64_t first_word_id = 0;  // archive word id of its first word
  bool held_out = false;
};

class WordPool {
 public:
  // Chooses the clips and reads them from the archive (ClipWords::Read), in parallel.
  // InvalidArgument: bad options or weights; errors of the reader pass through.
  static Result<WordPool> Build(const FrameFileReader& reader,
                                const std::vector<float>& joint_weights,
                                const WordPoolOptions& options);
  // A pool of the given clips, all of them (max_words is ignored), clip i numbered i. For tests
  // and small in-memory sets. InvalidArgument: no clips, clips of different shapes.
  static Result<WordPool> FromClips(std::span<const ClipWords> clips,
                                    const WordPoolOptions& options);

  uint64_t size() const { return word_clip_.size(); }
  uint32_t versions() const { return versions_; }  // 1 + warp_copies; version 0 is the word
  uint32_t word_frames() const { return word_frames_; }
  uint32_t weighted_joints() const { return weighted_joints_; }
  const std::vector<float>& joint_weights() const { return weights_; }  // the weighted joints'
  const std::vector<PoolClip>& clips() const { return clips_; }

  // The pool clip of word `word`, and the word's index within that clip.
  uint32_t clip_of(uint64_t word) const { return word_clip_[word]; }
  uint64_t index_in_clip(uint64_t word) const { return word - clips_[word_clip_[word]].first_word; }
  bool held_out(uint64_t word) const { return clips_[word_clip_[word]].held_out; }

  // W x 4 J_w int16 and W x 4 floats of version `version` of word `word`.
  const int16_t* features(uint64_t word, uint32_t version) const;
  const float* root_motion(uint64_t word, uint32_t version) const;
  // The network input (W x C floats, word_input.h).
  void EncodeInput(uint64_t word, uint32_t version, float* out) const;
  uint32_t input_channels() const;

  // Words of one clip that overlap word w (|index difference| < ceil(W / S)) are trivial
  // matches of it: neither positives of the DTW kind nor negatives.
  uint32_t overlap_words() const { return overlap_words_; }

 private:
  struct ClipData;
  static Result<WordPool> Assemble(std::vector<PoolClip> clips, std::vector<ClipData> data,
                                   const FrameResampler& resampler, const WordPoolOptions& options);
  static ClipData MakeClipData(const ClipWords& clip, uint64_t word_count,
                               const WordPoolOptions& options);

  uint32_t versions_ = 1;
  uint32_t word_frames_ = 0;
  uint32_t weighted_joints_ = 0;
  uint32_t overlap_words_ = 1;
  std::vector<float> weights_;
  std::vector<PoolClip> clips_;
  std::vector<uint32_t> word_clip_;
  std::vector<int16_t> features_;  // word-major, then version
  std::vector<float> root_motion_;
};

}  // namespace motif
