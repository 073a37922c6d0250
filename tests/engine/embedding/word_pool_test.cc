#include "engine/embedding/word_pool.h"

#include <cstring>

#include <gtest/gtest.h>

#include "engine/embedding/word_input.h"
#include "tests/engine/embedding/embedding_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

bool SameFeatures(const WordPool& a, uint64_t word_a, uint32_t version_a, const WordPool& b,
                  uint64_t word_b, uint32_t version_b) {
  const size_t values = a.word_frames() * 4 * a.weighted_joints();
  const size_t root = a.word_frames() * kRootMotionChannels;
  return std::memcmp(a.features(word_a, version_a), b.features(word_b, version_b),
                     values * sizeof(int16_t)) == 0 &&
         std::memcmp(a.root_motion(word_a, version_a), b.root_motion(word_b, version_b),
                     root * sizeof(float)) == 0;
}

TEST(WordPool, HoldsEveryWordAndReproducibleWarpedCopies) {
  const SynthClips synth = MakeSynthClips(6000, 3);
  const std::vector<ClipWords> clips = ClipWordsOf(synth);
  WordPoolOptions options;
  options.warp_copies = 2;
  options.held_out_fraction = 0.25;
  const WordPool pool = PoolOf(clips, options);
  uint64_t words = 0;
  for (const ClipWords& clip : clips) words += clip.word_count();
  ASSERT_EQ(pool.size(), words);
  EXPECT_EQ(pool.versions(), 3u);
  EXPECT_EQ(pool.overlap_words(), 4u);
  // Version 0 is the word, byte for byte.
  uint64_t word = 0;
  size_t copies_differing = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    WordBatch batch;
    clips[clip_idx].AllWords(&batch);
    for (size_t idx = 0; idx < batch.size(); ++idx, ++word) {
      EXPECT_EQ(pool.clip_of(word), clip_idx);
      EXPECT_EQ(pool.index_in_clip(word), idx);
      ASSERT_EQ(std::memcmp(pool.features(word, 0), batch.word(idx),
                            batch.word_values() * sizeof(int16_t)),
                0);
      copies_differing += !SameFeatures(pool, word, 0, pool, word, 1);
    }
  }
  EXPECT_GT(copies_differing, words * 9 / 10);
  // Same seed, same copies; another seed, other copies.
  const WordPool again = PoolOf(clips, options);
  options.seed = 2;
  const WordPool other = PoolOf(clips, options);
  size_t other_differing = 0;
  for (uint64_t idx = 0; idx < pool.size(); ++idx) {
    ASSERT_TRUE(SameFeatures(pool, idx, 1, again, idx, 1));
    ASSERT_TRUE(SameFeatures(pool, idx, 0, other, idx, 0));
    other_differing += !SameFeatures(pool, idx, 1, other, idx, 1);
  }
  EXPECT_GT(other_differing, words * 9 / 10);
  // A quarter of the clips held out.
  size_t held = 0;
  for (const PoolClip& clip : pool.clips()) held += clip.held_out;
  EXPECT_EQ(held, static_cast<size_t>(std::llround(0.25 * clips.size())));
}

TEST(WordPool, FromAnArchiveEqualsFromTheClipsAndKeepsToTheBudget) {
  const SynthClips synth = MakeSynthClips(6000, 5);
  TempDir dir;
  const std::string path = dir.File("a.mfs");
  WriteClips(path, synth.skeleton, synth.clips, 120.0);
  auto reader = OpenArchive(path);
  ASSERT_NE(reader, nullptr);
  // The archive stores quantised rows: the reference reads the clips back from it.
  std::vector<ClipWords> clips;
  for (size_t clip = 0; clip < reader->clips().size(); ++clip) {
    auto words = ClipWords::Read(*reader, clip, JointWeightsOf(synth.skeleton));
    ASSERT_TRUE(words.ok()) << words.status().ToString();
    clips.push_back(std::move(*words));
  }
  WordPoolOptions options;
  options.threads = 2;
  const WordPool direct = PoolOf(clips, options);
  auto built = WordPool::Build(*reader, JointWeightsOf(synth.skeleton), options);
  ASSERT_TRUE(built.ok()) << built.status().ToString();
  ASSERT_EQ(built->size(), direct.size());
  for (uint64_t word = 0; word < direct.size(); ++word) {
    for (uint32_t version = 0; version < direct.versions(); ++version) {
      ASSERT_TRUE(SameFeatures(*built, word, version, direct, word, version)) << word;
    }
  }
  // A budget below the archive's words: exactly the budget, whole clips but maybe the last.
  options.max_words = direct.size() / 3;
  auto small = WordPool::Build(*reader, JointWeightsOf(synth.skeleton), options);
  ASSERT_TRUE(small.ok()) << small.status().ToString();
  EXPECT_EQ(small->size(), options.max_words);
  size_t cut = 0;
  for (const PoolClip& clip : small->clips()) {
    cut += clip.word_count < clips[clip.archive_clip].word_count();
    // The pool's words are the clip's first ones, with the archive's ids.
    const uint64_t first = clip.first_word;
    EXPECT_TRUE(
        SameFeatures(*small, first, 1, direct, direct.clips()[clip.archive_clip].first_word, 1));
  }
  EXPECT_LE(cut, 1u);
  options.threads = 1;
  auto serial = WordPool::Build(*reader, JointWeightsOf(synth.skeleton), options);
  ASSERT_TRUE(serial.ok());
  ASSERT_EQ(serial->size(), small->size());
  for (uint64_t word = 0; word < small->size(); ++word) {
    ASSERT_TRUE(SameFeatures(*serial, word, 2, *small, word, 2));
  }
}

TEST(WordPool, RefusesBadOptions) {
  WordPoolOptions options;
  options.max_words = 0;
  EXPECT_TRUE(ValidateWordPoolOptions(options).IsInvalidArgument());
  options = {};
  options.held_out_fraction = 1.0;
  EXPECT_TRUE(ValidateWordPoolOptions(options).IsInvalidArgument());
  options = {};
  options.words.word_frames = 0;
  EXPECT_TRUE(ValidateWordPoolOptions(options).IsInvalidArgument());
  EXPECT_TRUE(WordPool::FromClips({}, WordPoolOptions{}).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif::testing
