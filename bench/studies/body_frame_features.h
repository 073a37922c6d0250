// BodyFrameFeatures: one clip's frames as joint positions in the body's own frame, for the
// distance study (distance_study.cc, docs/design/motion_distance.md). Forward kinematics of the
// archive rows with the clip's own bone offsets, and:
//  * the root at the origin and its heading removed (the stored root rotation is the swing
//    only: formats/motion/pose_frames.h), so the frame turns with the body about the vertical;
//  * every length divided by the body's size: the height of the clip's rest pose (highest point
//    minus lowest, end sites included), so a taller performer or a skeleton in other units
//    (the Daz BVH is about 5.5 times bigger) gives the same numbers;
//  * points: the origin of every joint that has a positive pose weight or whose parent has one
//    (for CMU: hips, knees, ankles, lower and upper back, thorax, neck base, clavicles,
//    shoulders, elbows, wrists), less those that sit on the root in the rest pose;
//  * velocities: each point's displacement over 0.1 s, p(t + d) - p(t - d) with d = 0.05 s in
//    frames (clamped at the clip's ends), in body heights;
//  * root motion: the root's horizontal velocity in the heading frame times 0.1 s and its
//    height change over 0.1 s, in body heights (so a jump or a step shows without the root's
//    absolute position);
//  * body parts, from the skeleton's topology (no names): the legs are the subtrees of the
//    root's children other than the largest (the spine); the chest is the first joint of the
//    spine with three or more children, the arms the two largest subtrees below it. Arm points
//    are also given in the chest's frame (its position subtracted, its world rotation undone),
//    so a duck with the guard held keeps the arms still.
// Quaternion signs do not matter (forward kinematics of q and -q is the same).
// Thread-safety: immutable once built.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

namespace motif::testing {

enum class BodyPart { kTrunk, kArm, kLeg };

// Which values of a frame a distance uses (indices into BodyFrameFeatures::frame()).
using ChannelSet = std::vector<uint32_t>;

class BodyFrameFeatures {
 public:
  // `rows`: the clip's archive rows (frame_count * layout.stride() floats) at `fps`.
  // InvalidArgument when the skeleton has no weighted joint or no recognisable chest and arms.
  static Result<BodyFrameFeatures> Compute(const Skeleton& skeleton, const ClipInfo& clip,
                                           const std::vector<float>& rows, double fps);

  uint64_t frame_count() const { return frame_count_; }
  uint32_t values_per_frame() const { return values_per_frame_; }
  const float* frame(uint64_t frame_idx) const { return &values_[frame_idx * values_per_frame_]; }
  double body_height() const { return body_height_; }
  // The skeleton's joint of each point, and its part.
  const std::vector<uint32_t>& point_joints() const { return point_joints_; }
  const std::vector<BodyPart>& point_parts() const { return point_parts_; }

  // Channel sets: all points' positions; positions, velocities and root motion; the arm points
  // in the chest frame with their velocities; the leg points with their velocities and the root
  // motion.
  ChannelSet Positions() const;
  ChannelSet PositionsAndVelocities() const;
  ChannelSet Arms() const;
  ChannelSet Legs() const;
  // The velocity channels of Arms() and Legs() (the legs' with the root motion): how much a part
  // moves in a frame is the sum of their squares.
  ChannelSet ArmVelocities() const;
  ChannelSet LegVelocities() const;

  // A one-line description of the points and parts (joint names), for the study's log.
  std::string Describe(const Skeleton& skeleton) const;

 private:
  uint64_t frame_count_ = 0;
  uint32_t values_per_frame_ = 0;
  double body_height_ = 1;
  std::vector<uint32_t> point_joints_;
  std::vector<BodyPart> point_parts_;
  std::vector<uint32_t> arm_points_;  // indices into point_joints_
  // Per frame: 3P positions, 3P velocities, 3A chest-frame arm positions, 3A their velocities,
  // 3 root motion values.
  std::vector<float> values_;

  uint32_t velocity_offset() const { return 3 * static_cast<uint32_t>(point_joints_.size()); }
  uint32_t arm_offset() const { return 2 * velocity_offset(); }
  uint32_t arm_velocity_offset() const {
    return arm_offset() + 3 * static_cast<uint32_t>(arm_points_.size());
  }
  uint32_t root_motion_offset() const {
    return arm_velocity_offset() + 3 * static_cast<uint32_t>(arm_points_.size());
  }
};

}  // namespace motif::testing
