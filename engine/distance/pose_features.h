// PoseFeatures: what the pose distance needs of every frame of an archive, held compactly in
// memory for the trellis stage: the rotations of the joints with non-zero weight (for CMU
// takes: root swing with the heading removed, lowerback, upperback, thorax, humeri, radii,
// femurs, tibiae), each component quantised to int16 (value * 32767, error <= 1.6e-5), so 12
// joints take 96 bytes a frame. Also the clip layout, for the neighbour rules.
//
// The pose distance (Meng et al. 2008, docs/design/algorithm.md step 1):
//   D(f_i, f_j) = sum_k w_k * min(|q_ik - q_jk|, |q_ik + q_jk|)
// independent of each quaternion's sign; facing-independent because the root's heading is not
// part of the stored root rotation (formats/motion/pose_frames.h).
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/huge_page_allocator.h"
#include "common/rank_group.h"
#include "common/status.h"
#include "engine/distance/joint_term.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

class PoseFeatures {
 public:
  static constexpr float kQuantScale = 32767.0f;

  // Streams the archive once and keeps the joints with weight > 0. `joint_weights` has one
  // weight per archive joint (see DistanceWeights below). `progress(done, total)` in frames.
  // With `ranks` (a distributed run), each rank decodes its share of the frames and the shares
  // are exchanged (RankGroup::ShareParts): the same features on every rank.
  // InvalidArgument if no joint has a positive weight; errors of the reader pass through.
  static Result<PoseFeatures> FromArchive(
      const FrameFileReader& reader, const std::vector<float>& joint_weights,
      const std::function<void(uint64_t, uint64_t)>& progress = nullptr,
      RankGroup* ranks = nullptr);

  // `prefix` (the features of the archive's first prefix.frame_count() frames, with these
  // weights) extended by the archive's later frames, streamed from the reader: an archive that
  // grew by appended clips costs only its new frames. InvalidArgument if the weights select
  // other joints or the archive has fewer frames; errors of the reader pass through.
  static Result<PoseFeatures> ExtendFromArchive(
      PoseFeatures prefix, const FrameFileReader& reader, const std::vector<float>& joint_weights,
      const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

  // From saved parts (a cache of an earlier run): frame_count * 4 * weights.size() values
  // (copied; `values` need not be aligned), joints the archive joint of each weight, clip starts
  // ascending from 0. InvalidArgument if the sizes do not match.
  static Result<PoseFeatures> FromParts(uint64_t frame_count, std::vector<float> weights,
                                        std::vector<uint32_t> joints,
                                        std::vector<uint64_t> clip_first_frames,
                                        const int16_t* values);

  // From rows in FrameLayout order (tests, benchmarks). `clip_first_frames` as below;
  // joint_weights.size() must be joint_count (checked: aborts otherwise).
  static PoseFeatures FromRows(const float* rows, uint64_t frame_count, uint32_t joint_count,
                               const std::vector<float>& joint_weights,
                               std::vector<uint64_t> clip_first_frames);

  uint64_t frame_count() const { return frame_count_; }
  // Number of weighted joints kept (J_w); a frame is 4 * J_w int16 values (w, x, y, z each).
  uint32_t weighted_joint_count() const { return static_cast<uint32_t>(weights_.size()); }
  const int16_t* frame(uint64_t frame_idx) const {
    return &values_[frame_idx * 4 * weights_.size()];
  }
  // Weight of each kept joint, and which archive joint it is.
  const std::vector<float>& weights() const { return weights_; }
  const std::vector<uint32_t>& joints() const { return joints_; }
  // First global frame of each clip, ascending, starting with 0.
  const std::vector<uint64_t>& clip_first_frames() const { return clip_first_frames_; }
  // Index of the clip holding `frame_idx`.
  uint32_t ClipOf(uint64_t frame_idx) const;
  uint64_t memory_bytes() const { return values_.size() * sizeof(int16_t); }
  // All frames' values, frame after frame (frame_count * 4 * weighted_joint_count()).
  const int16_t* values() const { return values_.data(); }

 private:
  // Quantises frames [first_frame, end_frame) of the archive into values_ (sized already).
  Status DecodeFrames(const FrameFileReader& reader, uint64_t first_frame, uint64_t end_frame,
                      const std::function<void(uint64_t, uint64_t)>& progress);

  uint64_t frame_count_ = 0;
  std::vector<float> weights_;
  std::vector<uint32_t> joints_;
  // Read at random by every verification: on huge pages (HugePageAllocator).
  std::vector<int16_t, HugePageAllocator<int16_t>> values_;
  std::vector<uint64_t> clip_first_frames_;
};

// The term of weighted joint `joint_idx` in D, unweighted (JointTermFromSums) of the dequantised
// components of frames `a` and `b` (4 int16 per joint). Every scalar evaluation of D uses it.
inline float JointTerm(const int16_t* a, const int16_t* b, uint32_t joint_idx) {
  const float inverse = 1.0f / PoseFeatures::kQuantScale;
  float dot = 0;
  float norm_a = 0;
  float norm_b = 0;
  for (int component = 0; component < 4; ++component) {
    const float qa = a[4 * joint_idx + component] * inverse;
    const float qb = b[4 * joint_idx + component] * inverse;
    dot += qa * qb;
    norm_a += qa * qa;
    norm_b += qb * qb;
  }
  return JointTermFromSums<ScalarLanes>(norm_a, norm_b, dot);
}

// The exact pose distance D between two frames (dequantised components, each joint's
// quaternion renormalised is NOT needed: |q|^2 ~ 1 within 1e-4; the formula used is
// sqrt(max(0, |q|^2 + |p|^2 - 2|q.p|)) per joint, which equals min(|q-p|, |q+p|)).
float PoseDistance(const PoseFeatures& features, uint64_t frame_a, uint64_t frame_b);

// Per-joint weights of the pose distance: the skeleton's defaults, or a weights file overriding
// some of them. File format (text): one "joint_name weight" pair per line, '#' starts a comment;
// names are the archive's (canonical for CMU takes: "lfemur 1.0"). InvalidArgument naming the
// file and line for an unknown joint, a negative or non-numeric weight; NotFound for no file.
Result<std::vector<float>> LoadDistanceWeights(const Skeleton& skeleton,
                                               const std::string& weights_path);

}  // namespace motif
