// Example-based motion retrieval with signatures (Aristidou et al. 2018, section 6.2):
//  * sliding window: a query of q words (a clip range of the archive, or a motion from outside)
//    becomes one signature (its words' motifs, TF-IDF with the archive's idf); a window of q
//    consecutive words slides one word at a time along every take and each window's signature
//    is compared with the query's by the EMD. A take gives several matches, chosen greedily:
//    its best window (ties: the earliest), then its best window sharing no source frame with
//    one kept, and so on; the matches of all takes are ranked together (ties: the lower clip,
//    then the earlier window) and the first `top` kept. Windows of the query's own clip that
//    share a word or a source frame with the query are trivial matches and left out. A take of
//    fewer words than the query (but at least one) is compared whole: one window of all its
//    words. A take of no word is left out (wordless_clips).
//  * whole take: the query is a whole take's signature, compared with every other take's.
// A window's term counts are updated word by word (one in, one out), so a take of m words costs
// m - q + 1 EMDs over at most q motifs (a few microseconds each at q = 9), not a recount.
// Takes are searched in parallel, each written to its own slot: the result does not depend on
// the thread count.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
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
  double distance = 0;        // EMD to the query
  uint32_t rank_in_take = 1;  // 1: the take's best window, 2: its best one not overlapping it...
  bool whole_take = false;    // the take has fewer words than the query: the window is all of it
};

// Two windows overlap when they read a source frame in common (frames [start, end) each).
inline bool WindowsOverlap(uint64_t start_a, uint64_t end_a, uint64_t start_b, uint64_t end_b) {
  return start_a < end_b && start_b < end_a;
}

struct WindowQuery {
  std::vector<uint32_t> motifs;  // the query's words' motifs, in order
  // The query's place in the archive when it is a clip range (its windows are excluded), or
  // exclude_clip = UINT32_MAX for a query from outside.
  uint32_t exclude_clip = UINT32_MAX;
  uint64_t exclude_first_word = 0;
  uint64_t exclude_end_word = 0;
  // And the query's source frames [exclude_start_frame, exclude_end_frame) within exclude_clip:
  // a window reading any of them is left out too (none when the span is empty).
  uint64_t exclude_start_frame = 0;
  uint64_t exclude_end_frame = 0;
};

struct SearchResult {
  std::string distance = "emd";  // or "movement" (movement_search.h)
  bool whole_take = false;
  std::vector<WindowMatch> matches;          // the top windows, best first
  std::vector<std::vector<float>> profiles;  // per match: the EMD of every window of its take
  uint64_t windows = 0;                      // windows compared in all
  // Sliding window: takes of fewer words than the query (at least one), each compared whole.
  uint64_t shorter_takes = 0;
  std::vector<uint32_t> shorter_clips;   // those takes (clip indices, in archive order)
  std::vector<uint32_t> wordless_clips;  // takes of no word (shorter than one): left out
};

// `top` >= 1 windows. InvalidArgument: an empty query, top 0, a motif id out of range.
Result<SearchResult> SlidingWindowSearch(const FrameFileReader& reader, const LoadedWords& words,
                                         const WindowQuery& query, uint32_t top, int threads);

// Every other take ranked by the EMD between whole-take signatures (one match a take; takes of no
// word in wordless_clips). InvalidArgument: a clip with no word, top 0.
Result<SearchResult> WholeTakeSearch(const FrameFileReader& reader, const LoadedWords& words,
                                     uint32_t query_clip, uint32_t top, int threads);

// The words of clip `clip` that lie within its frames [start, end) (clip-relative): [first, end)
// word indices. InvalidArgument when no word fits (the range is shorter than one word).
Result<std::pair<uint64_t, uint64_t>> WordsWithin(const FrameFileReader& reader,
                                                  const LoadedWords& words, uint32_t clip,
                                                  uint64_t start, uint64_t end);

}  // namespace motif
