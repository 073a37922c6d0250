// The one side-from-name rule (formats/motion/joint_side.h) on the namings both of its readers
// meet: the report's colours (JointSide) and the body landmarks (SplitJointSide with parts).
#include "formats/motion/joint_side.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace motif {
namespace {

const std::vector<std::string> kParts = {"arm",   "upperarm", "shldr", "humerus",
                                         "upleg", "upperleg", "thigh", "femur"};

void ExpectSplit(const std::string& name, BodySide side, const std::string& part) {
  const SidedJointName sided = SplitJointSide(name, kParts);
  EXPECT_EQ(sided.side, side) << name;
  EXPECT_EQ(sided.part, part) << name;
}

// CMU ASF and BVH, Daz, a studio rig, Blender and Mixamo: the side on its own, and the part.
TEST(JointSide, ReadsTheTaggedNamesOfEveryFamily) {
  EXPECT_EQ(JointSide("lfemur"), 1);
  EXPECT_EQ(JointSide("rhumerus"), 2);
  EXPECT_EQ(JointSide("LeftUpLeg"), 1);
  EXPECT_EQ(JointSide("RHipJoint"), 2);
  EXPECT_EQ(JointSide("lThigh"), 1);
  EXPECT_EQ(JointSide("UpperArm_R"), 2);
  EXPECT_EQ(JointSide("hand.L"), 1);
  EXPECT_EQ(JointSide("R_Elbow"), 2);
  EXPECT_EQ(JointSide("mixamorig:LeftArm"), 1);
  EXPECT_EQ(JointSide("rig|RightFoot"), 2);
  for (const char* centre : {"root", "lowerback", "ROOT", "Hips", "head", "l", "joint_Root"}) {
    EXPECT_EQ(JointSide(centre), 0) << centre;
  }
  ExpectSplit("lfemur", BodySide::kLeft, "femur");
  ExpectSplit("LeftUpLeg", BodySide::kLeft, "upleg");
  ExpectSplit("rShldr", BodySide::kRight, "shldr");
  ExpectSplit("UpperArm_L", BodySide::kLeft, "upperarm");
  ExpectSplit("L_Thigh", BodySide::kLeft, "thigh");
  ExpectSplit("mixamorig:RightArm", BodySide::kRight, "arm");
  ExpectSplit("Hips", BodySide::kCentre, "hips");
  ExpectSplit("leftEye", BodySide::kLeft, "eye");
}

// A side glued to its part without a capital or separator counts beside a known part only.
TEST(JointSide, ReadsAGluedSideBesideAKnownPartOnly) {
  ExpectSplit("UpperArmLeft", BodySide::kLeft, "upperarm");
  ExpectSplit("thigh_right", BodySide::kRight, "thigh");
  ExpectSplit("upperarmL", BodySide::kLeft, "upperarm");
  ExpectSplit("LARM", BodySide::kLeft, "arm");
  ExpectSplit("Rarm", BodySide::kRight, "arm");
  ExpectSplit("lShld_r", BodySide::kLeft, "shldr");  // separators aside, "lshldr"
  for (const char* alone :
       {"UpperArmLeft", "upperarmL", "LARM", "Rarm", "Tail", "Upright", "Larynx"}) {
    EXPECT_EQ(JointSide(alone), 0) << alone;
  }
  ExpectSplit("Tail", BodySide::kCentre, "tail");
}

}  // namespace
}  // namespace motif
