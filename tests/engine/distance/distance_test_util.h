// Helpers for the pose-distance tests: the canonical CMU skeleton with its default weights,
// random and smooth synthetic takes, random frame rows, and small synthetic archives from
// MotionSynthesizer held in memory as PoseFeatures.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "engine/distance/pose_features.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"
#include "formats/motion/take.h"

namespace motif::testing {

// The canonical "cmu31" skeleton with the default pose-distance weights (12 weighted joints).
inline Skeleton CmuSkeleton() {
  const std::vector<std::string>& names = CmuCanonicalJointNames();
  const std::vector<int>& parents = CmuCanonicalParents();
  std::vector<Joint> joints;
  for (size_t joint_idx = 0; joint_idx < names.size(); ++joint_idx) {
    Joint joint;
    joint.name = names[joint_idx];
    joint.parent = parents[joint_idx];
    joint.offset = {0.0, joint_idx == 0 ? 0.0 : 1.0, 0.0};
    joint.weight = DefaultJointWeight(kCmuFamily, joint.name, joint_idx == 0);
    joints.push_back(joint);
  }
  return Skeleton(kCmuFamily, std::move(joints));
}

inline std::vector<float> WeightsOf(const Skeleton& skeleton) {
  std::vector<float> weights;
  for (const Joint& joint : skeleton.joints()) weights.push_back(joint.weight);
  return weights;
}

inline Eigen::Quaterniond RandomRotation(std::mt19937_64* rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(*rng), normal(*rng), normal(*rng), normal(*rng));
  return q.normalized();
}

// A take of `frame_count` frames on the CMU skeleton: every joint turns smoothly (sinusoids of
// random axes, amplitudes and phases around a random rest rotation), the root also walks and
// turns about the vertical. Deterministic for a seed.
inline Take SmoothTake(uint64_t frame_count, uint64_t seed, const std::string& name = "take") {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Take take;
  take.name = name;
  take.fps = 120;
  take.source_fps = 120;
  take.skeleton = CmuSkeleton();
  const size_t joint_count = take.joint_count();
  struct Motion {
    Eigen::Quaterniond rest;
    Eigen::Vector3d axis;
    double amplitude, frequency, phase;
  };
  std::vector<Motion> motions;
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    Motion motion;
    motion.rest = RandomRotation(&rng);
    motion.axis = RandomRotation(&rng) * Eigen::Vector3d::UnitX();
    motion.amplitude = 0.2 + 1.0 * uniform(rng);
    motion.frequency = 0.3 + 1.5 * uniform(rng);
    motion.phase = 2 * kPi * uniform(rng);
    motions.push_back(motion);
  }
  const double turn_rate = 0.5 * (uniform(rng) - 0.5);  // radians per second about Y
  Eigen::Vector3d position(10 * uniform(rng), 90, 10 * uniform(rng));
  for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const double time = static_cast<double>(frame_idx) / take.fps;
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      const Motion& motion = motions[joint_idx];
      const double angle =
          motion.amplitude * std::sin(2 * kPi * motion.frequency * time + motion.phase);
      Eigen::Quaterniond q =
          motion.rest * Eigen::Quaterniond(Eigen::AngleAxisd(angle, motion.axis));
      if (joint_idx == 0) q = AxisRotation(Axis::kY, turn_rate * time) * q;
      take.rotations.push_back(q.normalized());
    }
    position += Eigen::Vector3d(std::cos(turn_rate * time), 0, std::sin(turn_rate * time)) * 0.5;
    take.root_positions.push_back(position);
  }
  return take;
}

// `take` performed facing another way: the whole motion (root rotation and positions) turned
// by `yaw_radians` about the vertical axis through the origin.
inline Take Yawed(const Take& take, double yaw_radians) {
  Take turned = take;
  const Eigen::Quaterniond yaw = AxisRotation(Axis::kY, yaw_radians);
  for (size_t frame_idx = 0; frame_idx < take.frame_count(); ++frame_idx) {
    turned.rotation(frame_idx, 0) = (yaw * take.rotation(frame_idx, 0)).normalized();
    turned.root_positions[frame_idx] = yaw * take.root_positions[frame_idx];
  }
  return turned;
}

// Rows (FrameLayout of `joint_count` joints) of random unit quaternions with random signs.
inline std::vector<float> RandomRows(uint64_t frame_count, uint32_t joint_count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const FrameLayout layout{joint_count};
  std::vector<float> rows(frame_count * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      const Eigen::Quaterniond q = RandomRotation(&rng);
      float* out = &rows[frame_idx * layout.stride() + layout.quaternion_offset(joint_idx)];
      out[0] = static_cast<float>(q.w());
      out[1] = static_cast<float>(q.x());
      out[2] = static_cast<float>(q.y());
      out[3] = static_cast<float>(q.z());
    }
  }
  return rows;
}

// Clips concatenated into one archive's rows, with the first frame of each clip.
struct ArchiveRows {
  Skeleton skeleton;
  std::vector<float> rows;
  std::vector<uint64_t> clip_first_frames;
  uint64_t frame_count = 0;

  void Append(const ClipFrames& clip) {
    clip_first_frames.push_back(frame_count);
    rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
    frame_count += clip.info.frame_count;
  }
  PoseFeatures Features() const {
    return PoseFeatures::FromRows(rows.data(), frame_count,
                                  static_cast<uint32_t>(skeleton.joint_count()),
                                  WeightsOf(skeleton), clip_first_frames);
  }
};

// A synthetic archive of `frames` frames in clips of 5-12 s, with two planted motifs when
// there is room for them (6000 frames or more).
inline ArchiveRows SynthArchive(uint64_t frames, uint64_t seed) {
  SynthOptions options;
  options.frames = frames;
  options.seed = seed;
  options.motifs = frames >= 6000 ? 2 : 0;
  options.clip_seconds_min = 5;
  options.clip_seconds_max = 12;
  options.motif_seconds_min = 0.5;
  options.motif_seconds_max = 1.0;
  options.instances_min = 2;
  options.instances_max = 3;
  options.threads = 1;
  ArchiveRows archive;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  if (!synthesizer.ok()) return archive;
  archive.skeleton = (*synthesizer)->skeleton();
  const Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    archive.Append(clip);
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok()) << status.ToString();
  return archive;
}

}  // namespace motif::testing
