#include "engine/report/limb_side.h"

#include <gtest/gtest.h>

#include <string>

#include "engine/report/instance_player_script.h"

namespace motif {
namespace {

// The joint names of the families the archive holds (CMU ASF and BVH, Daz, a studio rig's
// "_L" / "_R", Blender's ".L", a Mixamo namespace) fall on their sides; the spines on none.
TEST(LimbSide, JointSidesOfEveryNamingFamily) {
  for (const char* left : {"lfemur", "lhipjoint", "lclavicle", "LeftUpLeg", "LHipJoint", "LThumb",
                           "lThigh", "lCollar", "leftEye", "UpperLeg_L", "Shoulder_L", "hand.L",
                           "L_Knee", "mixamorig:LeftArm", "LEFTFOOT"}) {
    EXPECT_EQ(JointSide(left), 1) << left;
  }
  for (const char* right :
       {"rfemur", "rradius", "RightHand", "RHipJoint", "RThumb", "rShin", "rButtock", "Toes_R",
        "UpperArm_R", "foot.r", "R_Elbow", "mixamorig:RightFoot"}) {
    EXPECT_EQ(JointSide(right), 2) << right;
  }
  for (const char* centre :
       {"root",       "lowerback", "lowerneck", "upperback", "thorax",    "head", "Hips",
        "Spine",      "Spine1",    "Neck",      "l",         "r",         "ROOT", "Root",
        "joint_Root", "hip",       "abdomen",   "chest",     "LowerBack", "Chest"}) {
    EXPECT_EQ(JointSide(centre), 0) << centre;
  }
}

// The player takes its colours from the figure's JSON (LimbSideColoursJson), never its own.
TEST(LimbSide, ThePlayerHasNoColourTableOfItsOwn) {
  EXPECT_EQ(LimbSideColoursJson(), R"(["#555","#1f6fd1","#d62728"])");
  const std::string script = kInstancePlayerScript;
  EXPECT_NE(script.find("COL=F.colours"), std::string::npos);
  for (const char* colour : {"#555", "#1f6fd1", "#d62728"}) {
    EXPECT_EQ(script.find(colour), std::string::npos) << colour;
  }
}

}  // namespace
}  // namespace motif
