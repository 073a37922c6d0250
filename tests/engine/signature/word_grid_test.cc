// WordGrid: the sample and word arithmetic of word_grid.h, against the formulas written out by
// hand and against brute-force enumeration.
#include "engine/signature/word_grid.h"

#include <gtest/gtest.h>

#include <cmath>

namespace motif {
namespace {

TEST(WordGrid, CountsWordsPerClipByTheFormulaAt120Fps) {
  const WordOptions options;  // 16 frames at 24 Hz, stride 4
  for (uint64_t frames = 0; frames <= 2000; ++frames) {
    const WordGrid grid(frames, 120.0, options);
    const uint64_t samples = frames == 0 ? 0 : (frames - 1) / 5 + 1;
    EXPECT_EQ(grid.sample_count(), samples) << frames;
    const uint64_t words = samples >= 16 ? (samples - 16) / 4 + 1 : 0;
    ASSERT_EQ(grid.word_count(), words) << frames;
    // Brute force: word w exists iff its last sample, at source frame 5 (4 w + 15), is a frame.
    uint64_t counted = 0;
    while (frames > 0 && 5 * (4 * counted + 15) <= frames - 1) ++counted;
    EXPECT_EQ(grid.word_count(), counted) << frames;
  }
  // The hand cases of the design note.
  EXPECT_EQ(WordGrid(75, 120.0, options).word_count(), 0u);
  EXPECT_EQ(WordGrid(76, 120.0, options).word_count(), 1u);
  EXPECT_EQ(WordGrid(95, 120.0, options).word_count(), 1u);
  EXPECT_EQ(WordGrid(96, 120.0, options).word_count(), 2u);
  EXPECT_EQ(WordGrid(1, 120.0, options).word_count(), 0u);
  EXPECT_EQ(WordGrid(1, 120.0, options).sample_count(), 1u);
}

TEST(WordGrid, WordsAt120FpsCoverSeventySixSourceFrames) {
  const WordGrid grid(1000, 120.0, WordOptions());
  ASSERT_EQ(grid.word_count(), 47u);  // M = 200 samples: (200 - 16) / 4 + 1
  for (uint64_t word = 0; word < grid.word_count(); ++word) {
    EXPECT_EQ(grid.SourceFrames(word), (FrameSpan{20 * word, 20 * word + 76})) << word;
    EXPECT_EQ(grid.FirstSample(word), 4 * word);
    EXPECT_DOUBLE_EQ(grid.StartSeconds(word), static_cast<double>(word) / 6.0);
  }
  // Every regular sample falls on a source frame: copied, never blended.
  for (uint64_t sample = 0; sample < grid.sample_count(); ++sample) {
    const SourcePosition position = grid.Sample(sample);
    EXPECT_EQ(position.lower, 5 * sample);
    EXPECT_EQ(position.upper, 5 * sample);
    EXPECT_EQ(position.alpha, 0.0);
  }
}

TEST(WordGrid, SamplesAt30FpsFallBetweenFrames) {
  const WordGrid grid(100, 30.0, WordOptions());
  // t(k) = 1.25 k source frames.
  EXPECT_EQ(grid.sample_count(), 80u);  // floor(99 / 1.25) + 1
  const SourcePosition one = grid.Sample(1);
  EXPECT_EQ(one.lower, 1u);
  EXPECT_EQ(one.upper, 2u);
  EXPECT_EQ(one.alpha, 0.25);
  const SourcePosition two = grid.Sample(2);
  EXPECT_EQ(two.lower, 2u);
  EXPECT_EQ(two.alpha, 0.5);
  const SourcePosition four = grid.Sample(4);
  EXPECT_EQ(four.lower, 5u);
  EXPECT_EQ(four.upper, 5u);
  EXPECT_EQ(four.alpha, 0.0);
  // Word 0: samples 0..15, the last at t = 18.75, between frames 18 and 19.
  EXPECT_EQ(grid.SourceFrames(0), (FrameSpan{0, 20}));
  // Word 1: samples 4..19: t from 5 to 23.75.
  EXPECT_EQ(grid.SourceFrames(1), (FrameSpan{5, 25}));
}

TEST(WordGrid, SameRateIsOneSampleAFrame) {
  // 24.01 is within 0.1 % of 24: the importers' rule treats it as the same rate.
  for (double fps : {24.0, 24.01}) {
    const WordGrid grid(50, fps, WordOptions());
    EXPECT_EQ(grid.sample_count(), 50u);
    EXPECT_EQ(grid.word_count(), 9u);  // (50 - 16) / 4 + 1
    for (uint64_t sample = 0; sample < 50; ++sample) {
      EXPECT_EQ(grid.Sample(sample).lower, sample);
      EXPECT_EQ(grid.Sample(sample).alpha, 0.0);
    }
    EXPECT_EQ(grid.SourceFrames(2), (FrameSpan{8, 24}));
  }
}

TEST(WordGrid, WordLengthAndStrideAreSettable) {
  WordOptions options;
  options.word_frames = 8;
  options.stride_frames = 10;  // gaps between words
  options.word_fps = 30;
  const WordGrid grid(241, 60.0, options);  // t(k) = 2 k: samples 0..120
  EXPECT_EQ(grid.sample_count(), 121u);
  EXPECT_EQ(grid.word_count(), 12u);                     // (121 - 8) / 10 + 1
  EXPECT_EQ(grid.SourceFrames(3), (FrameSpan{60, 75}));  // samples 30..37: frames 60..74
  EXPECT_DOUBLE_EQ(grid.StartSeconds(3), 1.0);
}

TEST(WordGrid, WordsReadingAFrameMatchTheirSourceRanges) {
  for (double fps : {120.0, 30.0, 100.0}) {
    const WordGrid grid(700, fps, WordOptions());
    for (uint64_t frame = 0; frame < 700; ++frame) {
      const FrameSpan words = grid.WordsReading(frame);
      for (uint64_t word = 0; word < grid.word_count(); ++word) {
        const FrameSpan source = grid.SourceFrames(word);
        const bool reads = source.first <= frame && frame < source.end;
        EXPECT_EQ(reads, word >= words.first && word < words.end)
            << "fps " << fps << " frame " << frame << " word " << word;
      }
    }
  }
}

TEST(WordGrid, NeverReadsPastTheClip) {
  for (double fps : {120.0, 100.0, 60.0, 30.0, 25.0, 12.0, 119.88}) {
    for (uint64_t frames = 1; frames < 400; frames += 7) {
      const WordGrid grid(frames, fps, WordOptions());
      for (uint64_t sample = 0; sample < grid.sample_count(); ++sample) {
        const SourcePosition position = grid.Sample(sample);
        ASSERT_LT(position.upper, frames) << fps << " " << frames << " " << sample;
        ASSERT_GE(position.alpha, 0.0);
        ASSERT_LT(position.alpha, 1.0);
      }
      // The next sample would be past the last frame (up to the rounding allowance).
      EXPECT_GT(grid.SourceTime(static_cast<double>(grid.sample_count())),
                static_cast<double>(frames - 1) - 1e-6);
      for (uint64_t word = 0; word < grid.word_count(); ++word) {
        EXPECT_LE(grid.SourceFrames(word).end, frames);
      }
    }
  }
}

TEST(WordGrid, RejectsBadOptions) {
  WordOptions options;
  options.word_frames = 0;
  EXPECT_EQ(ValidateWordOptions(options).code(), Status::Code::kInvalidArgument);
  options = WordOptions();
  options.word_frames = kMaxWordFrames + 1;
  EXPECT_EQ(ValidateWordOptions(options).code(), Status::Code::kInvalidArgument);
  options = WordOptions();
  options.stride_frames = 0;
  EXPECT_EQ(ValidateWordOptions(options).code(), Status::Code::kInvalidArgument);
  options = WordOptions();
  options.word_fps = 0;
  EXPECT_EQ(ValidateWordOptions(options).code(), Status::Code::kInvalidArgument);
  options.word_fps = std::nan("");
  EXPECT_EQ(ValidateWordOptions(options).code(), Status::Code::kInvalidArgument);
  EXPECT_TRUE(ValidateWordOptions(WordOptions()).ok());
}

}  // namespace
}  // namespace motif
