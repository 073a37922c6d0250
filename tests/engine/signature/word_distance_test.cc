// WordDistance: DTW with a Sakoe-Chiba band under the trellis's pose distance. Band 0 is the
// lock-step sum; a word against itself shifted by one frame costs less than lock-step; symmetry;
// a plain full-matrix reference for every band; early abandoning never changes a result below
// its threshold; and on a real CMU take, adjacent words are nearer than words far apart.
#include "engine/signature/word_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/distance/pose_features.h"
#include "engine/signature/clip_words.h"
#include "engine/signature/word_stream.h"
#include "formats/import/take_importer.h"
#include "tests/engine/signature/word_test_util.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The resampled frames of one synthetic clip as features, so words at any sample offset can be
// cut out of it (word k = frames [k, k + 16)).
class WordDistanceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const testing::SynthClips synth = testing::MakeSynthClips(6000, 31);
    const ClipWords words = testing::WordsOfClip(testing::LongestClip(synth), synth.skeleton);
    const std::vector<float> rows = words.ResampledRows();
    const size_t stride = words.resampler().layout().stride();
    values_ = words.resampler().feature_values();
    samples_ = words.grid().sample_count();
    features_ = new std::vector<int16_t>(samples_ * values_);
    for (uint64_t sample = 0; sample < samples_; ++sample) {
      words.resampler().RowFeatures(&rows[sample * stride], &(*features_)[sample * values_]);
    }
    weights_ = new std::vector<float>(words.resampler().weights());
  }
  static void TearDownTestSuite() {
    delete features_;
    delete weights_;
  }
  // The word starting at resampled frame `sample`.
  static const int16_t* Word(uint64_t sample) { return &(*features_)[sample * values_]; }
  static uint64_t word_starts() { return samples_ - 16 + 1; }

  static std::vector<int16_t>* features_;
  static std::vector<float>* weights_;
  static size_t values_;
  static uint64_t samples_;
};
std::vector<int16_t>* WordDistanceTest::features_ = nullptr;
std::vector<float>* WordDistanceTest::weights_ = nullptr;
size_t WordDistanceTest::values_ = 0;
uint64_t WordDistanceTest::samples_ = 0;

// Full-matrix DTW with a band, written as plainly as possible.
double ReferenceDtw(const WordDistance& distance, const int16_t* a, const int16_t* b,
                    uint32_t band) {
  const int n = static_cast<int>(distance.word_frames());
  const size_t values = distance.feature_values();
  std::vector<std::vector<double>> cost(n, std::vector<double>(n, kInfinity));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (std::abs(i - j) > static_cast<int>(band)) continue;
      const double d = distance.FrameDistance(a + i * values, b + j * values);
      if (i == 0 && j == 0) {
        cost[i][j] = d;
        continue;
      }
      double best = kInfinity;
      if (i > 0) best = std::min(best, cost[i - 1][j]);
      if (j > 0) best = std::min(best, cost[i][j - 1]);
      if (i > 0 && j > 0) best = std::min(best, cost[i - 1][j - 1]);
      cost[i][j] = d + best;
    }
  }
  return cost[n - 1][n - 1];
}

TEST_F(WordDistanceTest, BandZeroIsTheLockStepSum) {
  const WordDistance lock_step(*weights_, 16, 0);
  ASSERT_GT(word_starts(), 100u);
  for (uint64_t a = 0; a < word_starts(); a += 5) {
    for (uint64_t b = 0; b < word_starts(); b += 17) {
      double sum = 0;
      for (uint32_t frame = 0; frame < 16; ++frame) {
        sum += lock_step.FrameDistance(Word(a) + frame * values_, Word(b) + frame * values_);
      }
      ASSERT_EQ(lock_step.Dtw(Word(a), Word(b)), sum) << a << " " << b;
      ASSERT_EQ(lock_step.LockStep(Word(a), Word(b)), sum);
    }
  }
}

TEST_F(WordDistanceTest, AWordShiftedByOneFrameCostsLessThanLockStep) {
  const WordDistance distance(*weights_, 16);  // band 2
  for (uint64_t a = 0; a + 1 < word_starts(); ++a) {
    const double dtw = distance.Dtw(Word(a), Word(a + 1));
    const double lock_step = distance.LockStep(Word(a), Word(a + 1));
    if (lock_step > 0) {  // strictly, unless the motion stops
      ASSERT_LT(dtw, lock_step) << a;
    }
    // The path (0,0), (1,0), (2,1), ..., (15,14), (15,15) pairs 14 identical frames: only the
    // two corners cost anything.
    const double corners =
        static_cast<double>(distance.FrameDistance(Word(a), Word(a + 1))) +
        distance.FrameDistance(Word(a) + 15 * values_, Word(a + 1) + 15 * values_);
    ASSERT_LE(dtw, corners) << a;
  }
}

TEST_F(WordDistanceTest, IsSymmetricAndZeroOnItself) {
  for (uint32_t band : {0u, 1u, 2u, 4u, 15u}) {
    const WordDistance distance(*weights_, 16, band);
    for (uint64_t a = 0; a < word_starts(); a += 7) {
      EXPECT_EQ(distance.Dtw(Word(a), Word(a)), 0.0);
      for (uint64_t b = a + 3; b < word_starts(); b += 23) {
        ASSERT_EQ(distance.Dtw(Word(a), Word(b)), distance.Dtw(Word(b), Word(a)))
            << band << " " << a << " " << b;
      }
    }
  }
}

TEST_F(WordDistanceTest, MatchesAFullMatrixReferenceForEveryBand) {
  for (uint32_t band = 0; band <= 16; ++band) {
    const WordDistance distance(*weights_, 16, band);
    double previous_total = kInfinity;
    double total = 0;
    for (uint64_t a = 0; a < word_starts(); a += 11) {
      for (uint64_t b = 1; b < word_starts(); b += 13) {
        const double expected = ReferenceDtw(distance, Word(a), Word(b), band);
        ASSERT_EQ(distance.Dtw(Word(a), Word(b)), expected) << band << " " << a << " " << b;
        total += expected;
      }
    }
    EXPECT_LE(total, previous_total) << "a wider band never costs more";
    previous_total = total;
  }
}

TEST_F(WordDistanceTest, EarlyAbandoningNeverChangesTheResultBelowTheThreshold) {
  const WordDistance distance(*weights_, 16);
  uint64_t abandoned = 0;
  uint64_t calls = 0;
  for (uint64_t a = 0; a < word_starts(); a += 3) {
    for (uint64_t b = 0; b < word_starts(); b += 19) {
      const double exact = distance.Dtw(Word(a), Word(b));
      for (double fraction : {0.0, 0.1, 0.5, 0.9, 0.999, 1.0, 1.001, 2.0}) {
        const double threshold = exact * fraction;
        const double bounded = distance.Dtw(Word(a), Word(b), threshold);
        ++calls;
        if (exact <= threshold) {
          ASSERT_EQ(bounded, exact) << a << " " << b << " x" << fraction;
        } else {
          ASSERT_TRUE(bounded == kInfinity || bounded == exact) << a << " " << b;
          abandoned += bounded == kInfinity;
        }
      }
      ASSERT_EQ(distance.Dtw(Word(a), Word(b), kInfinity), exact);
    }
  }
  EXPECT_GT(abandoned, calls / 4) << "thresholds well below the result are abandoned";
}

TEST_F(WordDistanceTest, PreparedWordsGiveTheSameBits) {
  for (uint32_t band : {0u, 2u, 15u}) {
    const WordDistance distance(*weights_, 16, band);
    PreparedWord a;
    PreparedWord b;
    for (uint64_t first = 0; first < word_starts(); first += 9) {
      distance.Prepare(Word(first), &a);  // reused: prepared over and over
      for (uint64_t second = 2; second < word_starts(); second += 31) {
        distance.Prepare(Word(second), &b);
        const double raw = distance.Dtw(Word(first), Word(second));
        ASSERT_EQ(distance.Dtw(a, b), raw) << band << " " << first << " " << second;
        ASSERT_EQ(distance.Dtw(a, b, 0.5 * raw),
                  distance.Dtw(Word(first), Word(second), 0.5 * raw));
      }
    }
  }
}

TEST_F(WordDistanceTest, OtherWordLengths) {
  // W = 5 and W = 40 (more cells than one run of SIMD lanes, lengths not a multiple of it).
  for (uint32_t frames : {5u, 40u}) {
    for (uint32_t band : {0u, 1u, 3u, 100u}) {
      const WordDistance distance(*weights_, frames, band);
      for (uint64_t a = 0; a + frames <= samples_; a += 37) {
        for (uint64_t b = 3; b + frames <= samples_; b += 41) {
          ASSERT_EQ(distance.Dtw(Word(a), Word(b)), ReferenceDtw(distance, Word(a), Word(b), band))
              << frames << " " << band << " " << a << " " << b;
        }
      }
    }
  }
}

TEST(WordDistance, OneFrameWordsAreOneFrameDistance) {
  const int16_t a[4] = {32767, 0, 0, 0};
  const int16_t b[4] = {0, 32767, 0, 0};
  const WordDistance distance({2.0f}, 1, 2);
  EXPECT_EQ(distance.Dtw(a, b), distance.FrameDistance(a, b));
  EXPECT_NEAR(distance.FrameDistance(a, b), 2.0 * std::sqrt(2.0), 1e-4);
}

// Real CMU take (BVH, 120 fps): its words through the whole path (import, archive, stream).
// Adjacent words (a 4-sample, 0.17 s step) are nearer than words at least 10 words (1.7 s)
// apart, on average.
TEST(WordDistanceRealTake, AdjacentWordsAreNearerThanWordsFarApart) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string bvh = ::motif::testing::MocapDir() + "/bvh/06_13.bvh";
  TakeSource source;
  source.format = TakeFormat::kBvh;
  source.path = bvh;
  Result<Take> take = ImportTake(source, ImportOptions());
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  ::motif::testing::TempDir dir;
  const std::string path = dir.File("real.mfs");
  testing::WriteClips(path, take->skeleton, {TakeToClipFrames(*take)}, take->fps);
  auto reader = testing::OpenArchive(path);
  ASSERT_NE(reader, nullptr);
  auto weights = LoadDistanceWeights(reader->skeleton(), "");
  ASSERT_TRUE(weights.ok());
  auto stream = WordStream::Create(*reader, *weights);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  std::vector<int16_t> words;
  WordBatch batch;
  size_t values = 0;
  while (true) {
    Result<bool> more = (*stream)->Next(&batch);
    ASSERT_TRUE(more.ok()) << more.status().ToString();
    if (!*more) break;
    values = batch.word_values();
    for (size_t word = 0; word < batch.size(); ++word) {
      words.insert(words.end(), batch.word(word), batch.word(word) + values);
    }
  }
  ASSERT_GT(values, 0u);
  const size_t count = words.size() / values;
  EXPECT_EQ(count, (*stream)->word_count());
  EXPECT_GT(count, 200u) << "06_13 has 4,905 frames of motion: 242 words";
  const WordDistance distance((*stream)->resampler().weights(), 16);
  EXPECT_EQ(distance.weights().size(), 12u);
  auto word = [&](size_t idx) { return &words[idx * values]; };
  double adjacent = 0;
  for (size_t idx = 0; idx + 1 < count; ++idx) adjacent += distance.Dtw(word(idx), word(idx + 1));
  adjacent /= static_cast<double>(count - 1);
  double far = 0;
  uint64_t far_pairs = 0;
  for (size_t a = 0; a < count; ++a) {
    for (size_t b = a + 10; b < count; ++b) {
      far += distance.Dtw(word(a), word(b));
      ++far_pairs;
    }
  }
  far /= static_cast<double>(far_pairs);
  std::printf(
      "06_13: %zu words; mean DTW adjacent %.3f, at least 10 words apart %.3f (%llu pairs)\n",
      count, adjacent, far, static_cast<unsigned long long>(far_pairs));
  EXPECT_LT(adjacent, 0.5 * far);
}

}  // namespace
}  // namespace motif
