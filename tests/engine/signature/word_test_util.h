// Helpers for the motion-word tests: clips whose every joint turns at a constant rate about a
// fixed axis (so the rotation at any time is known exactly), synthetic clips from the
// MotionSynthesizer (the CMU skeleton and its 12 weighted joints), archives written from clips,
// and the words of in-memory clips.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "engine/signature/clip_words.h"
#include "engine/signature/word_batch.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

namespace motif::testing {

// A chain of `joint_count` joints "j0", "j1", ...; every third joint (2, 5, ...) has weight 0.
inline Skeleton ChainSkeleton(uint32_t joint_count) {
  std::vector<Joint> joints(joint_count);
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    Joint& joint = joints[joint_idx];
    char name[16];  // "j" + std::to_string() trips GCC 12's -Wrestrict false positive
    std::snprintf(name, sizeof(name), "j%u", joint_idx);
    joint.name = name;
    joint.parent = static_cast<int32_t>(joint_idx) - 1;
    joint.offset = {0.0, joint_idx == 0 ? 0.0 : 10.0, 0.0};
    if (joint_idx == 0) {
      joint.channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition,
                        ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
    } else {
      joint.channels = {ChannelType::kZRotation, ChannelType::kXRotation, ChannelType::kYRotation};
    }
    joint.weight = joint_idx % 3 == 2 ? 0.0f : 1.0f;
  }
  return Skeleton("custom", std::move(joints));
}

// A clip of `frames` frames of ChainSkeleton(joints) at `fps`, named `name` (from
// "<name>.bvh"), its rows all zero for the caller to fill.
inline ClipFrames ChainClip(const std::string& name, uint64_t frames, uint32_t joints, double fps) {
  ClipFrames clip;
  clip.info.name = name;
  clip.info.source_path = name + ".bvh";
  clip.info.frame_count = frames;
  clip.info.fps = fps;
  clip.info.source_fps = fps;
  clip.info.joint_offsets.assign(joints, {0.0f, 10.0f, 0.0f});
  clip.info.end_sites.assign(joints, {0.0f, 0.0f, 0.0f});
  clip.rows.assign(frames * FrameLayout{joints}.stride(), 0.0f);
  return clip;
}

// Writes `q` as joint `joint`'s quaternion (w x y z) into frame row `row`.
inline void StoreQuaternion(const Eigen::Quaterniond& q, const FrameLayout& layout, uint32_t joint,
                            float* row) {
  float* out = row + layout.quaternion_offset(joint);
  out[0] = static_cast<float>(q.w());
  out[1] = static_cast<float>(q.x());
  out[2] = static_cast<float>(q.y());
  out[3] = static_cast<float>(q.z());
}

inline std::vector<float> JointWeightsOf(const Skeleton& skeleton) {
  std::vector<float> weights;
  for (const Joint& joint : skeleton.joints()) weights.push_back(joint.weight);
  return weights;
}

// Joint j turns about a fixed unit axis at a constant rate (radians per second) from a fixed
// start angle; the root's height, velocity and heading are linear in time.
struct AxisMotion {
  uint32_t joint_count = 4;
  double fps = 120;

  Eigen::Vector3d Axis(uint32_t joint_idx) const {
    return Eigen::Vector3d(1.0 + joint_idx, -0.5 * joint_idx, 2.0 - joint_idx).normalized();
  }
  double Rate(uint32_t joint_idx) const { return 1.5 + 0.9 * joint_idx; }  // rad/s
  double StartAngle(uint32_t joint_idx) const { return 0.3 - 0.2 * joint_idx; }
  double Angle(uint32_t joint_idx, double seconds) const {
    return StartAngle(joint_idx) + Rate(joint_idx) * seconds;
  }
  Eigen::Quaterniond Rotation(uint32_t joint_idx, double seconds) const {
    return Eigen::Quaterniond(Eigen::AngleAxisd(Angle(joint_idx, seconds), Axis(joint_idx)));
  }
  double Height(double seconds) const { return 0.9 + 0.25 * seconds; }
  double VelocityX(double seconds) const { return 1.5 - 0.5 * seconds; }
  double VelocityZ(double seconds) const { return 0.25 + seconds; }
  double Heading(double seconds) const { return -0.5 + 0.75 * seconds; }

  // `frame_count` frames at `fps`. With `flip_every` > 0, the quaternion of every joint of every
  // flip_every-th frame is stored negated (the same rotation).
  ClipFrames Clip(const std::string& name, uint64_t frame_count, uint32_t flip_every = 0) const {
    const FrameLayout layout{joint_count};
    ClipFrames clip = ChainClip(name, frame_count, joint_count, fps);
    for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
      const double seconds = static_cast<double>(frame_idx) / fps;
      float* row = &clip.rows[frame_idx * layout.stride()];
      const double sign = flip_every > 0 && frame_idx % flip_every == 0 ? -1.0 : 1.0;
      for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
        const Eigen::Quaterniond q = Rotation(joint_idx, seconds);
        StoreQuaternion(Eigen::Quaterniond(q.coeffs() * sign), layout, joint_idx, row);
      }
      row[layout.height_offset()] = static_cast<float>(Height(seconds));
      row[layout.velocity_offset()] = static_cast<float>(VelocityX(seconds));
      row[layout.velocity_offset() + 1] = static_cast<float>(VelocityZ(seconds));
      row[layout.heading_offset()] = static_cast<float>(Heading(seconds));
    }
    return clip;
  }
};

// The rotation angle (radians) between quaternion `q` (w, x, y, z floats) and `expected`.
inline double AngleTo(const float* q, const Eigen::Quaterniond& expected) {
  const Eigen::Quaterniond actual(q[0], q[1], q[2], q[3]);
  const double dot = std::abs(actual.normalized().dot(expected));
  return 2.0 * std::acos(std::min(1.0, dot));
}

// Synthetic clips (procedural, CMU skeleton) of about `frames` frames in all, clips of 2 to 8 s
// at 120 fps.
struct SynthClips {
  Skeleton skeleton;
  std::vector<ClipFrames> clips;
};
inline SynthClips MakeSynthClips(uint64_t frames, uint64_t seed) {
  SynthOptions options;
  options.frames = frames;
  options.seed = seed;
  options.motifs = 0;
  options.clip_seconds_min = 2;
  options.clip_seconds_max = 8;
  options.threads = 1;
  SynthClips result;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  if (!synthesizer.ok()) return result;
  result.skeleton = (*synthesizer)->skeleton();
  const Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    result.clips.push_back(clip);
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok()) << status.ToString();
  return result;
}

// The clip with the most frames (the first of them).
inline const ClipFrames& LongestClip(const SynthClips& synth) {
  size_t best = 0;
  for (size_t idx = 1; idx < synth.clips.size(); ++idx) {
    if (synth.clips[idx].info.frame_count > synth.clips[best].info.frame_count) best = idx;
  }
  return synth.clips.at(best);
}

// Writes `clips` to a new archive at `path` and commits.
inline void WriteClips(const std::string& path, const Skeleton& skeleton,
                       const std::vector<ClipFrames>& clips, double fps,
                       const FrameFileWriterOptions& options = {}) {
  auto writer = FrameFileWriter::Create(path, skeleton, fps, options);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  for (const ClipFrames& clip : clips) {
    const Status status = (*writer)->AppendClip(clip);
    ASSERT_TRUE(status.ok()) << status.ToString();
  }
  const Status status = (*writer)->Commit();
  ASSERT_TRUE(status.ok()) << status.ToString();
}

inline std::unique_ptr<FrameFileReader> OpenArchive(const std::string& path) {
  auto reader = FrameFileReader::Open(path);
  EXPECT_TRUE(reader.ok()) << reader.status().ToString();
  return reader.ok() ? std::move(*reader) : nullptr;
}

// The words of one in-memory clip (ClipWords::FromRows; the test fails on error).
inline ClipWords WordsOfClip(const ClipFrames& clip, const Skeleton& skeleton,
                             const WordOptions& options = {}) {
  auto words = ClipWords::FromRows(clip.rows, clip.info.fps,
                                   FrameLayout{static_cast<uint32_t>(skeleton.joint_count())},
                                   JointWeightsOf(skeleton), options);
  EXPECT_TRUE(words.ok()) << words.status().ToString();
  return std::move(*words);
}

}  // namespace motif::testing
