// RangeQuery: the motion words a search query made of a clip's frame range consists of, and
// the query it becomes (engine/words/window_search.h). Words lie on a grid (a new word every hop,
// each reading more frames than the hop: word_grid.h), so a range rarely starts and ends on word
// boundaries:
//  * a range at least one word long is the words that lie within it give or take half a hop at
//    either end (any such range holds at least one: their first frames are a hop apart);
//  * a shorter range is padded to one word: the word of the clip whose centre is nearest the
//    range's centre (ties: the earlier), so the motion around the range fills it out.
// The query then excludes, in its own clip, every window sharing a word or a source frame with
// the range or with the words read, so the query never finds itself.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>

#include "common/status.h"
#include "engine/signature/word_grid.h"
#include "engine/words/window_search.h"
#include "engine/words/word_model.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct RangeQuery {
  uint32_t clip = 0;
  FrameSpan range;          // the frames asked for (clip-relative)
  uint64_t first_word = 0;  // the query's words [first_word, end_word) within the clip
  uint64_t end_word = 0;
  FrameSpan word_frames;         // the source frames those words read
  uint64_t one_word_frames = 0;  // the source frames one word reads (the first word's span)
  bool padded = false;           // the range was shorter than one word: padded to one
};

// The words of frames [start, end) of `clip`. InvalidArgument: an empty range or one past the
// clip's end, a clip of no word (shorter than one word).
Result<RangeQuery> RangeQueryWords(const FrameFileReader& reader, const LoadedWords& words,
                                   uint32_t clip, uint64_t start, uint64_t end);

// The sliding-window query of those words: their motifs, the query's own windows excluded.
WindowQuery ToWindowQuery(const RangeQuery& range, const LoadedWords& words);

}  // namespace motif
