// WordStream: the motion words of an archive (Aristidou et al. 2018; word_grid.h defines them),
// streamed in archive order (clip after clip, word after word) a batch at a time, without ever
// holding all of them: the archive is read through one FrameStream (one decoded block at a time)
// and each clip is resampled to the word rate on the fly into a sliding buffer of W samples.
//
// Memory: the reader's decoded block, one archive row (the last frame of the previous block, the
// lower end of a sample straddling two blocks), a ring of W word frames (and W rows with
// keep_rows), and the batch being filled (batch_words words). Nothing grows with the archive or
// with the length of a clip.
//
// Samples that no word uses (a clip's tail after its last word, and the gaps between words when
// the stride exceeds the word length) are never computed, and clips shorter than one word are
// skipped (their blocks are still decoded: FrameStream reads the archive in order).
//
// The words are identical, info and bytes, to ClipWords' materialisation of each clip
// (clip_words.h), which the tests check.
// Thread-safety: one thread at a time per stream. Several streams over disjoint clip ranges
// (WordStreamOptions::first_clip / clip_count) may run in parallel on one reader.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/status.h"
#include "engine/signature/frame_resampler.h"
#include "engine/signature/word_batch.h"
#include "engine/signature/word_grid.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct WordStreamOptions {
  WordOptions words;
  uint32_t batch_words = 1024;  // at most this many words per Next()
  bool keep_rows = false;       // also hand out each word's resampled rows (all joints, root)
  // The clips to stream: [first_clip, first_clip + clip_count), clamped to the archive. Word ids
  // still count from the archive's first word.
  uint64_t first_clip = 0;
  uint64_t clip_count = UINT64_MAX;
};

// The rate of a clip's frames: its own recorded rate, or the archive's if it records none.
double ClipFps(const FrameFileReader& reader, const ClipInfo& clip);

// The word grid of clip `clip_idx` (< reader.clips().size()). Preconditions as WordGrid's.
WordGrid ClipWordGrid(const FrameFileReader& reader, size_t clip_idx, const WordOptions& options);

class WordStream {
 public:
  // `joint_weights`: one per archive joint (see FrameResampler::Create). The reader must outlive
  // the stream. InvalidArgument: bad word options (ValidateWordOptions), batch_words 0, bad
  // weights.
  static Result<std::unique_ptr<WordStream>> Create(const FrameFileReader& reader,
                                                    const std::vector<float>& joint_weights,
                                                    const WordStreamOptions& options = {});

  // Replaces `batch` with the next words: 1 to batch_words of them, true; false (and an empty
  // batch) at the end. Corruption or other errors of the reader pass through; the stream must not
  // be used after an error.
  Result<bool> Next(WordBatch* batch);

  const FrameResampler& resampler() const { return resampler_; }
  const WordStreamOptions& options() const { return options_; }
  // Words the stream gives in all (from the clip table) and the id of its first word.
  uint64_t word_count() const { return word_count_; }
  uint64_t first_word_id() const { return first_word_id_; }
  // Words handed out so far.
  uint64_t words_done() const { return next_word_id_ - first_word_id_; }

 private:
  WordStream(const FrameFileReader& reader, FrameResampler resampler,
             const WordStreamOptions& options);
  // Starts the next clip that has words; false when none is left.
  bool StartNextClip();
  // Decodes blocks until global frame `frame` is in the current block.
  Status EnsureFrame(uint64_t frame);
  // The row of global frame `frame`: in the current block, or the kept last row of the previous.
  const float* Row(uint64_t frame) const;

  const FrameFileReader& reader_;
  FrameResampler resampler_;
  WordStreamOptions options_;
  size_t stride_ = 0;
  uint64_t end_clip_ = 0;
  uint64_t word_count_ = 0;
  uint64_t first_word_id_ = 0;
  uint64_t next_word_id_ = 0;

  std::unique_ptr<FrameStream> frames_;
  bool have_block_ = false;
  uint64_t block_first_ = 0;
  uint64_t block_end_ = 0;
  std::vector<float> previous_row_;
  uint64_t previous_frame_ = UINT64_MAX;

  // The clip being cut into words.
  uint64_t clip_idx_ = 0;
  bool in_clip_ = false;
  WordGrid grid_;
  uint64_t clip_first_frame_ = 0;
  uint64_t next_sample_ = 0;
  uint64_t sample_end_ = 0;  // one past the last word's last sample
  // The last W samples of the clip, sample k in slot k % W.
  std::vector<int16_t> ring_features_;
  std::vector<float> ring_rows_;
};

}  // namespace motif
