#include "engine/words/range_query.h"

#include <algorithm>
#include <string>

#include "engine/signature/word_stream.h"

namespace motif {
namespace {

// The words lying within [start - slack, end + slack], or an empty span.
FrameSpan WordsNearlyWithin(const WordGrid& grid, uint64_t start, uint64_t end, uint64_t slack) {
  FrameSpan found{UINT64_MAX, 0};
  for (uint64_t word = 0; word < grid.word_count(); ++word) {
    const FrameSpan span = grid.SourceFrames(word);
    if (span.first + slack >= start && span.end <= end + slack) {
      found.first = std::min(found.first, word);
      found.end = word + 1;
    }
  }
  return found.first == UINT64_MAX ? FrameSpan{} : found;
}

// The word whose centre is nearest the centre of [start, end) (ties: the earlier).
uint64_t WordCentredOn(const WordGrid& grid, uint64_t start, uint64_t end) {
  uint64_t best = 0;
  uint64_t best_offset = UINT64_MAX;
  for (uint64_t word = 0; word < grid.word_count(); ++word) {
    const FrameSpan span = grid.SourceFrames(word);
    // Twice the centres, to stay in whole frames.
    const uint64_t word_centre = span.first + span.end;
    const uint64_t range_centre = start + end;
    const uint64_t offset =
        word_centre > range_centre ? word_centre - range_centre : range_centre - word_centre;
    if (offset < best_offset) {
      best_offset = offset;
      best = word;
    }
  }
  return best;
}

}  // namespace

Result<RangeQuery> RangeQueryWords(const FrameFileReader& reader, const LoadedWords& words,
                                   uint32_t clip, uint64_t start, uint64_t end) {
  const ClipInfo& info = reader.clips()[clip];
  if (start >= end || end > info.frame_count) {
    return Status::InvalidArgument("frames [" + std::to_string(start) + ", " + std::to_string(end) +
                                   ") are not a range within clip " + info.name + "'s " +
                                   std::to_string(info.frame_count) + " frames");
  }
  const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
  if (grid.word_count() == 0) {
    return Status::InvalidArgument("clip " + info.name + " has no motion word: its " +
                                   std::to_string(info.frame_count) +
                                   " frames are shorter than one word");
  }
  RangeQuery query;
  query.clip = clip;
  query.range = {start, end};
  query.one_word_frames = grid.SourceFrames(0).count();
  const uint64_t hop =
      grid.word_count() > 1 ? grid.SourceFrames(1).first - grid.SourceFrames(0).first : 0;
  FrameSpan found;
  if (end - start >= query.one_word_frames) {
    found = WordsNearlyWithin(grid, start, end, (hop + 1) / 2);
  }
  if (found.count() == 0) {  // shorter than a word (or at the clip's edge): one word
    const uint64_t word = WordCentredOn(grid, start, end);
    found = {word, word + 1};
    query.padded = true;
  }
  query.first_word = found.first;
  query.end_word = found.end;
  query.word_frames = {grid.SourceFrames(found.first).first, grid.SourceFrames(found.end - 1).end};
  return query;
}

WindowQuery ToWindowQuery(const RangeQuery& range, const LoadedWords& words) {
  WindowQuery query;
  const std::vector<uint32_t> clip_motifs = words.ClipMotifs(range.clip);
  query.motifs.assign(clip_motifs.begin() + static_cast<std::ptrdiff_t>(range.first_word),
                      clip_motifs.begin() + static_cast<std::ptrdiff_t>(range.end_word));
  query.exclude_clip = range.clip;
  query.exclude_first_word = range.first_word;
  query.exclude_end_word = range.end_word;
  query.exclude_start_frame = std::min(range.range.first, range.word_frames.first);
  query.exclude_end_frame = std::max(range.range.end, range.word_frames.end);
  return query;
}

}  // namespace motif
