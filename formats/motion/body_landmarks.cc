#include "formats/motion/body_landmarks.h"

#include <algorithm>
#include <string>

#include "formats/motion/joint_side.h"

namespace motif {
namespace {

int Depth(const Skeleton& skeleton, int joint) {
  int depth = 0;
  for (int at = joint; skeleton.joint(at).parent >= 0; at = skeleton.joint(at).parent) ++depth;
  return depth;
}

// The joint of `side` whose part is one of `parts`, the one nearest the root if several; -1.
int FindSided(const Skeleton& skeleton, BodySide side, const std::vector<std::string>& parts) {
  int best = -1;
  for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
    const SidedJointName sided = SplitJointSide(skeleton.joint(joint).name, parts);
    if (sided.side != side) continue;
    if (std::find(parts.begin(), parts.end(), sided.part) == parts.end()) continue;
    const int index = static_cast<int>(joint);
    if (best < 0 || Depth(skeleton, index) < Depth(skeleton, best)) best = index;
  }
  return best;
}

// Each joint's number of descendants, in one pass from the last joint up (parents come first).
std::vector<int> DescendantCounts(const Skeleton& skeleton) {
  std::vector<int> counts(skeleton.joint_count(), 0);
  for (size_t joint = skeleton.joint_count(); joint-- > 0;) {
    const int parent = skeleton.joint(joint).parent;
    if (parent >= 0) counts[parent] += counts[joint] + 1;
  }
  return counts;
}

// The child of `joint` that carries the chain on (the most `descendants`, the first if tied); -1.
int ChainChild(const Skeleton& skeleton, const std::vector<int>& descendants, int joint) {
  if (joint < 0) return -1;
  int best = -1;
  int best_count = -1;
  for (size_t child = 0; child < skeleton.joint_count(); ++child) {
    if (skeleton.joint(child).parent != joint) continue;
    const int count = descendants[child];
    if (count > best_count) {
      best = static_cast<int>(child);
      best_count = count;
    }
  }
  return best;
}

// `joint` and its ancestors, from the joint up to the root.
std::vector<int> PathToRoot(const Skeleton& skeleton, int joint) {
  std::vector<int> path;
  for (int at = joint; at >= 0; at = skeleton.joint(at).parent) path.push_back(at);
  return path;
}

bool IsAncestor(const Skeleton& skeleton, int ancestor, int joint) {
  const std::vector<int> path = PathToRoot(skeleton, joint);
  return std::find(path.begin(), path.end(), ancestor) != path.end();
}

// The joints strictly between `top` and `bottom` (an ancestor of it), top-down.
std::vector<int> JointsBetween(const Skeleton& skeleton, int top, int bottom) {
  std::vector<int> between;
  for (int at = skeleton.joint(bottom).parent; at >= 0 && at != top;
       at = skeleton.joint(at).parent) {
    between.push_back(at);
  }
  std::reverse(between.begin(), between.end());
  return between;
}

const std::vector<std::string>& UpperArmParts() {
  static const std::vector<std::string> parts = {"arm", "upperarm", "shldr", "humerus"};
  return parts;
}

const std::vector<std::string>& ThighParts() {
  static const std::vector<std::string> parts = {"upleg", "upperleg", "thigh", "femur"};
  return parts;
}

Status Missing(const std::string& what, const std::string& like) {
  return Status::InvalidArgument("no " + what + ": no joint named like " + like);
}

Result<LimbJoints> FindLimbs(const Skeleton& skeleton, const std::vector<int>& descendants,
                             BodySide side) {
  const bool left = side == BodySide::kLeft;
  LimbJoints limbs;
  limbs.upper_arm = FindSided(skeleton, side, UpperArmParts());
  if (limbs.upper_arm < 0) {
    return Missing(left ? "left upper arm" : "right upper arm",
                   left ? "LeftArm, lShldr or UpperArm_L" : "RightArm, rShldr or UpperArm_R");
  }
  limbs.hip = FindSided(skeleton, side, ThighParts());
  if (limbs.hip < 0) {
    return Missing(left ? "left thigh" : "right thigh",
                   left ? "LeftUpLeg, lThigh or UpperLeg_L" : "RightUpLeg, rThigh or UpperLeg_R");
  }
  limbs.elbow = ChainChild(skeleton, descendants, limbs.upper_arm);
  limbs.wrist = ChainChild(skeleton, descendants, limbs.elbow);
  limbs.knee = ChainChild(skeleton, descendants, limbs.hip);
  limbs.ankle = ChainChild(skeleton, descendants, limbs.knee);
  limbs.toes = ChainChild(skeleton, descendants, limbs.ankle);
  if (limbs.wrist < 0 || limbs.ankle < 0) {
    return Status::InvalidArgument(std::string("the ") + (left ? "left" : "right") +
                                   (limbs.wrist < 0 ? " arm" : " leg") +
                                   " ends before its third joint (upper limb, middle, end)");
  }
  return limbs;
}

// The nearest common ancestor of two joints.
int CommonAncestor(const Skeleton& skeleton, int a, int b) {
  const std::vector<int> path = PathToRoot(skeleton, a);
  for (int at = b; at >= 0; at = skeleton.joint(at).parent) {
    if (std::find(path.begin(), path.end(), at) != path.end()) return at;
  }
  return 0;
}

// The head: a joint named "head" below the chest, else the chest's chain child off the arms.
int FindHead(const Skeleton& skeleton, const std::vector<int>& descendants,
             const BodyLandmarks& body) {
  for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
    const int index = static_cast<int>(joint);
    const SidedJointName name = SplitJointSide(skeleton.joint(joint).name, {});
    if (name.side == BodySide::kCentre && name.part == "head" && index != body.chest &&
        IsAncestor(skeleton, body.chest, index)) {
      return index;
    }
  }
  int best = -1;
  int best_count = -1;
  for (size_t child = 0; child < skeleton.joint_count(); ++child) {
    const int index = static_cast<int>(child);
    if (skeleton.joint(child).parent != body.chest) continue;
    if (IsAncestor(skeleton, index, body.left.upper_arm) ||
        IsAncestor(skeleton, index, body.right.upper_arm)) {
      continue;
    }
    const int count = descendants[child];
    if (count > best_count) {
      best = index;
      best_count = count;
    }
  }
  return best;
}

}  // namespace

Result<BodyLandmarks> FindBodyLandmarks(const Skeleton& skeleton) {
  const std::vector<int> descendants = DescendantCounts(skeleton);
  BodyLandmarks body;
  MOTIF_ASSIGN_OR_RETURN(body.left, FindLimbs(skeleton, descendants, BodySide::kLeft));
  MOTIF_ASSIGN_OR_RETURN(body.right, FindLimbs(skeleton, descendants, BodySide::kRight));
  body.chest = CommonAncestor(skeleton, body.left.upper_arm, body.right.upper_arm);
  if (body.chest == body.pelvis || IsAncestor(skeleton, body.chest, body.left.hip)) {
    return Status::InvalidArgument("the arms do not meet on a chest above the pelvis");
  }
  body.spine = JointsBetween(skeleton, body.pelvis, body.chest);
  for (LimbJoints* limbs : {&body.left, &body.right}) {
    const int parent = skeleton.joint(limbs->upper_arm).parent;
    if (parent != body.chest) limbs->clavicle = parent;
  }
  body.head = FindHead(skeleton, descendants, body);
  if (body.head < 0) return Status::InvalidArgument("no head: the chest has no joint off the arms");
  body.neck = JointsBetween(skeleton, body.chest, body.head);
  return body;
}

}  // namespace motif
