// Time-warped copies of words: speed 1 gives the word itself, a constant-rate turn played at
// speed s turns s times as fast, copies stay inside their clip, and the speeds drawn from a seed
// are deterministic and inside their range.
#include "engine/signature/time_warp.h"

#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <vector>

#include "engine/signature/clip_words.h"
#include "engine/signature/word_distance.h"
#include "tests/engine/signature/word_test_util.h"

namespace motif {
namespace {

using testing::AxisMotion;

TEST(TimeWarp, SpeedOneIsTheWordItself) {
  const testing::SynthClips synth = testing::MakeSynthClips(3000, 21);
  for (const ClipFrames& clip : synth.clips) {
    const ClipWords words = testing::WordsOfClip(clip, synth.skeleton);
    WordBatch batch;
    words.AllWords(&batch, /*keep_rows=*/true);
    std::vector<int16_t> features(batch.word_values());
    std::vector<float> rows(batch.word_frames() * batch.row_floats());
    for (size_t word = 0; word < batch.size(); ++word) {
      words.WarpedWord(word, 1.0, features.data(), rows.data());
      ASSERT_EQ(std::memcmp(features.data(), batch.word(word), features.size() * sizeof(int16_t)),
                0)
          << clip.info.name << " word " << word;
      ASSERT_EQ(std::memcmp(rows.data(), batch.rows(word), rows.size() * sizeof(float)), 0);
    }
  }
}

TEST(TimeWarp, PlaysATurnAtTheGivenSpeed) {
  AxisMotion motion;
  const ClipFrames clip = motion.Clip("c", 1201);  // 10 s at 120 fps
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  const ClipWords words = testing::WordsOfClip(clip, skeleton);
  const FrameLayout layout{motion.joint_count};
  const uint64_t word = 20;  // well inside the clip: no shift
  for (double speed : {0.8, 0.9, 1.1, 1.25}) {
    std::vector<int16_t> features(16 * words.resampler().feature_values());
    std::vector<float> rows(16 * layout.stride());
    words.WarpedWord(word, speed, features.data(), rows.data());
    const double centre_seconds = (words.grid().FirstSample(word) + 7.5) / 24.0;
    double worst = 0;
    for (uint32_t frame = 0; frame < 16; ++frame) {
      const double seconds = centre_seconds + (frame - 7.5) * speed / 24.0;
      for (uint32_t joint = 0; joint < motion.joint_count; ++joint) {
        worst = std::max(
            worst,
            testing::AngleTo(&rows[frame * layout.stride() + layout.quaternion_offset(joint)],
                             motion.Rotation(joint, seconds)));
      }
      EXPECT_NEAR(rows[frame * layout.stride() + layout.height_offset()], motion.Height(seconds),
                  1e-6);
    }
    EXPECT_LT(worst, 1e-6) << "speed " << speed;
  }
}

TEST(TimeWarp, CopiesStayInsideTheClip) {
  const WordGrid grid(1000, 120.0, WordOptions());  // samples 0 .. 199.8: last position 199.8
  for (double speed : {0.5, 0.8, 1.0, 1.25, 2.0}) {
    for (uint64_t word : {uint64_t{0}, uint64_t{1}, grid.word_count() - 1}) {
      const std::vector<double> positions = WarpedSamplePositions(grid, word, speed);
      ASSERT_EQ(positions.size(), 16u);
      EXPECT_GE(positions.front(), 0.0) << speed << " " << word;
      EXPECT_LE(positions.back(), grid.last_sample_position()) << speed << " " << word;
      for (size_t frame = 1; frame < positions.size(); ++frame) {
        EXPECT_NEAR(positions[frame] - positions[frame - 1], speed, 1e-12);
      }
    }
  }
  // The first word at speed 1.25 would start at -1.875: shifted to start at 0.
  EXPECT_EQ(WarpedSamplePositions(grid, 0, 1.25).front(), 0.0);
  // A copy longer than the clip: centred, its ends clamped when sampled.
  const WordGrid short_grid(76, 120.0, WordOptions());  // one word, samples 0 .. 15
  const std::vector<double> positions = WarpedSamplePositions(short_grid, 0, 2.0);
  EXPECT_DOUBLE_EQ(positions.front() + positions.back(), 15.0);
  EXPECT_EQ(short_grid.Locate(short_grid.SourceTime(positions.back())).lower, 75u);
  EXPECT_EQ(short_grid.Locate(short_grid.SourceTime(positions.front())).lower, 0u);
}

TEST(TimeWarp, SpeedsAreDeterministicForASeedAndInRange) {
  const TimeWarpOptions options;
  std::set<double> distinct;
  int faster = 0;
  for (uint64_t seed = 0; seed < 1000; ++seed) {
    const double speed = DrawWarpSpeed(seed, options);
    EXPECT_EQ(speed, DrawWarpSpeed(seed, options));
    EXPECT_GE(speed, 0.8);
    EXPECT_LE(speed, 1.25);
    distinct.insert(speed);
    faster += speed > 1.0;
  }
  EXPECT_GT(distinct.size(), 990u);
  // Log-uniform: half of the draws above 1 (ln 0.8 = -ln 1.25).
  EXPECT_GT(faster, 440);
  EXPECT_LT(faster, 560);
  TimeWarpOptions fixed;
  fixed.min_speed = fixed.max_speed = 1.1;
  EXPECT_EQ(DrawWarpSpeed(7, fixed), 1.1);
}

TEST(TimeWarp, RandomCopiesAreReproducibleAndCloseToTheWord) {
  const testing::SynthClips synth = testing::MakeSynthClips(3000, 22);
  const ClipWords words = testing::WordsOfClip(testing::LongestClip(synth), synth.skeleton);
  ASSERT_GE(words.word_count(), 9u);
  const WordDistance distance(words.resampler().weights(), 16);
  WordBatch batch;
  words.AllWords(&batch);
  std::vector<int16_t> a(batch.word_values());
  std::vector<int16_t> b(batch.word_values());
  double to_copy = 0;
  double to_far = 0;
  int pairs = 0;
  for (uint64_t word = 0; word + 8 < words.word_count(); ++word) {
    const double speed = words.RandomWarpedWord(word, 1000 + word, TimeWarpOptions(), a.data());
    EXPECT_EQ(words.RandomWarpedWord(word, 1000 + word, TimeWarpOptions(), b.data()), speed);
    EXPECT_EQ(a, b);
    to_copy += distance.Dtw(batch.word(word), a.data());
    to_far += distance.Dtw(batch.word(word), batch.word(word + 8));
    ++pairs;
  }
  ASSERT_GT(pairs, 0);
  // A warped copy is a positive: much nearer its word than a word 1.3 s away.
  EXPECT_LT(to_copy, 0.5 * to_far)
      << "mean DTW to the copy " << to_copy / pairs << ", to a word 8 words on " << to_far / pairs;
}

TEST(TimeWarp, RejectsBadOptions) {
  TimeWarpOptions options;
  options.min_speed = 0;
  EXPECT_TRUE(ValidateTimeWarpOptions(options).IsInvalidArgument());
  options = TimeWarpOptions();
  options.min_speed = 1.3;
  EXPECT_TRUE(ValidateTimeWarpOptions(options).IsInvalidArgument());
  EXPECT_TRUE(ValidateTimeWarpOptions(TimeWarpOptions()).ok());
}

}  // namespace
}  // namespace motif
