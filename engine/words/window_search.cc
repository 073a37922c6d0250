#include "engine/words/window_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/word_stream.h"

namespace motif {
namespace {

// One take's part of a search, written by the task that searched it.
struct TakeWindows {
  std::vector<double> distances;  // the EMD of every window (NaN: left out)
  std::vector<float> profile;     // the same as floats, for the page and search.json
  std::vector<WindowMatch> kept;  // its non-overlapping best windows, best first
  Status status;
};

// The source frames windows [first, first + count) words read.
FrameSpan WindowFrames(const WordGrid& grid, uint64_t first, uint64_t count) {
  return {grid.SourceFrames(first).first, grid.SourceFrames(first + count - 1).end};
}

WindowMatch MatchOf(const WordGrid& grid, uint32_t clip, uint64_t first_word, uint64_t count,
                    double distance) {
  const FrameSpan frames = WindowFrames(grid, first_word, count);
  WindowMatch match;
  match.clip = clip;
  match.first_word = first_word;
  match.words = count;
  match.start_frame = frames.first;
  match.end_frame = frames.end;
  match.distance = distance;
  return match;
}

// The TF-IDF signature of a bag of `words` words with these motif counts.
void CountsSignature(const std::vector<uint32_t>& counts, uint64_t words,
                     const std::vector<double>& idf, std::vector<double>* signature) {
  for (size_t motif = 0; motif < counts.size(); ++motif) {
    (*signature)[motif] =
        counts[motif] ? counts[motif] / static_cast<double>(words) * idf[motif] : 0.0;
  }
}

// Does window [first, first + q) of `clip` overlap the query itself?
bool IsTrivial(const WindowQuery& query, const WordGrid& grid, uint32_t clip, uint64_t first,
               uint64_t q) {
  if (clip != query.exclude_clip) return false;
  if (first < query.exclude_end_word && first + q > query.exclude_first_word) return true;
  const FrameSpan frames = WindowFrames(grid, first, q);
  return WindowsOverlap(frames.first, frames.end, query.exclude_start_frame,
                        query.exclude_end_frame);
}

// Greedy: the best window of the profile (ties: the earliest), then the best sharing no source
// frame with a kept one, ... up to `top`. Windows overlapping a kept one form a run around it
// (the windows' starts and ends both grow with their first word), so each is blocked once.
std::vector<uint64_t> NonOverlappingBest(const std::vector<double>& profile, const WordGrid& grid,
                                         uint64_t q, uint32_t top) {
  std::vector<uint64_t> order;
  for (uint64_t first = 0; first < profile.size(); ++first) {
    if (!std::isnan(profile[first])) order.push_back(first);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](uint64_t a, uint64_t b) { return profile[a] < profile[b]; });
  std::vector<bool> blocked(profile.size(), false);
  std::vector<uint64_t> kept;
  for (uint64_t first : order) {
    if (kept.size() >= top) break;
    if (blocked[first]) continue;
    kept.push_back(first);
    const FrameSpan frames = WindowFrames(grid, first, q);
    for (uint64_t other = first; other < profile.size(); ++other) {
      if (WindowFrames(grid, other, q).first >= frames.end) break;
      blocked[other] = true;
    }
    for (uint64_t other = first; other-- > 0;) {
      if (WindowFrames(grid, other, q).end <= frames.first) break;
      blocked[other] = true;
    }
  }
  return kept;
}

// Every window of q words along one take of m >= q words, into take->profile.
Status SlideAlongTake(const LoadedWords& words, const WindowQuery& query,
                      const std::vector<double>& query_signature, const WordGrid& grid,
                      uint32_t clip, EarthMoversDistance* emd, TakeWindows* take) {
  const uint64_t q = query.motifs.size();
  const uint64_t m = words.signatures.clip_words[clip];
  const std::vector<double>& idf = words.tf_idf->idf();
  const uint16_t* motifs = &words.signatures.word_motifs[words.clip_first_words[clip]];
  std::vector<uint32_t> counts(words.motifs.motif_count(), 0);
  std::vector<double> signature(counts.size());
  for (uint64_t word = 0; word < q; ++word) ++counts[motifs[word]];
  take->distances.assign(m - q + 1, std::numeric_limits<double>::quiet_NaN());
  for (uint64_t first = 0; first + q <= m; ++first) {
    if (first > 0) {
      --counts[motifs[first - 1]];
      ++counts[motifs[first + q - 1]];
    }
    if (IsTrivial(query, grid, clip, first, q)) continue;
    CountsSignature(counts, q, idf, &signature);
    MOTIF_ASSIGN_OR_RETURN(const double distance,
                           emd->Distance(query_signature, signature, words.ground));
    take->distances[first] = distance;
  }
  return Status::Ok();
}

// A take of fewer words than the query (m >= 1): one window, all of its words.
Status CompareWholeShorterTake(const LoadedWords& words, const WindowQuery& query,
                               const std::vector<double>& query_signature, const WordGrid& grid,
                               uint32_t clip, EarthMoversDistance* emd, TakeWindows* take) {
  const uint64_t m = words.signatures.clip_words[clip];
  const uint16_t* motifs = &words.signatures.word_motifs[words.clip_first_words[clip]];
  std::vector<uint32_t> counts(words.motifs.motif_count(), 0);
  std::vector<double> signature(counts.size());
  for (uint64_t word = 0; word < m; ++word) ++counts[motifs[word]];
  take->distances.assign(1, std::numeric_limits<double>::quiet_NaN());
  if (IsTrivial(query, grid, clip, 0, m)) return Status::Ok();
  CountsSignature(counts, m, words.tf_idf->idf(), &signature);
  MOTIF_ASSIGN_OR_RETURN(const double distance,
                         emd->Distance(query_signature, signature, words.ground));
  take->distances[0] = distance;
  return Status::Ok();
}

// One take of a sliding search: its profile and its kept windows.
void SearchTake(const FrameFileReader& reader, const LoadedWords& words, const WindowQuery& query,
                const std::vector<double>& query_signature, uint32_t clip, uint32_t top,
                EarthMoversDistance* emd, TakeWindows* take) {
  const uint64_t q = query.motifs.size();
  const uint64_t m = words.signatures.clip_words[clip];
  if (m == 0) return;
  const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
  const bool whole = m < q;
  const uint64_t count = whole ? m : q;
  take->status = whole
                     ? CompareWholeShorterTake(words, query, query_signature, grid, clip, emd, take)
                     : SlideAlongTake(words, query, query_signature, grid, clip, emd, take);
  if (!take->status.ok()) return;
  take->profile.assign(take->distances.begin(), take->distances.end());
  for (uint64_t first : NonOverlappingBest(take->distances, grid, count, top)) {
    WindowMatch match = MatchOf(grid, clip, first, count, take->distances[first]);
    match.rank_in_take = static_cast<uint32_t>(take->kept.size() + 1);
    match.whole_take = whole;
    take->kept.push_back(match);
  }
}

// The `top` kept windows of all takes with the least distance (ties: the lower clip, then the
// earlier window), each with its take's profile.
SearchResult Rank(std::vector<TakeWindows>& takes, uint32_t top) {
  std::vector<const WindowMatch*> all;
  for (const TakeWindows& take : takes) {
    for (const WindowMatch& match : take.kept) all.push_back(&match);
  }
  std::sort(all.begin(), all.end(), [](const WindowMatch* a, const WindowMatch* b) {
    if (a->distance != b->distance) return a->distance < b->distance;
    if (a->clip != b->clip) return a->clip < b->clip;
    return a->first_word < b->first_word;
  });
  SearchResult result;
  for (size_t rank = 0; rank < all.size() && rank < top; ++rank) {
    result.matches.push_back(*all[rank]);
    result.profiles.push_back(takes[all[rank]->clip].profile);
  }
  return result;
}

}  // namespace

Result<std::pair<uint64_t, uint64_t>> WordsWithin(const FrameFileReader& reader,
                                                  const LoadedWords& words, uint32_t clip,
                                                  uint64_t start, uint64_t end) {
  const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
  uint64_t first = UINT64_MAX;
  uint64_t last = 0;
  for (uint64_t word = 0; word < grid.word_count(); ++word) {
    const FrameSpan span = grid.SourceFrames(word);
    if (span.first >= start && span.end <= end) {
      first = std::min(first, word);
      last = word + 1;
    }
  }
  if (first == UINT64_MAX) {
    return Status::InvalidArgument(
        "frames [" + std::to_string(start) + ", " + std::to_string(end) + ") of clip " +
        reader.clips()[clip].name + " hold no whole motion word (a word reads " +
        std::to_string(grid.word_count() ? grid.SourceFrames(0).count() : 0) + " frames)");
  }
  return std::make_pair(first, last);
}

Result<SearchResult> SlidingWindowSearch(const FrameFileReader& reader, const LoadedWords& words,
                                         const WindowQuery& query, uint32_t top, int threads) {
  if (query.motifs.empty()) return Status::InvalidArgument("search: the query has no word");
  if (top == 0) return Status::InvalidOption("top", "must be at least 1");
  MOTIF_ASSIGN_OR_RETURN(std::vector<double> query_signature,
                         words.tf_idf->Signature(query.motifs));
  const uint64_t q = query.motifs.size();
  const size_t clips = words.signatures.clip_words.size();
  std::vector<TakeWindows> takes(clips);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, clips, 1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        EarthMoversDistance emd;
                        for (size_t clip = range.begin(); clip != range.end(); ++clip) {
                          SearchTake(reader, words, query, query_signature,
                                     static_cast<uint32_t>(clip), top, &emd, &takes[clip]);
                        }
                      });
  });
  uint64_t windows = 0;
  for (const TakeWindows& take : takes) {
    MOTIF_RETURN_IF_ERROR(take.status);
    windows += take.profile.size();
  }
  SearchResult result = Rank(takes, top);
  result.windows = windows;
  for (size_t clip = 0; clip < clips; ++clip) {
    const uint64_t m = words.signatures.clip_words[clip];
    if (m == 0) {
      result.wordless_clips.push_back(static_cast<uint32_t>(clip));
    } else if (m < q) {
      ++result.shorter_takes;
      result.shorter_clips.push_back(static_cast<uint32_t>(clip));
    }
  }
  return result;
}

Result<SearchResult> WholeTakeSearch(const FrameFileReader& reader, const LoadedWords& words,
                                     uint32_t query_clip, uint32_t top, int threads) {
  const size_t clips = words.signatures.clip_words.size();
  if (query_clip >= clips || words.signatures.clip_words[query_clip] == 0) {
    return Status::InvalidArgument(
        "search: clip " +
        (query_clip < clips ? reader.clips()[query_clip].name : std::to_string(query_clip)) +
        " has no motion word (shorter than one word)");
  }
  if (top == 0) return Status::InvalidOption("top", "must be at least 1");
  const std::vector<double> query = words.ClipSignature(query_clip, false);
  std::vector<TakeWindows> takes(clips);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, clips, 1), [&](const tbb::blocked_range<size_t>& range) {
          EarthMoversDistance emd;
          for (size_t clip = range.begin(); clip != range.end(); ++clip) {
            const uint64_t m = words.signatures.clip_words[clip];
            if (clip == query_clip || m == 0) continue;
            Result<double> distance =
                emd.Distance(query, words.ClipSignature(clip, false), words.ground);
            if (!distance.ok()) {
              takes[clip].status = distance.status();
              continue;
            }
            const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
            takes[clip].kept = {MatchOf(grid, static_cast<uint32_t>(clip), 0, m, *distance)};
            takes[clip].kept[0].whole_take = true;
            takes[clip].profile = {static_cast<float>(*distance)};
          }
        });
  });
  for (const TakeWindows& take : takes) MOTIF_RETURN_IF_ERROR(take.status);
  SearchResult result = Rank(takes, top);
  result.whole_take = true;
  result.windows = clips - 1;
  for (size_t clip = 0; clip < clips; ++clip) {
    if (words.signatures.clip_words[clip] == 0) {
      result.wordless_clips.push_back(static_cast<uint32_t>(clip));
    }
  }
  return result;
}

}  // namespace motif
