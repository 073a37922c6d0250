// Archives for the words tests: procedural clips (MotionSynthesizer) and clips of a few distinct
// motion classes (each joint swinging sinusoidally about a class-specific axis at a
// class-specific rate, each clip starting at a random phase of it), and small, fast options for the
// words pipeline.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/split_mix64.h"
#include "engine/words/words_builder.h"
#include "tests/engine/signature/word_test_util.h"

namespace motif::testing {

// Options that train in about a second on a few hundred words.
inline WordsOptions SmallWordsOptions(uint32_t motifs = 10) {
  WordsOptions options;
  options.motifs = motifs;
  options.train.epochs = 3;
  options.train.shape.conv1_channels = 16;
  options.train.shape.conv2_channels = 16;
  options.train.shape.embedding_dims = 8;
  options.train.batch_triplets = 64;
  options.pool.warp_copies = 1;
  options.threads = 2;
  return options;
}

struct ClassClips {
  Skeleton skeleton;
  std::vector<ClipFrames> clips;
  std::vector<int> classes;  // per clip
};

// `per_class` clips of `seconds` at 120 fps for each of `classes` motion classes.
inline ClassClips MakeClassClips(int classes, int per_class, double seconds, uint64_t seed) {
  ClassClips result;
  const uint32_t joints = 6;
  result.skeleton = ChainSkeleton(joints);
  const FrameLayout layout{joints};
  SplitMix64 random(seed);
  const double fps = 120;
  for (int clip_idx = 0; clip_idx < classes * per_class; ++clip_idx) {
    const int c = clip_idx % classes;
    const uint64_t frames = static_cast<uint64_t>(seconds * fps);
    ClipFrames clip =
        ChainClip("class" + std::to_string(c) + "_" + std::to_string(clip_idx / classes), frames,
                  joints, fps);
    // One phase for the whole clip: the clips of a class are one motion started at different
    // moments.
    const double phase = 2 * M_PI * random.Uniform();
    for (uint64_t frame = 0; frame < frames; ++frame) {
      const double t = static_cast<double>(frame) / fps;
      float* row = &clip.rows[frame * layout.stride()];
      for (uint32_t joint = 0; joint < joints; ++joint) {
        // Class c swings about axis c (X, Y, Z, then again with other rates), tilted a little
        // per joint.
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        axis[c % 3] = 1.0;
        axis[(c + 1) % 3] = 0.1 * joint;
        axis.normalize();
        const double amplitude = 0.5;
        const double rate = 2 * M_PI * (0.8 + 0.4 * c);
        const double angle = amplitude * std::sin(rate * t + phase + 0.7 * joint);
        StoreQuaternion(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), layout, joint, row);
      }
      row[layout.height_offset()] = 1.0f;
    }
    result.clips.push_back(std::move(clip));
    result.classes.push_back(c);
  }
  return result;
}

}  // namespace motif::testing
