// Mapping a take of another skeleton family onto the canonical CMU body, so that a folder that
// mixes families (CMU ASF/AMC, cgspeed BVH, Daz BVH, a studio rig) mines as one archive.
//
// Two ways, chosen by the source's rest pose (its zero rotations):
//   - a rig that stands upright at rest (a T- or A-pose: CMU, Daz): each canonical joint of the
//     torso takes its source joint's world rotation times a constant correction that turns the
//     canonical rest bone onto the source's rest bone;
//   - a rig whose zero rotations fold the body up (a studio rig whose joint orients live in its
//     motion): the torso is placed from where the source's joints are, each frame: the pelvis
//     up to the chest and left from the right hip to the left hip; the spine and chest up along
//     the spine, left along the hips (lower back) or the shoulders.
// Either way the arms and legs are placed from the joints' positions: the upper arm, forearm,
// thigh, shin (and foot) point along the source's bone, their twist from the elbow's or knee's
// hinge axis (upper x lower bone) set onto the rest hinge axes of the CMU body
// (cmu_rest_pose.h), so an elbow or knee is a hinge as in CMU's takes; where a limb is almost
// straight the axis is carried over from the frame before, in the parent's frame. The hip
// joints, clavicles and the joints the source lacks keep their rest rotation relative to their
// parent. The limbs' directions are exact: a canonical bone points where the source's does.
// The take comes out at the rest body's size: the skeleton is CmuRestSkeleton(), the root
// positions are the source's divided by the source's leg length over the rest body's (and
// meters_per_unit multiplied by it), so heights, speeds and the report's figures compare across
// families, and an export stands on its floor and travels as far, in body lengths, as the source.
// Rule and figures: docs/design/mixed_skeletons.md.
// Thread-safety: pure functions.
#pragma once

#include "common/status.h"
#include "formats/motion/take.h"

namespace motif {

// `take` (any family, its joints as imported) on the canonical CMU body: family cmu31, 31 joints
// in canonical order, default weights, the same frames, rate, name and provenance, and
// source_joint_names cleared (the joints are not the source's). InvalidArgument, prefixed with
// the take's path, when FindBodyLandmarks cannot read the skeleton as a human body.
Result<Take> RetargetToCmuBody(const Take& take);

}  // namespace motif
