#include "engine/embedding/dtw_neighbours.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "engine/signature/word_distance.h"
#include "tests/engine/embedding/embedding_test_util.h"

namespace motif::testing {
namespace {

// Every pair: the k nearest non-trivial words of each word (ties: lower index).
std::vector<std::vector<WordNeighbour>> BruteForce(const WordPool& pool, uint32_t k) {
  const WordDistance distance(pool.joint_weights(), pool.word_frames(), 2);
  std::vector<std::vector<WordNeighbour>> result(pool.size());
  for (uint64_t word = 0; word < pool.size(); ++word) {
    std::vector<WordNeighbour> all;
    for (uint64_t other = 0; other < pool.size(); ++other) {
      if (pool.clip_of(other) == pool.clip_of(word)) {
        const int64_t gap = static_cast<int64_t>(pool.index_in_clip(other)) -
                            static_cast<int64_t>(pool.index_in_clip(word));
        if (std::abs(gap) < static_cast<int64_t>(pool.overlap_words())) continue;
      }
      all.push_back(
          {static_cast<uint32_t>(other),
           static_cast<float>(distance.Dtw(pool.features(word, 0), pool.features(other, 0)))});
    }
    std::sort(all.begin(), all.end(), [](const WordNeighbour& a, const WordNeighbour& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.word < b.word);
    });
    all.resize(std::min<size_t>(k, all.size()));
    result[word] = all;
  }
  return result;
}

TEST(DtwNeighbours, ExhaustiveSearchIsTheBruteForce) {
  const std::vector<ClipWords> clips = ClipWordsOf(MakeSynthClips(5000, 7));
  const WordPool pool = WordsOnlyPool(clips);
  DtwNeighbourOptions options;
  options.lists = 6;
  options.probes = 6;
  options.max_verified = 0;
  auto found = FindDtwNeighbours(pool, options);
  ASSERT_TRUE(found.ok()) << found.status().ToString();
  const auto expected = BruteForce(pool, options.k);
  ASSERT_EQ(found->size(), expected.size());
  for (uint64_t word = 0; word < pool.size(); ++word) {
    ASSERT_EQ((*found)[word], expected[word]) << "word " << word;
  }
}

TEST(DtwNeighbours, DefaultSearchFindsMostTrueNeighbours) {
  const std::vector<ClipWords> clips = ClipWordsOf(MakeSynthClips(20000, 9));
  const WordPool pool = WordsOnlyPool(clips);
  DtwNeighbourOptions options;
  options.threads = 2;
  auto found = FindDtwNeighbours(pool, options);
  ASSERT_TRUE(found.ok()) << found.status().ToString();
  const auto expected = BruteForce(pool, options.k);
  uint64_t hits = 0;
  uint64_t total = 0;
  for (uint64_t word = 0; word < pool.size(); ++word) {
    for (const WordNeighbour& truth : expected[word]) {
      ++total;
      for (const WordNeighbour& got : (*found)[word]) hits += got.word == truth.word;
    }
  }
  const double recall = static_cast<double>(hits) / static_cast<double>(total);
  RecordProperty("recall", std::to_string(recall));
  std::printf("DTW neighbour recall %.3f over %llu words\n", recall,
              static_cast<unsigned long long>(pool.size()));
  EXPECT_GT(recall, 0.85);
}

// Apart from the recall above, so that ThreadSanitizer runs this one on fewer words.
TEST(DtwNeighbours, DefaultSearchIsTheSameForAnyThreadCount) {
  const std::vector<ClipWords> clips = ClipWordsOf(MakeSynthClips(6000, 9));
  const WordPool pool = WordsOnlyPool(clips);
  DtwNeighbourOptions options;
  options.threads = 1;
  auto one = FindDtwNeighbours(pool, options);
  options.threads = 2;
  auto two = FindDtwNeighbours(pool, options);
  ASSERT_TRUE(one.ok() && two.ok());
  ASSERT_GT(pool.size(), 100u);
  EXPECT_EQ(*one, *two);
}

TEST(DtwNeighbours, RefusesZeroK) {
  const std::vector<ClipWords> clips = ClipWordsOf(MakeSynthClips(2000, 1));
  const WordPool pool = PoolOf(clips);
  DtwNeighbourOptions options;
  options.k = 0;
  EXPECT_TRUE(FindDtwNeighbours(pool, options).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif::testing
