#include "engine/words/window_search.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "engine/words/word_model.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// Clip 0's frames [2000, 2400) copied into the middle of clip `target` at `at`.
struct CopyArchive {
  std::string path;
  uint32_t target = 0;
  uint64_t at = 0;
};

CopyArchive MakeCopyArchive(const TempDir& dir, const std::string& name, uint64_t at) {
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
  std::copy(clips[0].rows.begin() + 2000 * stride, clips[0].rows.begin() + 2400 * stride,
            clips[archive.target].rows.begin() + static_cast<std::ptrdiff_t>(at * stride));
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

  // A query longer than some takes: those are left out, and counted.
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
  EXPECT_EQ(long_query->matches.size(), clip_words.size() - shorter);
  // And named: exactly the clips with fewer words, in archive order.
  std::vector<uint32_t> expected;
  for (uint32_t clip = 0; clip < clip_words.size(); ++clip) {
    if (clip_words[clip] < longest) expected.push_back(clip);
  }
  EXPECT_EQ(long_query->shorter_clips, expected);
}

}  // namespace
}  // namespace motif::testing
