// The canonical CMU body at rest: the "cmu31" skeleton (canonical_skeleton.h) with the bone
// offsets of the cgspeed BVH conversion of CMU subject 02, rounded to 0.01 length units (body
// 24.6 units from the toes to the top of the head), channels as cgspeed writes them. Takes of
// other skeleton families are mapped onto this body (body_retarget.h).
// Also the axes of the elbows and knees in this rest pose: the direction, in the rest pose, of
// (upper bone) x (lower bone) when the joint bends. docs/design/mixed_skeletons.md says how they
// were measured on CMU takes.
// Thread-safety: immutable values built once.
#pragma once

#include <Eigen/Core>

#include "formats/motion/skeleton.h"

namespace motif {

// Family cmu31, canonical names and order, default weights.
const Skeleton& CmuRestSkeleton();

// Rest-pose hinge axes, unit vectors: left and right elbow, left and right knee.
struct CmuHingeAxes {
  Eigen::Vector3d left_elbow;
  Eigen::Vector3d right_elbow;
  Eigen::Vector3d left_knee;
  Eigen::Vector3d right_knee;
};
const CmuHingeAxes& CmuRestHingeAxes();

}  // namespace motif
