// Pools of synthetic words for the embedding tests: procedural clips of the CMU skeleton
// (MotionSynthesizer) cut into words.
#pragma once

#include <vector>

#include <gtest/gtest.h>

#include "engine/embedding/word_pool.h"
#include "tests/engine/signature/word_test_util.h"

namespace motif::testing {

inline std::vector<ClipWords> ClipWordsOf(const SynthClips& synth) {
  std::vector<ClipWords> clips;
  for (const ClipFrames& clip : synth.clips) clips.push_back(WordsOfClip(clip, synth.skeleton));
  return clips;
}

inline WordPool PoolOf(const std::vector<ClipWords>& clips, const WordPoolOptions& options = {}) {
  auto pool = WordPool::FromClips(clips, options);
  EXPECT_TRUE(pool.ok()) << pool.status().ToString();
  return std::move(*pool);
}

// The words alone, no warped copies (for the neighbour search).
inline WordPool WordsOnlyPool(const std::vector<ClipWords>& clips) {
  WordPoolOptions options;
  options.warp_copies = 0;
  return PoolOf(clips, options);
}

}  // namespace motif::testing
