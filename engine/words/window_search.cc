#include "engine/words/window_search.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/word_stream.h"

namespace motif {
namespace {

struct TakeBest {
  double distance = std::numeric_limits<double>::infinity();
  uint64_t first_word = 0;
  std::vector<float> profile;
  Status status;
};

WindowMatch MatchOf(const FrameFileReader& reader, const LoadedWords& words, uint32_t clip,
                    uint64_t first_word, uint64_t count, double distance) {
  const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
  WindowMatch match;
  match.clip = clip;
  match.first_word = first_word;
  match.words = count;
  match.start_frame = grid.SourceFrames(first_word).first;
  match.end_frame = grid.SourceFrames(first_word + count - 1).end;
  match.distance = distance;
  return match;
}

// The `top` takes with the least distance (ties: lower clip), as matches with their profiles.
SearchResult Rank(const FrameFileReader& reader, const LoadedWords& words,
                  std::vector<TakeBest>& best, uint64_t window_words, uint32_t top) {
  std::vector<uint32_t> order;
  for (uint32_t clip = 0; clip < best.size(); ++clip) {
    if (best[clip].distance < std::numeric_limits<double>::infinity()) order.push_back(clip);
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return best[a].distance < best[b].distance || (best[a].distance == best[b].distance && a < b);
  });
  SearchResult result;
  for (size_t rank = 0; rank < order.size() && rank < top; ++rank) {
    const uint32_t clip = order[rank];
    const uint64_t count = window_words ? window_words : words.signatures.clip_words[clip];
    result.matches.push_back(
        MatchOf(reader, words, clip, best[clip].first_word, count, best[clip].distance));
    result.profiles.push_back(std::move(best[clip].profile));
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
  const uint32_t k = words.motifs.motif_count();
  if (query.motifs.empty()) return Status::InvalidArgument("search: the query has no word");
  if (top == 0) return Status::InvalidOption("top", "must be at least 1");
  MOTIF_ASSIGN_OR_RETURN(std::vector<double> query_signature,
                         words.tf_idf->Signature(query.motifs));
  const uint64_t q = query.motifs.size();
  const std::vector<double>& idf = words.tf_idf->idf();
  const size_t clips = words.signatures.clip_words.size();
  std::vector<TakeBest> best(clips);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, clips, 1), [&](const tbb::blocked_range<size_t>& range) {
          EarthMoversDistance emd;
          std::vector<uint32_t> counts(k);
          std::vector<double> signature(k);
          for (size_t clip = range.begin(); clip != range.end(); ++clip) {
            const uint64_t m = words.signatures.clip_words[clip];
            if (m < q) continue;
            const uint16_t* motifs = &words.signatures.word_motifs[words.clip_first_words[clip]];
            std::fill(counts.begin(), counts.end(), 0);
            for (uint64_t word = 0; word < q; ++word) ++counts[motifs[word]];
            TakeBest& take = best[clip];
            take.profile.assign(m - q + 1, std::numeric_limits<float>::quiet_NaN());
            for (uint64_t first = 0; first + q <= m; ++first) {
              if (first > 0) {
                --counts[motifs[first - 1]];
                ++counts[motifs[first + q - 1]];
              }
              const bool trivial = clip == query.exclude_clip && first < query.exclude_end_word &&
                                   first + q > query.exclude_first_word;
              if (trivial) continue;
              for (uint32_t motif = 0; motif < k; ++motif) {
                signature[motif] =
                    counts[motif] ? counts[motif] / static_cast<double>(q) * idf[motif] : 0.0;
              }
              Result<double> distance = emd.Distance(query_signature, signature, words.ground);
              if (!distance.ok()) {
                take.status = distance.status();
                break;
              }
              take.profile[first] = static_cast<float>(*distance);
              if (*distance < take.distance) {
                take.distance = *distance;
                take.first_word = first;
              }
            }
          }
        });
  });
  uint64_t windows = 0;
  for (const TakeBest& take : best) {
    MOTIF_RETURN_IF_ERROR(take.status);
    windows += take.profile.size();
  }
  SearchResult result = Rank(reader, words, best, q, top);
  result.windows = windows;
  for (size_t clip = 0; clip < clips; ++clip) {
    if (words.signatures.clip_words[clip] >= q) continue;
    ++result.shorter_takes;
    result.shorter_clips.push_back(static_cast<uint32_t>(clip));
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
  std::vector<TakeBest> best(clips);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, clips, 1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        EarthMoversDistance emd;
                        for (size_t clip = range.begin(); clip != range.end(); ++clip) {
                          if (clip == query_clip || words.signatures.clip_words[clip] == 0)
                            continue;
                          Result<double> distance =
                              emd.Distance(query, words.ClipSignature(clip, false), words.ground);
                          if (!distance.ok()) {
                            best[clip].status = distance.status();
                            continue;
                          }
                          best[clip].distance = *distance;
                          best[clip].profile = {static_cast<float>(*distance)};
                        }
                      });
  });
  for (const TakeBest& take : best) MOTIF_RETURN_IF_ERROR(take.status);
  SearchResult result = Rank(reader, words, best, 0, top);
  result.whole_take = true;
  result.windows = clips - 1;
  return result;
}

}  // namespace motif
