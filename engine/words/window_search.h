// Example-based motion retrieval with signatures (Aristidou et al. 2018, section 6.2):
//  * sliding window: a query of q words (a clip range of the archive, or a motion from outside)
//    becomes one signature (its words' motifs, TF-IDF with the archive's idf); a window of q
//    consecutive words slides one word at a time along every take, each window's signature is
//    compared with the query's by the EMD, and each take's best window (ties: the earliest) is
//    its match; takes are ranked by their best window (ties: the lower clip index). Windows of
//    the query's own clip that overlap the query's words are trivial matches and left out.
//  * whole take: the query is a whole take's signature, compared with every other take's.
// A window's term counts are updated word by word (one in, one out), so a take of m words costs
// m - q + 1 EMDs over at most q motifs (a few microseconds each at q = 9), not a recount.
// Takes are searched in parallel, each written to its own slot: the result does not depend on
// the thread count.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/status.h"
#include "engine/words/word_model.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct WindowMatch {
  uint32_t clip = 0;        // archive clip index
  uint64_t first_word = 0;  // within the clip
  uint64_t words = 0;
  uint64_t start_frame = 0;  // clip-relative source frames the window's words read: [start, end)
  uint64_t end_frame = 0;
  double distance = 0;  // EMD to the query
};

struct WindowQuery {
  std::vector<uint32_t> motifs;  // the query's words' motifs, in order
  // The query's place in the archive when it is a clip range (its windows are excluded), or
  // exclude_clip = UINT32_MAX for a query from outside.
  uint32_t exclude_clip = UINT32_MAX;
  uint64_t exclude_first_word = 0;
  uint64_t exclude_end_word = 0;
};

struct SearchResult {
  bool whole_take = false;
  std::vector<WindowMatch> matches;          // the top takes, best first
  std::vector<std::vector<float>> profiles;  // per match: the EMD of every window of its take
  uint64_t windows = 0;                      // windows compared in all
  uint64_t shorter_takes = 0;  // sliding window: takes of fewer words than the query, left out
  std::vector<uint32_t> shorter_clips;  // those takes (clip indices, in archive order)
};

// `top` >= 1 takes. InvalidArgument: an empty query, top 0, a motif id out of range.
Result<SearchResult> SlidingWindowSearch(const FrameFileReader& reader, const LoadedWords& words,
                                         const WindowQuery& query, uint32_t top, int threads);

// Every other take ranked by the EMD between whole-take signatures. InvalidArgument: a clip with
// no word, top 0.
Result<SearchResult> WholeTakeSearch(const FrameFileReader& reader, const LoadedWords& words,
                                     uint32_t query_clip, uint32_t top, int threads);

// The words of clip `clip` that lie within its frames [start, end) (clip-relative): [first, end)
// word indices. InvalidArgument when no word fits (the range is shorter than one word).
Result<std::pair<uint64_t, uint64_t>> WordsWithin(const FrameFileReader& reader,
                                                  const LoadedWords& words, uint32_t clip,
                                                  uint64_t start, uint64_t end);

}  // namespace motif
