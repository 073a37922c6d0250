// Small pieces of body geometry that both ways of mapping a take onto the CMU body use
// (body_retarget.h, rest_aligned_mapping.h): a canonical joint's index by name, forward
// kinematics of one frame, and the rotation between two frames given by a bone and a second
// direction.
// Thread-safety: pure functions.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/skeleton.h"

namespace motif {

// The index of a canonical CMU joint ("lfemur"): its place in CmuCanonicalJointNames().
int CanonicalJointIndex(const char* name);

// World positions of the joints of `skeleton` posed by `local` rotations (one per joint; the
// root's is its world rotation) with the root at `root`; `world` receives the world rotations.
std::vector<Eigen::Vector3d> JointPositions(const Skeleton& skeleton, const Eigen::Vector3d& root,
                                            const Eigen::Quaterniond* local,
                                            std::vector<Eigen::Quaterniond>* world);

// The world rotation that turns the frame (rest_bone, rest_reference) into (bone, reference):
// the bone exactly, the reference as near as the bone allows. A reference along its bone is
// replaced by any perpendicular.
Eigen::Quaterniond Orientation(const Eigen::Vector3d& rest_bone,
                               const Eigen::Vector3d& rest_reference, const Eigen::Vector3d& bone,
                               const Eigen::Vector3d& reference);

}  // namespace motif
