// The root that moves (formats/import/animated_root.h): a studio rig's static top joint is
// folded into the animated joint below it, exactly; every other hierarchy is left as it is.
#include "formats/import/animated_root.h"

#include <gtest/gtest.h>

#include <string>

#include "formats/import/bvh_parser.h"
#include "tests/formats/import/import_test_util.h"

namespace motif {
namespace {

using import_test::Rot;
using import_test::SameRotation;

// A rig as studios write it: a top joint with 6 channels over `hips` (6 channels, offset far
// from the origin) over `spine` and `leg`. `top` is the top joint's values in both frames.
std::string StudioRig(const std::string& top_frame0, const std::string& top_frame1,
                      bool hips_has_sibling = false, bool hips_has_position = true) {
  const std::string hips_channels =
      hips_has_position ? "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
                        : "CHANNELS 3 Zrotation Xrotation Yrotation";
  std::string text =
      "HIERARCHY\nROOT joint_Root\n{\n OFFSET 0 0 0\n"
      " CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      " JOINT hips\n {\n  OFFSET 4.5 91.5 -427\n  " + hips_channels + "\n"
      "  JOINT spine\n  {\n   OFFSET 15 0 0\n   CHANNELS 3 Zrotation Xrotation Yrotation\n"
      "   End Site\n   {\n    OFFSET 6 0 0\n   }\n  }\n"
      "  JOINT leg\n  {\n   OFFSET 0 -40 0\n   CHANNELS 3 Zrotation Xrotation Yrotation\n"
      "   End Site\n   {\n    OFFSET 0 -40 0\n   }\n  }\n }\n";
  if (hips_has_sibling) {
    text += " JOINT prop\n {\n  OFFSET 1 0 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n"
            "  End Site\n  {\n   OFFSET 1 0 0\n  }\n }\n";
  }
  text += "}\nMOTION\nFrames: 2\nFrame Time: 0.0333333\n";
  const std::string hips0 = hips_has_position ? "-0.5 80 -4 90 -4 11" : "90 -4 11";
  const std::string hips1 = hips_has_position ? "20 81 -3 90 -4 41" : "90 -4 41";
  const std::string rest = hips_has_sibling ? " 1 2 3 4 5 6 7 8 9" : " 1 2 3 4 5 6";
  text += top_frame0 + " " + hips0 + rest + "\n" + top_frame1 + " " + hips1 + rest + "\n";
  return text;
}

Take Parse(const std::string& text) {
  Result<Take> take = ParseBvh(text, "rig.bvh", 0);
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? std::move(take).value() : Take();
}

TEST(AnimatedRoot, AStaticTopJointAtTheOriginLeavesAndTheHipsBecomeTheRoot) {
  const Take take = Parse(StudioRig("0 0 0 0 0 0", "0 0 0 0 0 0"));
  ASSERT_EQ(take.joint_count(), 3u);
  EXPECT_EQ(take.skeleton.joint(0).name, "hips");
  EXPECT_EQ(take.skeleton.joint(0).parent, -1);
  EXPECT_EQ(take.skeleton.joint(1).parent, 0);
  EXPECT_EQ(take.skeleton.joint(2).parent, 0);
  EXPECT_EQ(take.skeleton.joint(0).offset, (std::array<double, 3>{4.5, 91.5, -427}));
  EXPECT_TRUE(take.skeleton.Validate().ok());
  // The hips' position channels are the root's motion, its rotation the root rotation.
  EXPECT_EQ(take.root_positions[0], Eigen::Vector3d(-0.5, 80, -4));
  EXPECT_EQ(take.root_positions[1], Eigen::Vector3d(20, 81, -3));
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), Rot('z', 90) * Rot('x', -4) * Rot('y', 41)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 1), Rot('z', 1) * Rot('x', 2) * Rot('y', 3)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 2), Rot('z', 4) * Rot('x', 5) * Rot('y', 6)));
  EXPECT_EQ(take.rotations.size(), 6u);
}

TEST(AnimatedRoot, AStaticTopJointsTransformIsFoldedIntoTheNewRoot) {
  // The top joint stands at (10, 0, 0), turned 90 degrees about Y, in both frames.
  const Take take = Parse(StudioRig("10 0 0 0 0 90", "10 0 0 0 0 90"));
  ASSERT_EQ(take.joint_count(), 3u);
  const Eigen::Quaterniond turn = Rot('y', 90);
  const Eigen::Vector3d expected = Eigen::Vector3d(10, 0, 0) + turn * Eigen::Vector3d(20, 81, -3);
  EXPECT_LT((take.root_positions[1] - expected).norm(), 1e-9);
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), turn * Rot('z', 90) * Rot('x', -4) * Rot('y', 41)));
  const Eigen::Vector3d offset = Eigen::Vector3d(10, 0, 0) + turn * Eigen::Vector3d(4.5, 91.5, -427);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(take.skeleton.joint(0).offset[axis], offset[axis], 1e-9);
  }
}

TEST(AnimatedRoot, ATopJointThatMovesStaysTheRoot) {
  const Take take = Parse(StudioRig("0 0 0 0 0 0", "5 0 0 0 0 0"));
  ASSERT_EQ(take.joint_count(), 4u);
  EXPECT_EQ(take.skeleton.joint(0).name, "joint_Root");
  EXPECT_EQ(take.root_positions[1], Eigen::Vector3d(5, 0, 0));
  const Take turning = Parse(StudioRig("0 0 0 0 0 0", "0 0 0 0 0 1"));
  EXPECT_EQ(turning.joint_count(), 4u);
}

TEST(AnimatedRoot, AStaticTopJointWithTwoChildrenOrAChildWithoutPositionsStaysTheRoot) {
  EXPECT_EQ(Parse(StudioRig("0 0 0 0 0 0", "0 0 0 0 0 0", /*hips_has_sibling=*/true))
                .skeleton.joint(0)
                .name,
            "joint_Root");
  EXPECT_EQ(Parse(StudioRig("0 0 0 0 0 0", "0 0 0 0 0 0", false, /*hips_has_position=*/false))
                .skeleton.joint(0)
                .name,
            "joint_Root");
}

TEST(AnimatedRoot, AOneFrameStudioTakeIsRerootedToo) {
  std::string text = StudioRig("0 0 0 0 0 0", "0 0 0 0 0 0");
  text.replace(text.find("Frames: 2"), 9, "Frames: 1");
  text.erase(text.rfind('\n', text.size() - 2) + 1);  // the second frame line
  const Take take = Parse(text);
  ASSERT_EQ(take.frame_count(), 1u);
  EXPECT_EQ(take.skeleton.joint(0).name, "hips");
}

}  // namespace
}  // namespace motif
