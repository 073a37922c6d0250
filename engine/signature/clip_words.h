// ClipWords: one clip held whole in memory (its source rows) with its word grid, to materialise
// all of its words at once or any time-warped copy of one of them. For what a single clip
// needs: a query clip or take in retrieval, the augmentation of training, and the reference the
// streaming (WordStream) is tested against. For a whole archive, stream (word_stream.h).
//
// AllWords resamples the whole clip to the word rate first (sample_count() rows, the same
// samples as word_grid.h defines) and cuts the words out of those rows: an independent path
// through the same definitions, giving the same words as WordStream, info and bytes.
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/signature/frame_resampler.h"
#include "engine/signature/time_warp.h"
#include "engine/signature/word_batch.h"
#include "engine/signature/word_grid.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

class ClipWords {
 public:
  // Reads clip `clip_idx` of the archive (ReadFrames); word ids and source frames are the
  // archive's, as WordStream gives them. InvalidArgument: clip_idx out of range, bad options or
  // weights (see WordStream::Create); errors of the reader pass through.
  static Result<ClipWords> Read(const FrameFileReader& reader, size_t clip_idx,
                                const std::vector<float>& joint_weights,
                                const WordOptions& options = {});
  // A clip given as rows (rows.size() / layout.stride() frames at `clip_fps`), e.g. a query take
  // that is not in the archive. `clip_idx`, `first_frame` and `first_word_id` go into the
  // WordInfo of its words. InvalidArgument: rows not a whole number of frames, clip_fps not
  // finite and positive, bad options or weights.
  static Result<ClipWords> FromRows(std::vector<float> rows, double clip_fps, FrameLayout layout,
                                    const std::vector<float>& joint_weights,
                                    const WordOptions& options = {}, uint32_t clip_idx = 0,
                                    uint64_t first_frame = 0, uint64_t first_word_id = 0);

  const WordGrid& grid() const { return grid_; }
  const FrameResampler& resampler() const { return resampler_; }
  uint64_t word_count() const { return grid_.word_count(); }
  const std::vector<float>& source_rows() const { return rows_; }

  // The clip at the word rate: grid().sample_count() rows of layout().stride() floats.
  std::vector<float> ResampledRows() const;
  // Where word `word_idx` (< word_count()) comes from.
  WordInfo Info(uint64_t word_idx) const;
  // Every word of the clip into `batch` (replacing its contents), with rows if `keep_rows`.
  void AllWords(WordBatch* batch, bool keep_rows = false) const;

  // Word `word_idx` played at `speed` (time_warp.h): W * feature_values() int16 into `features`,
  // and W rows into `rows` if not null.
  void WarpedWord(uint64_t word_idx, double speed, int16_t* features, float* rows = nullptr) const;
  // The same at a speed drawn from `seed` (DrawWarpSpeed); returns the speed.
  double RandomWarpedWord(uint64_t word_idx, uint64_t seed, const TimeWarpOptions& options,
                          int16_t* features, float* rows = nullptr) const;

 private:
  ClipWords() = default;

  std::vector<float> rows_;
  WordGrid grid_;
  FrameResampler resampler_;
  uint32_t clip_idx_ = 0;
  uint64_t first_frame_ = 0;
  uint64_t first_word_id_ = 0;
};

}  // namespace motif
