#include "engine/words/window_search.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/word_stream.h"
#include "engine/words/range_query.h"
#include "engine/words/word_model.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// Clip 0's frames [2000, 2400) copied into the middle of clip `target` at `at` (and at each of
// `more`).
struct CopyArchive {
  std::string path;
  uint32_t target = 0;
  uint64_t at = 0;
};

CopyArchive MakeCopyArchive(const TempDir& dir, const std::string& name, uint64_t at,
                            const std::vector<uint64_t>& more = {}) {
  SynthOptions options;
  options.frames = 15000;
  options.seed = 23;
  options.motifs = 0;
  options.clip_seconds_min = 25;
  options.clip_seconds_max = 30;
  options.threads = 1;
  // Background that does not repeat, so the copy is the only repeat of the query.
  options.background_variation_degrees = kRecommendedBackgroundVariation;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok());
  std::vector<ClipFrames> clips;
  EXPECT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) {
                    clips.push_back(clip);
                    return Status::Ok();
                  })
                  .ok());
  const FrameLayout layout{static_cast<uint32_t>((*synthesizer)->skeleton().joint_count())};
  const size_t stride = layout.stride();
  CopyArchive archive;
  archive.path = dir.File(name);
  archive.target = static_cast<uint32_t>(clips.size() - 2);
  archive.at = at;
  std::vector<uint64_t> positions = more;
  positions.push_back(at);
  for (uint64_t position : positions) {
    std::copy(clips[0].rows.begin() + 2000 * stride, clips[0].rows.begin() + 2400 * stride,
              clips[archive.target].rows.begin() + static_cast<std::ptrdiff_t>(position * stride));
  }
  WriteClips(archive.path, (*synthesizer)->skeleton(), clips, 120.0);
  return archive;
}

TEST(WindowSearch, FindsACopyOfTheQueryInsertedInAnotherTake) {
  TempDir dir;
  // At 1000 the copy's words fall on the grid as the query's (1000 and 2000 are multiples of the
  // 20 source frames between words): identical words, EMD 0. At 1010 they are half a word step
  // out of phase: other words, found by their embedding.
  for (uint64_t at : {uint64_t{1000}, uint64_t{1010}}) {
    const CopyArchive archive = MakeCopyArchive(dir, "copy" + std::to_string(at) + ".mfs", at);
    const WordsPaths paths = DefaultWordsPaths(archive.path);
    WordsOptions options = SmallWordsOptions(40);
    options.train.epochs = 6;
    ASSERT_TRUE(BuildWords(archive.path, paths, options).ok());
    auto reader = OpenArchive(archive.path);
    auto words = LoadWords(*reader, paths, false);
    ASSERT_TRUE(words.ok()) << words.status().ToString();
    auto range = WordsWithin(*reader, *words, 0, 2000, 2400);
    ASSERT_TRUE(range.ok());
    EXPECT_EQ(range->first, 100u);  // word w reads frames [20 w, 20 w + 76)
    EXPECT_EQ(range->second, 117u);
    WindowQuery query;
    const std::vector<uint32_t> motifs = words->ClipMotifs(0);
    query.motifs.assign(motifs.begin() + 100, motifs.begin() + 117);
    query.exclude_clip = 0;
    query.exclude_first_word = 100;
    query.exclude_end_word = 117;
    auto one = SlidingWindowSearch(*reader, *words, query, 5, 1);
    auto two = SlidingWindowSearch(*reader, *words, query, 5, 2);
    ASSERT_TRUE(one.ok() && two.ok());
    ASSERT_FALSE(one->matches.empty());
    const WindowMatch& best = one->matches[0];
    EXPECT_EQ(best.clip, archive.target) << "copy at " << at;
    EXPECT_LT(std::max(best.start_frame, at), std::min(best.end_frame, at + 400))
        << "the match [" << best.start_frame << ", " << best.end_frame << ") misses the copy";
    if (at == 1000) {
      EXPECT_EQ(best.distance, 0.0);
      EXPECT_EQ(best.start_frame, 1000u);
    }
    if (one->matches.size() > 1) {
      EXPECT_GT(one->matches[1].distance, best.distance);
    }
    ASSERT_EQ(one->matches.size(), two->matches.size());
    for (size_t rank = 0; rank < one->matches.size(); ++rank) {
      EXPECT_EQ(one->matches[rank].clip, two->matches[rank].clip);
      EXPECT_EQ(one->matches[rank].distance, two->matches[rank].distance);
    }
    // The query's own windows are left out.
    for (const WindowMatch& match : one->matches) {
      if (match.clip == 0) {
        EXPECT_TRUE(match.first_word + 17 <= 100 || match.first_word >= 117);
      }
    }
  }
}

TEST(WindowSearch, WholeTakesAndErrors) {
  TempDir dir;
  const CopyArchive archive = MakeCopyArchive(dir, "copy.mfs", 1000);
  const WordsPaths paths = DefaultWordsPaths(archive.path);
  ASSERT_TRUE(BuildWords(archive.path, paths, SmallWordsOptions()).ok());
  auto reader = OpenArchive(archive.path);
  auto words = LoadWords(*reader, paths, false);
  ASSERT_TRUE(words.ok());
  auto whole = WholeTakeSearch(*reader, *words, 1, 100, 2);
  ASSERT_TRUE(whole.ok());
  EXPECT_TRUE(whole->whole_take);
  EXPECT_EQ(whole->matches.size(), reader->clips().size() - 1);
  for (size_t rank = 1; rank < whole->matches.size(); ++rank) {
    EXPECT_NE(whole->matches[rank].clip, 1u);
    EXPECT_LE(whole->matches[rank - 1].distance, whole->matches[rank].distance);
  }
  EXPECT_TRUE(WordsWithin(*reader, *words, 0, 100, 150).status().IsInvalidArgument());
  EXPECT_TRUE(
      SlidingWindowSearch(*reader, *words, WindowQuery{}, 5, 1).status().IsInvalidArgument());
  WindowQuery bad;
  bad.motifs = {9999};
  EXPECT_TRUE(SlidingWindowSearch(*reader, *words, bad, 5, 1).status().IsInvalidArgument());

  // A query longer than some takes: those are compared whole (one window of all their words),
  // counted and named; the longest take has exactly one window.
  const std::vector<uint64_t>& clip_words = words->signatures.clip_words;
  const uint64_t longest = *std::max_element(clip_words.begin(), clip_words.end());
  WindowQuery longest_query;
  longest_query.motifs.assign(longest, 0);
  auto long_query = SlidingWindowSearch(*reader, *words, longest_query, 100, 1);
  ASSERT_TRUE(long_query.ok()) << long_query.status().ToString();
  const uint64_t shorter = static_cast<uint64_t>(std::count_if(
      clip_words.begin(), clip_words.end(), [&](uint64_t count) { return count < longest; }));
  EXPECT_GT(shorter, 0u);
  EXPECT_EQ(long_query->shorter_takes, shorter);
  EXPECT_EQ(long_query->windows, clip_words.size());
  ASSERT_EQ(long_query->matches.size(), clip_words.size()) << "every take, one window each";
  for (const WindowMatch& match : long_query->matches) {
    const bool is_shorter = clip_words[match.clip] < longest;
    EXPECT_EQ(match.whole_take, is_shorter) << match.clip;
    EXPECT_EQ(match.first_word, 0u);
    EXPECT_EQ(match.words, clip_words[match.clip]);
    EXPECT_EQ(match.start_frame, 0u);
    EXPECT_EQ(match.rank_in_take, 1u);
    // A whole take's signature against the query's: the same EMD computed directly.
    auto signature = words->tf_idf->Signature(words->ClipMotifs(match.clip));
    auto query_signature = words->tf_idf->Signature(longest_query.motifs);
    ASSERT_TRUE(signature.ok() && query_signature.ok());
    EarthMoversDistance emd;
    auto expected = emd.Distance(*query_signature, *signature, words->ground);
    ASSERT_TRUE(expected.ok());
    EXPECT_NEAR(match.distance, *expected, 1e-9) << match.clip;
  }
  // And named: exactly the clips with fewer words, in archive order.
  std::vector<uint32_t> expected;
  for (uint32_t clip = 0; clip < clip_words.size(); ++clip) {
    if (clip_words[clip] < longest) expected.push_back(clip);
  }
  EXPECT_EQ(long_query->shorter_clips, expected);
  EXPECT_TRUE(long_query->wordless_clips.empty());
}

// The greedy choice made again the slow way from a take's profile: the best window (ties: the
// earliest), then the best sharing no frame with any kept one, ...
std::vector<uint64_t> ReferenceGreedy(const std::vector<float>& profile, const WordGrid& grid,
                                      uint64_t q, size_t top) {
  std::vector<uint64_t> kept;
  while (kept.size() < top) {
    uint64_t best = UINT64_MAX;
    for (uint64_t first = 0; first < profile.size(); ++first) {
      if (std::isnan(profile[first])) continue;
      const uint64_t start = grid.SourceFrames(first).first;
      const uint64_t end = grid.SourceFrames(first + q - 1).end;
      bool overlaps = false;
      for (uint64_t other : kept) {
        overlaps |=
            start < grid.SourceFrames(other + q - 1).end && grid.SourceFrames(other).first < end;
      }
      if (!overlaps && (best == UINT64_MAX || profile[first] < profile[best])) best = first;
    }
    if (best == UINT64_MAX) break;
    kept.push_back(best);
  }
  return kept;
}

// Two copies of the query in one take: both found, as that take's first and second windows;
// several windows a take, none overlapping another of its take or the query.
TEST(WindowSearch, KeepsSeveralWindowsOfATakeNoneOverlapping) {
  TempDir dir;
  const CopyArchive archive = MakeCopyArchive(dir, "twice.mfs", 1000, {2200});
  const WordsPaths paths = DefaultWordsPaths(archive.path);
  ASSERT_TRUE(BuildWords(archive.path, paths, SmallWordsOptions(40)).ok());
  auto reader = OpenArchive(archive.path);
  auto words = LoadWords(*reader, paths, false);
  ASSERT_TRUE(words.ok()) << words.status().ToString();
  auto range = RangeQueryWords(*reader, *words, 0, 2000, 2400);
  ASSERT_TRUE(range.ok());
  EXPECT_FALSE(range->padded);
  const WindowQuery query = ToWindowQuery(*range, *words);
  EXPECT_EQ(query.exclude_start_frame, 2000u);
  EXPECT_EQ(query.exclude_end_frame, 2400u);  // words [100, 117) read [2000, 2396)
  const uint32_t top = 20;                    // of 27 non-overlapping windows in all
  auto result = SlidingWindowSearch(*reader, *words, query, top, 2);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_EQ(result->matches.size(), top);
  // The copies, grid-aligned: identical words, EMD 0, the earlier first.
  EXPECT_EQ(result->matches[0].clip, archive.target);
  EXPECT_EQ(result->matches[0].start_frame, 1000u);
  EXPECT_EQ(result->matches[0].distance, 0.0);
  EXPECT_EQ(result->matches[0].rank_in_take, 1u);
  EXPECT_EQ(result->matches[1].clip, archive.target);
  EXPECT_EQ(result->matches[1].start_frame, 2200u);
  EXPECT_EQ(result->matches[1].distance, 0.0);
  EXPECT_EQ(result->matches[1].rank_in_take, 2u);
  std::map<uint32_t, std::vector<const WindowMatch*>> by_take;
  for (size_t rank = 0; rank < result->matches.size(); ++rank) {
    const WindowMatch& match = result->matches[rank];
    if (rank > 0) {
      EXPECT_LE(result->matches[rank - 1].distance, match.distance);
    }
    EXPECT_FALSE(match.clip == 0 && WindowsOverlap(match.start_frame, match.end_frame, 2000, 2400))
        << "the query found itself: [" << match.start_frame << ", " << match.end_frame << ")";
    by_take[match.clip].push_back(&match);
  }
  size_t takes_with_several = 0;
  for (const auto& [clip, matches] : by_take) {
    takes_with_several += matches.size() > 1;
    const WordGrid grid = ClipWordGrid(*reader, clip, words->signatures.words);
    const size_t at = static_cast<size_t>(
        std::find_if(result->matches.begin(), result->matches.end(),
                     [&](const WindowMatch& match) { return match.clip == clip; }) -
        result->matches.begin());
    const std::vector<uint64_t> expected =
        ReferenceGreedy(result->profiles[at], grid, query.motifs.size(), matches.size());
    ASSERT_EQ(expected.size(), matches.size()) << clip;
    for (size_t idx = 0; idx < matches.size(); ++idx) {
      EXPECT_EQ(matches[idx]->rank_in_take, idx + 1);
      EXPECT_EQ(matches[idx]->first_word, expected[idx]) << "clip " << clip << " #" << idx + 1;
      for (size_t other = 0; other < idx; ++other) {
        EXPECT_FALSE(WindowsOverlap(matches[idx]->start_frame, matches[idx]->end_frame,
                                    matches[other]->start_frame, matches[other]->end_frame));
      }
    }
  }
  EXPECT_GT(takes_with_several, 1u);
  // The query's own clip: its windows reading any query frame have no distance in the profile.
  const WordGrid grid0 = ClipWordGrid(*reader, 0, words->signatures.words);
  const size_t own =
      static_cast<size_t>(std::find_if(result->matches.begin(), result->matches.end(),
                                       [](const WindowMatch& match) { return match.clip == 0; }) -
                          result->matches.begin());
  ASSERT_LT(own, result->matches.size()) << "clip 0's other windows are searched";
  const std::vector<float>& profile = result->profiles[own];
  for (uint64_t first = 0; first < profile.size(); ++first) {
    const bool reads_query = WindowsOverlap(grid0.SourceFrames(first).first,
                                            grid0.SourceFrames(first + 16).end, 2000, 2400);
    EXPECT_EQ(std::isnan(profile[first]), reads_query) << "window " << first;
  }

  // A range shorter than one word (76 frames): the word centred on it.
  auto short_range = RangeQueryWords(*reader, *words, 0, 2000, 2064);
  ASSERT_TRUE(short_range.ok());
  EXPECT_TRUE(short_range->padded);
  EXPECT_EQ(short_range->one_word_frames, 76u);
  EXPECT_EQ(short_range->first_word, 100u);  // centre 2032; word 100 [2000, 2076) centre 2038
  EXPECT_EQ(short_range->end_word, 101u);
  EXPECT_EQ(short_range->word_frames, (FrameSpan{2000, 2076}));
  const WindowQuery short_query = ToWindowQuery(*short_range, *words);
  EXPECT_EQ(short_query.motifs.size(), 1u);
  EXPECT_EQ(short_query.exclude_start_frame, 2000u);
  EXPECT_EQ(short_query.exclude_end_frame, 2076u);
  auto short_result = SlidingWindowSearch(*reader, *words, short_query, 5, 1);
  ASSERT_TRUE(short_result.ok());
  for (const WindowMatch& match : short_result->matches) {
    EXPECT_EQ(match.words, 1u);
    EXPECT_FALSE(match.clip == 0 && WindowsOverlap(match.start_frame, match.end_frame, 2000, 2076));
  }
  // At least one word long but off the grid: the words within it give or take half a hop (10).
  auto off_grid = RangeQueryWords(*reader, *words, 0, 2010, 2090);
  ASSERT_TRUE(off_grid.ok());
  EXPECT_FALSE(off_grid->padded);
  EXPECT_EQ(off_grid->first_word, 100u);
  EXPECT_EQ(off_grid->end_word, 102u);  // [2000, 2076) and [2020, 2096)
  EXPECT_TRUE(RangeQueryWords(*reader, *words, 0, 10, 10).status().IsInvalidArgument());
  EXPECT_TRUE(RangeQueryWords(*reader, *words, 0, 0, reader->clips()[0].frame_count + 1)
                  .status()
                  .IsInvalidArgument());
}

}  // namespace
}  // namespace motif::testing
