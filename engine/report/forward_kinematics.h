// Forward kinematics: the world positions of a pose's joints and end sites, from a skeleton's
// bone offsets (a clip's own, once ClipFramesToTake has put them in the take's skeleton) and the
// joint rotations of one frame. Used to draw stick figures of motif instances (report_html.h).
//
// Point numbering, shared with stick_figure_svg.h: points 0..J-1 are the joints in skeleton
// order; then one point per joint that has an end site, in joint order.
// Convention (BVH, quaternion_math.h): a joint's world rotation is its parent's world rotation
// times its own; its position is the parent's position plus the parent's world rotation applied
// to its offset. The root sits at the given root position (its offset is not added: the root
// position is already world).
// Thread-safety: pure functions.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/skeleton.h"
#include "formats/motion/take.h"

namespace motif {

// Joints plus end sites of `skeleton` (the number of points ForwardKinematics returns).
size_t PosePointCount(const Skeleton& skeleton);

// World positions of every point (see the numbering above). `rotations` holds
// skeleton.joint_count() rotations, each relative to its parent (the root's is its world
// rotation). Preconditions: a valid skeleton (parents before children).
std::vector<Eigen::Vector3d> ForwardKinematics(const Skeleton& skeleton,
                                               const Eigen::Vector3d& root_position,
                                               const Eigen::Quaterniond* rotations);

// The same for frame `frame_idx` of `take` (frame_idx < take.frame_count()).
std::vector<Eigen::Vector3d> TakeFramePositions(const Take& take, size_t frame_idx);

// Points of the skeleton's rest pose (every rotation the identity, the root at the origin).
std::vector<Eigen::Vector3d> RestPosePositions(const Skeleton& skeleton);

}  // namespace motif
