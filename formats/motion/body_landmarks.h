// The body parts of a humanoid skeleton of any naming: which joint is the pelvis, the chest, the
// head, and on each side the shoulder, elbow, wrist, hip, knee, ankle and toes. Mixed folders
// use them to map a skeleton of another family onto the canonical CMU body (body_retarget.h).
//
// How the joints are found (docs/design/mixed_skeletons.md gives the rule with examples):
//   - a joint's side and part are SplitJointSide of its name with the parts below as the known
//     ones (joint_side.h, the rule the report colours by): the part lower-cased, without a
//     namespace prefix ("mixamorig:"), the side or any character that is not a letter or digit,
//     so "UpperArm_L", "upperarm.l" and "upperarmL" are one left upper arm; a side is a leading
//     or trailing "left"/"right", or a single leading or trailing "l"/"r" ("lThigh",
//     "UpperLeg_L", "LeftUpLeg");
//   - the parts: upper arm {arm, upperarm, shldr, humerus}, thigh {upleg, upperleg, thigh,
//     femur}; the elbow, wrist, knee and ankle are then the first joint of the chain below
//     (the child with the most descendants), the toes the ankle's child if it has one;
//   - the pelvis is joint 0 (the joint that moves, formats/import/animated_root.h), the chest
//     the nearest common ancestor of the two upper arms, the spine the joints between them, the
//     neck the joints from the chest to a joint named "head" (or, lacking one, the chest's child
//     that is neither arm's ancestor).
// Thread-safety: pure functions.
#pragma once

#include <vector>

#include "common/status.h"
#include "formats/motion/skeleton.h"

namespace motif {

// One side's limb joints (skeleton indices; -1 where the skeleton has none).
struct LimbJoints {
  int clavicle = -1;  // the upper arm's parent when it is not the chest
  int upper_arm = -1;
  int elbow = -1;
  int wrist = -1;
  int hip = -1;  // the thigh joint (where the thigh bone starts)
  int knee = -1;
  int ankle = -1;
  int toes = -1;
};

struct BodyLandmarks {
  int pelvis = 0;
  std::vector<int> spine;  // pelvis (exclusive) to chest (exclusive), top-down order
  int chest = -1;
  std::vector<int> neck;  // chest (exclusive) to head (exclusive)
  int head = -1;
  LimbJoints left;
  LimbJoints right;
};

// The landmarks of `skeleton`. InvalidArgument naming the first body part not found (say
// "no left thigh: no joint named like LeftUpLeg, lThigh or UpperLeg_L") when the skeleton is not
// a humanoid this rule can read.
Result<BodyLandmarks> FindBodyLandmarks(const Skeleton& skeleton);

}  // namespace motif
