#include "formats/import/bvh_parser.h"

#include <gtest/gtest.h>

#include "tests/formats/import/import_test_util.h"

namespace motif {
namespace {

using import_test::FixturePath;
using import_test::ReadText;
using import_test::Rot;
using import_test::SameRotation;

std::string ReplaceAll(std::string text, const std::string& from, const std::string& to) {
  for (size_t pos = text.find(from); pos != std::string::npos;
       pos = text.find(from, pos + to.size())) {
    text.replace(pos, from.size(), to);
  }
  return text;
}

Take ParseOk(const std::string& text, double fps_override = 0) {
  Result<Take> take = ParseBvh(text, "test.bvh", fps_override);
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? std::move(take).value() : Take();
}

TEST(BvhParser, ReadsHierarchyOffsetsChannelsAndEndSites) {
  Take take = ParseOk(ReadText(FixturePath("custom_zxy.bvh")));
  const Skeleton& skeleton = take.skeleton;
  ASSERT_EQ(skeleton.joint_count(), 4u);
  EXPECT_EQ(skeleton.family(), "custom");
  EXPECT_EQ(skeleton.joint(0).name, "pelvis");
  EXPECT_EQ(skeleton.joint(1).name, "spine");
  EXPECT_EQ(skeleton.joint(2).name, "left arm");  // names may contain spaces
  EXPECT_EQ(skeleton.joint(3).name, "leg");
  EXPECT_EQ(skeleton.joint(0).parent, -1);
  EXPECT_EQ(skeleton.joint(1).parent, 0);
  EXPECT_EQ(skeleton.joint(2).parent, 1);
  EXPECT_EQ(skeleton.joint(3).parent, 0);
  EXPECT_EQ(skeleton.joint(0).offset, (std::array<double, 3>{1.5, 2.5, 3.5}));
  EXPECT_EQ(skeleton.joint(3).offset, (std::array<double, 3>{0, -10, 0}));
  EXPECT_FALSE(skeleton.joint(0).has_end_site);
  EXPECT_FALSE(skeleton.joint(1).has_end_site);
  EXPECT_TRUE(skeleton.joint(2).has_end_site);
  EXPECT_EQ(skeleton.joint(2).end_site, (std::array<double, 3>{8, 0, 0}));
  EXPECT_EQ(skeleton.joint(3).end_site, (std::array<double, 3>{0, -12, 0.5}));
  using C = ChannelType;
  EXPECT_EQ(skeleton.joint(0).channels,
            (std::vector<C>{C::kXPosition, C::kYPosition, C::kZPosition, C::kZRotation,
                            C::kXRotation, C::kYRotation}));
  EXPECT_EQ(skeleton.joint(2).channels,
            (std::vector<C>{C::kXRotation, C::kYRotation, C::kZRotation}));
  EXPECT_EQ(skeleton.joint(3).channels.size(), 6u);
  EXPECT_EQ(take.frame_count(), 3u);
  EXPECT_EQ(take.rotations.size(), 12u);
  EXPECT_EQ(take.source_path, "test.bvh");
}

TEST(BvhParser, ComposesRotationChannelsInListedOrder) {
  Take take = ParseOk(ReadText(FixturePath("custom_zxy.bvh")));
  for (size_t joint_idx = 0; joint_idx < 4; ++joint_idx) {
    EXPECT_TRUE(SameRotation(take.rotation(0, joint_idx), Eigen::Quaterniond::Identity()));
  }
  // Frame 1: pelvis Z X Y = 90 45 -30; spine Z X Y = 10 20 30; left arm X Y Z = -40 50 -60;
  // leg Y X Z = 15 -25 35 (after its ignored position channels).
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), Rot('z', 90) * Rot('x', 45) * Rot('y', -30)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 1), Rot('z', 10) * Rot('x', 20) * Rot('y', 30)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 2), Rot('x', -40) * Rot('y', 50) * Rot('z', -60)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 3), Rot('y', 15) * Rot('x', -25) * Rot('z', 35)));
  EXPECT_TRUE(SameRotation(take.rotation(2, 3), Rot('y', 16) * Rot('x', -24) * Rot('z', 36)));
}

TEST(BvhParser, RootPositionComesFromItsChannelsAndOtherPositionChannelsAreIgnored) {
  Take take = ParseOk(ReadText(FixturePath("custom_zxy.bvh")));
  EXPECT_EQ(take.root_positions[0], Eigen::Vector3d(0, 0, 0));  // channels, not the OFFSET
  EXPECT_EQ(take.root_positions[1], Eigen::Vector3d(10.5, 20.25, -30));
  EXPECT_EQ(take.root_positions[2], Eigen::Vector3d(11, 21, -31));
}

TEST(BvhParser, RootComponentsWithoutChannelsComeFromTheOffset) {
  const std::string text =
      "HIERARCHY\nROOT hips\n{\n OFFSET 1 2 3\n CHANNELS 4 Yposition Xrotation Yrotation "
      "Zrotation\n"
      " End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.01\n"
      "7 0 0 0\n8 0 90 0\n";
  Take take = ParseOk(text);
  ASSERT_EQ(take.frame_count(), 2u);
  EXPECT_EQ(take.root_positions[0], Eigen::Vector3d(1, 7, 3));
  EXPECT_EQ(take.root_positions[1], Eigen::Vector3d(1, 8, 3));
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), Rot('y', 90)));
  EXPECT_DOUBLE_EQ(take.fps, 100.0);
}

TEST(BvhParser, JointsWithFewOrNoRotationChannels) {
  const std::string text =
      "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n"
      "JOINT b\n{\nOFFSET 0 1 0\nCHANNELS 1 Zrotation\n"
      "JOINT c\n{\nOFFSET 0 1 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\n}\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.5\n1 2 3 30\n";
  Take take = ParseOk(text);
  ASSERT_EQ(take.joint_count(), 3u);
  EXPECT_TRUE(SameRotation(take.rotation(0, 0), Eigen::Quaterniond::Identity()));
  EXPECT_TRUE(SameRotation(take.rotation(0, 1), Rot('z', 30)));
  EXPECT_TRUE(SameRotation(take.rotation(0, 2), Eigen::Quaterniond::Identity()));
  EXPECT_DOUBLE_EQ(take.fps, 2.0);
}

TEST(BvhParser, AcceptsCrlfTabsAnyKeywordCaseAndTabSeparatedHeaders) {
  const std::string lf = ReadText(FixturePath("custom_zxy.bvh"));
  Take expected = ParseOk(lf);
  std::string variant = ReplaceAll(lf, "\n", "\r\n");
  variant = ReplaceAll(variant, "Frames: ", "Frames:\t");
  variant = ReplaceAll(variant, "Frame Time: ", "Frame Time:\t");
  variant = ReplaceAll(variant, "HIERARCHY", "hierarchy");
  variant = ReplaceAll(variant, "OFFSET", "Offset");
  variant = ReplaceAll(variant, " 0 ", "\t0  \t");
  variant = ReplaceAll(variant, "10.5", "+10.5");
  Take take = ParseOk(variant);
  ASSERT_EQ(take.frame_count(), expected.frame_count());
  ASSERT_EQ(take.joint_count(), expected.joint_count());
  for (size_t joint_idx = 0; joint_idx < take.joint_count(); ++joint_idx) {
    EXPECT_EQ(take.skeleton.joint(joint_idx).name, expected.skeleton.joint(joint_idx).name);
    EXPECT_EQ(take.skeleton.joint(joint_idx).offset, expected.skeleton.joint(joint_idx).offset);
  }
  for (size_t idx = 0; idx < take.rotations.size(); ++idx) {
    EXPECT_TRUE(SameRotation(take.rotations[idx], expected.rotations[idx], 0));
  }
  EXPECT_EQ(take.root_positions, expected.root_positions);
}

TEST(BvhParser, FrameRateIsTheInverseFrameTimeSnappedToIntegers) {
  const std::string base =
      "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 1\n";
  EXPECT_DOUBLE_EQ(ParseOk(base + "Frame Time: .0083333\n0\n").fps, 120.0);
  EXPECT_DOUBLE_EQ(ParseOk(base + "Frame Time: 0.00833333\n0\n").fps, 120.0);
  EXPECT_DOUBLE_EQ(ParseOk(base + "Frame Time: .033333\n0\n").fps, 30.0);
  EXPECT_NEAR(ParseOk(base + "Frame Time: 0.007\n0\n").fps, 1 / 0.007, 1e-9);  // not snapped
  Take overridden = ParseOk(base + "Frame Time: .033333\n0\n", 120.0);
  EXPECT_DOUBLE_EQ(overridden.fps, 120.0);
  EXPECT_DOUBLE_EQ(overridden.source_fps, 120.0);
}

TEST(BvhParser, BlankLinesAroundFramesAreSkipped) {
  const std::string text =
      "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\n\nFrames: 2\n"
      "Frame Time: 0.5\n\n1\n   \n2\n\n\n";
  Take take = ParseOk(text);
  EXPECT_EQ(take.frame_count(), 2u);
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), Rot('x', 2)));
}

}  // namespace
}  // namespace motif
