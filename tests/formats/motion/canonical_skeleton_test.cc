#include "formats/motion/canonical_skeleton.h"

#include <gtest/gtest.h>

#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

const char* kBvhNames[] = {
    "Hips",         "LHipJoint",      "LeftUpLeg",      "LeftLeg",         "LeftFoot",
    "LeftToeBase",  "RHipJoint",      "RightUpLeg",     "RightLeg",        "RightFoot",
    "RightToeBase", "LowerBack",      "Spine",          "Spine1",          "Neck",
    "Neck1",        "Head",           "LeftShoulder",   "LeftArm",         "LeftForeArm",
    "LeftHand",     "LeftFingerBase", "LeftHandIndex1", "LThumb",          "RightShoulder",
    "RightArm",     "RightForeArm",   "RightHand",      "RightFingerBase", "RightHandIndex1",
    "RThumb"};

// The CMU skeleton under BVH names, with the right leg listed before the left one, and one
// frame whose rotation of joint k is about X by k/100 radians (so reordering can be checked).
Take ShuffledCmuTake() {
  const auto& parents = CmuCanonicalParents();
  std::vector<int> order;  // take index -> canonical index
  for (int idx = 6; idx <= 10; ++idx) order.push_back(idx);
  for (int idx = 0; idx <= 5; ++idx) order.push_back(idx);
  for (int idx = 11; idx <= 30; ++idx) order.push_back(idx);
  std::swap(order[0], order[5]);  // root first
  // order now: 0(root), 7..10, 6, 1..5, 11..30 -- fix so parents precede children:
  order = {0, 6, 7, 8, 9, 10, 1, 2, 3, 4, 5};
  for (int idx = 11; idx <= 30; ++idx) order.push_back(idx);
  std::vector<int> take_index_of(31);
  for (int take_idx = 0; take_idx < 31; ++take_idx) take_index_of[order[take_idx]] = take_idx;
  std::vector<Joint> joints(31);
  Take take;
  for (int take_idx = 0; take_idx < 31; ++take_idx) {
    const int canonical = order[take_idx];
    joints[take_idx].name = kBvhNames[canonical];
    joints[take_idx].parent = parents[canonical] < 0 ? -1 : take_index_of[parents[canonical]];
    take.rotations.push_back(AxisRotation(Axis::kX, canonical / 100.0));
  }
  take.skeleton = Skeleton("custom", joints);
  take.root_positions.emplace_back(0, 0, 0);
  return take;
}

TEST(CanonicalSkeleton, MapsBvhNamesAndOrderToCanonical) {
  Take take = ShuffledCmuTake();
  ASSERT_TRUE(take.skeleton.Validate().ok());
  ASSERT_TRUE(CanonicalizeSkeleton(&take));
  EXPECT_EQ(take.skeleton.family(), "cmu31");
  const auto& names = CmuCanonicalJointNames();
  for (size_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
    EXPECT_EQ(take.skeleton.joint(joint_idx).name, names[joint_idx]);
    EXPECT_EQ(take.skeleton.joint(joint_idx).parent, CmuCanonicalParents()[joint_idx]);
    EXPECT_NEAR(RotationAngleBetween(take.rotation(0, joint_idx), Eigen::Quaterniond::Identity()),
                joint_idx / 100.0, 1e-12);
  }
  // Weights: the twelve joints of docs/design/algorithm.md, step 1.
  float total = 0;
  for (const Joint& joint : take.skeleton.joints()) total += joint.weight;
  EXPECT_EQ(total, 12.0f);
  EXPECT_EQ(take.skeleton.joint(take.skeleton.FindJoint("lhipjoint")).weight, 0.0f);
  EXPECT_EQ(take.skeleton.joint(take.skeleton.FindJoint("lfemur")).weight, 1.0f);
}

TEST(CanonicalSkeleton, LeavesOtherSkeletonsCustom) {
  Take take = ShuffledCmuTake();
  take.skeleton.mutable_joints()[30].name = "RPinky";
  EXPECT_FALSE(CanonicalizeSkeleton(&take));
  EXPECT_EQ(take.skeleton.family(), "custom");
  EXPECT_EQ(CmuCanonicalName("LeftUpLeg"), "lfemur");
  EXPECT_EQ(CmuCanonicalName("lfemur"), "lfemur");
  EXPECT_EQ(CmuCanonicalName("rShldr"), "");
}

TEST(CanonicalSkeleton, ConformReordersOrRefuses) {
  Take reference = ShuffledCmuTake();
  ASSERT_TRUE(CanonicalizeSkeleton(&reference));
  Take take = ShuffledCmuTake();
  ASSERT_TRUE(CanonicalizeSkeleton(&take));
  EXPECT_TRUE(ConformToSkeleton(reference.skeleton, &take).ok());
  Take other = ShuffledCmuTake();
  other.source_path = "x.bvh";
  other.skeleton.mutable_joints()[30].name = "RPinky";
  EXPECT_FALSE(CanonicalizeSkeleton(&other));
  Status status = ConformToSkeleton(reference.skeleton, &other);
  ASSERT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("x.bvh"), std::string::npos);
  // Daz-style weights for a custom skeleton.
  EXPECT_EQ(DefaultJointWeight("custom", "rShldr", false), 1.0f);
  EXPECT_EQ(DefaultJointWeight("custom", "rForeArm", false), 1.0f);
  EXPECT_EQ(DefaultJointWeight("custom", "lThigh", false), 1.0f);
  EXPECT_EQ(DefaultJointWeight("custom", "lFoot", false), 0.0f);
  EXPECT_EQ(DefaultJointWeight("custom", "rIndex1", false), 0.0f);
}

}  // namespace
}  // namespace motif
