// Helpers for the synthesiser tests: collecting an archive in memory, the pose distance D of
// docs/design/algorithm.md step 1 (weighted joints, sign-free quaternion distance, heading
// already removed from the root), a banded DTW over it, and checks shared by the procedural and
// re-sequencing tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "engine/synth/motion_synthesizer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"

namespace motif::testing {

struct CollectedArchive {
  std::vector<ClipFrames> clips;
  std::map<std::string, size_t> clip_index;
  uint64_t frames = 0;
};

inline CollectedArchive Collect(MotionSynthesizer* synthesizer) {
  CollectedArchive archive;
  Status status = synthesizer->Run([&](const ClipFrames& clip) {
    archive.clip_index[clip.info.name] = archive.clips.size();
    archive.frames += clip.info.frame_count;
    archive.clips.push_back(clip);
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok()) << status.ToString();
  return archive;
}

// The weighted joints of `skeleton` and a frame's pose reduced to their quaternions (w >= 0).
class PoseMetric {
 public:
  explicit PoseMetric(const Skeleton& skeleton)
      : layout_{static_cast<uint32_t>(skeleton.joint_count())} {
    for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
      if (skeleton.joint(joint_idx).weight > 0) {
        joints_.push_back(joint_idx);
        weights_.push_back(skeleton.joint(joint_idx).weight);
      }
    }
  }
  size_t weighted_joint_count() const { return joints_.size(); }
  const FrameLayout& layout() const { return layout_; }

  // D(a, b) = sum_k w_k min(|q_ak - q_bk|, |q_ak + q_bk|) over the weighted joints.
  double Distance(const float* row_a, const float* row_b) const {
    double total = 0;
    for (size_t idx = 0; idx < joints_.size(); ++idx) {
      const float* a = row_a + layout_.quaternion_offset(joints_[idx]);
      const float* b = row_b + layout_.quaternion_offset(joints_[idx]);
      double minus = 0;
      double plus = 0;
      for (int c = 0; c < 4; ++c) {
        minus += (a[c] - b[c]) * (a[c] - b[c]);
        plus += (a[c] + b[c]) * (a[c] + b[c]);
      }
      total += weights_[idx] * std::sqrt(std::min(minus, plus));
    }
    return total;
  }

  // Mean D along the best monotone alignment (DTW with a band of 35 % of the longer length) of
  // frames [a, a + a_frames) and [b, b + b_frames), every `step`-th frame.
  double AlignedDistance(const float* rows_a, size_t a_frames, const float* rows_b, size_t b_frames,
                         size_t step = 2) const {
    const size_t stride = layout_.stride();
    const size_t n = (a_frames + step - 1) / step;
    const size_t m = (b_frames + step - 1) / step;
    const double band = 0.35 * static_cast<double>(std::max(n, m)) + 2;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> cost((n + 1) * (m + 1), kInf);
    std::vector<int> length((n + 1) * (m + 1), 0);
    cost[0] = 0;
    for (size_t i = 1; i <= n; ++i) {
      const double center =
          static_cast<double>(i) * static_cast<double>(m) / static_cast<double>(n);
      const size_t lo = static_cast<size_t>(std::max(1.0, center - band));
      const size_t hi = static_cast<size_t>(std::min(static_cast<double>(m), center + band));
      for (size_t j = lo; j <= hi; ++j) {
        const double d =
            Distance(rows_a + (i - 1) * step * stride, rows_b + (j - 1) * step * stride);
        size_t best = (i - 1) * (m + 1) + (j - 1);
        const size_t up = (i - 1) * (m + 1) + j;
        const size_t left = i * (m + 1) + (j - 1);
        if (cost[up] < cost[best]) best = up;
        if (cost[left] < cost[best]) best = left;
        cost[i * (m + 1) + j] = cost[best] + d;
        length[i * (m + 1) + j] = length[best] + 1;
      }
    }
    return cost[n * (m + 1) + m] / std::max(1, length[n * (m + 1) + m]);
  }

 private:
  FrameLayout layout_;
  std::vector<size_t> joints_;
  std::vector<float> weights_;
};

inline double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Checks every invariant of a truth table against the clips' lengths: in a clip, sorted,
// non-overlapping with room for the blends and the gap, warp in range, counts per motif in
// range, one motif length per motif consistent with its instances' lengths and warps.
inline void ExpectValidTruth(const std::vector<PlantedInstance>& truth,
                             const std::map<std::string, uint64_t>& clip_frames,
                             const SynthOptions& options) {
  const uint64_t crossfade = static_cast<uint64_t>(
      std::max<long long>(options.crossfade_seconds > 0 ? 1 : 0,
                          std::llround(options.crossfade_seconds * options.fps)));
  const uint64_t gap = static_cast<uint64_t>(std::llround(options.gap_seconds * options.fps));
  std::map<uint32_t, std::vector<const PlantedInstance*>> by_motif;
  for (size_t idx = 0; idx < truth.size(); ++idx) {
    const PlantedInstance& instance = truth[idx];
    auto clip = clip_frames.find(instance.clip);
    ASSERT_NE(clip, clip_frames.end()) << instance.clip;
    EXPECT_LT(instance.start, instance.end);
    EXPECT_GE(instance.start, crossfade) << "blend-in ramp must be inside the clip";
    EXPECT_LE(instance.end + crossfade, clip->second) << "blend-out ramp must be inside the clip";
    EXPECT_GE(instance.warp, options.warp_min - 1e-9);
    EXPECT_LE(instance.warp, options.warp_max + 1e-9);
    EXPECT_LT(instance.motif, options.motifs);
    if (idx > 0 && truth[idx - 1].clip == instance.clip) {
      EXPECT_LT(truth[idx - 1].start, instance.start) << "sorted by start";
      EXPECT_GE(instance.start, truth[idx - 1].end + 2 * crossfade + gap)
          << "instances overlap or touch: " << instance.clip << " " << truth[idx - 1].end
          << " then " << instance.start;
    }
    if (idx > 0) {
      EXPECT_LE(truth[idx - 1].clip, instance.clip) << "sorted by clip";
    }
    by_motif[instance.motif].push_back(&instance);
  }
  EXPECT_EQ(by_motif.size(), options.motifs);
  for (const auto& [motif, instances] : by_motif) {
    EXPECT_GE(instances.size(), options.instances_min) << "motif " << motif;
    EXPECT_LE(instances.size(), options.instances_max) << "motif " << motif;
    const double motif_frames =
        static_cast<double>(instances[0]->end - instances[0]->start) / instances[0]->warp;
    EXPECT_NEAR(motif_frames, std::round(motif_frames), 1e-6);
    EXPECT_GE(motif_frames, std::floor(options.motif_seconds_min * options.fps) - 1);
    EXPECT_LE(motif_frames, std::ceil(options.motif_seconds_max * options.fps) + 1);
    for (const PlantedInstance* instance : instances) {
      const double length = static_cast<double>(instance->end - instance->start);
      EXPECT_NEAR(length, motif_frames * instance->warp, 1e-6) << "motif " << motif;
    }
  }
}

inline std::map<std::string, uint64_t> ClipLengths(const CollectedArchive& archive) {
  std::map<std::string, uint64_t> lengths;
  for (const ClipFrames& clip : archive.clips) lengths[clip.info.name] = clip.info.frame_count;
  return lengths;
}

// The largest rotation change (degrees) of any joint between consecutive frames, over all clips,
// and checks that every value is finite and every quaternion unit.
inline double MaxJointStepDegrees(const CollectedArchive& archive, size_t joint_count) {
  const FrameLayout layout{static_cast<uint32_t>(joint_count)};
  double worst = 0;
  for (const ClipFrames& clip : archive.clips) {
    for (size_t frame_idx = 0; frame_idx < clip.info.frame_count; ++frame_idx) {
      const float* row = &clip.rows[frame_idx * layout.stride()];
      for (size_t value_idx = 0; value_idx < layout.stride(); ++value_idx) {
        if (!std::isfinite(row[value_idx])) {
          ADD_FAILURE() << clip.info.name << " frame " << frame_idx << " value " << value_idx
                        << " is not finite";
          return 1e9;
        }
      }
      for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
        const float* q = row + layout.quaternion_offset(joint_idx);
        const Eigen::Quaterniond current(q[0], q[1], q[2], q[3]);
        EXPECT_NEAR(current.norm(), 1.0, 1e-4);
        if (frame_idx == 0) continue;
        const float* p = q - layout.stride();
        const Eigen::Quaterniond previous(p[0], p[1], p[2], p[3]);
        worst = std::max(worst, RadiansToDegrees(RotationAngleBetween(current, previous)));
      }
    }
  }
  return worst;
}

}  // namespace motif::testing
