#include "engine/words/word_bags.h"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "engine/signature/frame_resampler.h"
#include "engine/signature/word_stream.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// Two motion classes, two clips each, 3 s at 120 fps: 15 words a clip (72 samples at 24 Hz).
class WordBagsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ClassClips classes = MakeClassClips(2, 2, 3.0, 7);
    path_ = dir_.File("bags.mfs");
    WriteClips(path_, classes.skeleton, classes.clips, 120.0);
    reader_ = OpenArchive(path_);
    auto weights = LoadDistanceWeights(reader_->skeleton(), "");
    ASSERT_TRUE(weights.ok());
    weights_ = *weights;
    auto resampler = FrameResampler::Create(reader_->layout(), weights_);
    ASSERT_TRUE(resampler.ok());
    distance_ = std::make_unique<WordDistance>(resampler->weights(), words_.word_frames);
  }

  WordsOfClips Read(const std::vector<uint32_t>& clips) const {
    auto read = WordsOfClips::Read(*reader_, weights_, words_, *distance_, clips);
    EXPECT_TRUE(read.ok()) << read.status().ToString();
    return std::move(read.value());
  }

  TempDir dir_;
  std::string path_;
  std::unique_ptr<FrameFileReader> reader_;
  std::vector<float> weights_;
  WordOptions words_;
  std::unique_ptr<WordDistance> distance_;
};

TEST_F(WordBagsTest, WordsOfClipsHoldsTheWordsOfTheClipsInTheOrderGiven) {
  const uint64_t per_clip = ClipWordGrid(*reader_, 0, words_).word_count();
  ASSERT_EQ(per_clip, 15u);
  const WordsOfClips words = Read({3, 1});
  EXPECT_EQ(words.size(), 2 * per_clip);
  EXPECT_EQ(words.index(3, 0), 0u);
  EXPECT_EQ(words.index(1, 0), per_clip);
  EXPECT_EQ(words.index(1, 4), per_clip + 4);
  // Each is the word the archive's stream gives: at DTW 0 from it, and not from its neighbour.
  WordStreamOptions options;
  options.words = words_;
  auto stream = WordStream::Create(*reader_, weights_, options);
  ASSERT_TRUE(stream.ok());
  WordBatch batch;
  while (*(*stream)->Next(&batch)) {
    for (size_t w = 0; w < batch.size(); ++w) {
      const WordInfo& info = batch.info(w);
      if (info.clip_idx != 1 && info.clip_idx != 3) continue;
      PreparedWord expected;
      distance_->Prepare(batch.word(w), &expected);
      EXPECT_EQ(distance_->Dtw(words.word(info.clip_idx, info.word_idx), expected), 0.0);
      // A neighbour 4 samples away, never a whole period of these motions (20 or 30 samples).
      const uint64_t other = info.word_idx + 1 < per_clip ? info.word_idx + 1 : info.word_idx - 1;
      EXPECT_GT(distance_->Dtw(words.word(info.clip_idx, other), expected), 0.0);
    }
  }
  EXPECT_FALSE(WordsOfClips::Read(*reader_, weights_, words_, *distance_, {4}).ok());
}

TEST_F(WordBagsTest, TheGroundIsTheWordDtwForAnyThreadCount) {
  const WordsOfClips queries = Read({0});
  const WordsOfClips references = Read({1, 2});
  const WordBagGround one = WordBagGround::Compute(queries, 0, 2, 9, references, *distance_, 1);
  const WordBagGround two = WordBagGround::Compute(queries, 0, 2, 9, references, *distance_, 2);
  for (uint64_t word = 2; word < 9; ++word) {
    for (uint64_t reference = 0; reference < references.size(); ++reference) {
      const double dtw = distance_->Dtw(queries.word(0, word), references.at(reference));
      EXPECT_EQ(one.at(word, reference), static_cast<float>(dtw));
      EXPECT_EQ(two.at(word, reference), one.at(word, reference));
    }
  }
}

// With unit masses and windows of n words each, the EMD is the least mean cost of a one-to-one
// matching of the words: checked against every permutation.
TEST_F(WordBagsTest, TheDistanceIsTheMeanCostOfTheCheapestMatchingOfTheWords) {
  const WordsOfClips queries = Read({0});
  const WordsOfClips references = Read({1, 2, 3});
  const WordBagGround ground = WordBagGround::Compute(queries, 0, 0, 11, references, *distance_, 2);
  WordBagDistance bags;
  int checked = 0;
  for (const uint32_t clip : {1u, 2u, 3u}) {
    for (const uint64_t query_first : {0u, 3u, 6u}) {
      for (const uint64_t reference_first : {0u, 2u, 7u}) {
        std::vector<int> order(4);
        std::iota(order.begin(), order.end(), 0);
        double best = std::numeric_limits<double>::infinity();
        do {
          double sum = 0;
          for (int a = 0; a < 4; ++a) {
            sum += ground.at(query_first + a, references.index(clip, reference_first + order[a]));
          }
          best = std::min(best, sum / 4);
        } while (std::next_permutation(order.begin(), order.end()));
        auto emd = bags.Distance(ground, query_first, query_first + 4, references, clip,
                                 reference_first, reference_first + 4);
        ASSERT_TRUE(emd.ok());
        EXPECT_NEAR(*emd, best, 1e-9 * std::max(1.0, best));
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 27);
}

TEST_F(WordBagsTest, AWindowIsAtZeroFromItselfAndNearerToItsClassThanToTheOther) {
  // Clips 0 and 2 are class 0, clips 1 and 3 class 1 (MakeClassClips alternates).
  const WordsOfClips queries = Read({0});
  const WordsOfClips references = Read({0, 1, 2});
  const WordBagGround ground = WordBagGround::Compute(queries, 0, 0, 11, references, *distance_, 2);
  WordBagDistance bags;
  auto self = bags.Distance(ground, 1, 10, references, 0, 1, 10);
  ASSERT_TRUE(self.ok());
  EXPECT_EQ(*self, 0.0);
  auto same = bags.Distance(ground, 1, 10, references, 2, 1, 10);
  auto other = bags.Distance(ground, 1, 10, references, 1, 1, 10);
  ASSERT_TRUE(same.ok() && other.ok());
  EXPECT_LT(*same, *other);
  EXPECT_FALSE(bags.Distance(ground, 3, 3, references, 1, 0, 4).ok());
}

}  // namespace
}  // namespace motif::testing
