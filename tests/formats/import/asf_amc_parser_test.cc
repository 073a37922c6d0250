#include <gtest/gtest.h>

#include "formats/import/amc_parser.h"
#include "formats/import/asf_parser.h"
#include "tests/formats/import/import_test_util.h"

namespace motif {
namespace {

using import_test::FixturePath;
using import_test::ReadText;
using import_test::Rot;
using import_test::SameRotation;

AsfSkeleton TinyAsf() {
  Result<AsfSkeleton> asf = ParseAsf(ReadText(FixturePath("tiny.asf")), "tiny.asf");
  EXPECT_TRUE(asf.ok()) << asf.status().ToString();
  return asf.ok() ? std::move(asf).value() : AsfSkeleton();
}

Take TinyTake(double fps = 120) {
  Result<Take> take = ParseAmc(TinyAsf(), ReadText(FixturePath("tiny_01.amc")), "tiny_01.amc", fps);
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? std::move(take).value() : Take();
}

Eigen::Quaterniond Conjugated(const Eigen::Quaterniond& axis, const Eigen::Quaterniond& motion) {
  return axis * motion * axis.conjugate();
}

TEST(AsfParser, ReadsUnitsRootBonesAndHierarchy) {
  AsfSkeleton asf = TinyAsf();
  EXPECT_DOUBLE_EQ(asf.length_unit, 0.5);
  EXPECT_DOUBLE_EQ(asf.meters_per_unit, 0.0254 / 0.5);
  EXPECT_TRUE(asf.angles_in_degrees);
  EXPECT_EQ(asf.root_order, (std::vector<AsfDof>{AsfDof::kTx, AsfDof::kTy, AsfDof::kTz, AsfDof::kRx,
                                                 AsfDof::kRy, AsfDof::kRz}));
  ASSERT_EQ(asf.bones.size(), 4u);
  // Depth first from the root, children in listed order: root -> hip -> thigh -> shin; spine.
  EXPECT_EQ(asf.bones[0].name, "hip");
  EXPECT_EQ(asf.bones[1].name, "thigh");
  EXPECT_EQ(asf.bones[2].name, "shin");
  EXPECT_EQ(asf.bones[3].name, "spine");
  EXPECT_EQ(asf.bones[0].parent, -1);
  EXPECT_EQ(asf.bones[1].parent, 0);
  EXPECT_EQ(asf.bones[2].parent, 1);
  EXPECT_EQ(asf.bones[3].parent, -1);
  EXPECT_TRUE(asf.bones[0].dofs.empty());
  EXPECT_EQ(asf.bones[3].dofs, (std::vector<AsfDof>{AsfDof::kRz, AsfDof::kRx, AsfDof::kTx}));
  EXPECT_EQ(asf.bones[1].direction, Eigen::Vector3d(0, -1, 0));
  EXPECT_DOUBLE_EQ(asf.bones[1].length, 6);
  // "axis 0 0 20 XYZ": x first, so C = Rz(20) Ry(0) Rx(0).
  EXPECT_TRUE(SameRotation(asf.bones[1].axis_rotation, Rot('z', 20)));
  // "axis 10 -5 30 ZYX": one angle per letter, z first: C = Rx(30) Ry(-5) Rz(10).
  EXPECT_TRUE(SameRotation(asf.bones[3].axis_rotation, Rot('x', 30) * Rot('y', -5) * Rot('z', 10)));
  EXPECT_EQ(asf.FindBone("shin"), 2);
  EXPECT_EQ(asf.FindBone("root"), -1);
}

TEST(AsfParser, JointSkeletonUsesParentBoneVectorsAsOffsets) {
  Skeleton skeleton = AsfToSkeleton(TinyAsf());
  ASSERT_EQ(skeleton.joint_count(), 5u);
  ASSERT_TRUE(skeleton.Validate().ok());
  EXPECT_EQ(skeleton.joint(0).name, "root");
  EXPECT_EQ(skeleton.joint(1).name, "hip");
  EXPECT_EQ(skeleton.joint(4).name, "spine");
  EXPECT_EQ(skeleton.joint(2).parent, 1);
  EXPECT_EQ(skeleton.joint(4).parent, 0);
  EXPECT_EQ(skeleton.joint(1).offset, (std::array<double, 3>{0, 0, 0}));   // root position
  EXPECT_EQ(skeleton.joint(2).offset, (std::array<double, 3>{2, 0, 0}));   // hip 1 0 0 * 2
  EXPECT_EQ(skeleton.joint(3).offset, (std::array<double, 3>{0, -6, 0}));  // thigh 0 -1 0 * 6
  EXPECT_FALSE(skeleton.joint(1).has_end_site);
  EXPECT_TRUE(skeleton.joint(3).has_end_site);  // shin is a leaf: its own vector
  EXPECT_EQ(skeleton.joint(3).end_site, (std::array<double, 3>{0, -5, 0}));
  EXPECT_EQ(skeleton.joint(4).end_site, (std::array<double, 3>{0, 4, 0}));
  EXPECT_EQ(skeleton.joint(0).channels.size(), 6u);
  EXPECT_EQ(skeleton.joint(1).channels.size(), 3u);
}

TEST(AmcParser, RotationIsTheDofCompositionConjugatedByTheBoneAxis) {
  Take take = TinyTake();
  ASSERT_EQ(take.frame_count(), 2u);
  ASSERT_EQ(take.joint_count(), 5u);
  EXPECT_EQ(take.source_path, "tiny_01.amc");
  EXPECT_DOUBLE_EQ(take.meters_per_unit, 0.0254 / 0.5);
  // root: order TX TY TZ RX RY RZ, identity axis; rx first: M = Rz Ry Rx.
  EXPECT_EQ(take.root_positions[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(SameRotation(take.rotation(0, 0), Rot('z', 30) * Rot('y', 20) * Rot('x', 10)));
  // hip has no dof.
  EXPECT_TRUE(SameRotation(take.rotation(0, 1), Eigen::Quaterniond::Identity()));
  // thigh: dof rx ry rz = -30 5 10, C = Rz(20).
  EXPECT_TRUE(SameRotation(take.rotation(0, 2),
                           Conjugated(Rot('z', 20), Rot('z', 10) * Rot('y', 5) * Rot('x', -30))));
  EXPECT_TRUE(SameRotation(take.rotation(0, 3), Conjugated(Rot('z', 20), Rot('x', 45))));
  // spine: dof rz rx tx = 15 -25 0.5 (rz applied first; tx ignored), C = Rx(30) Ry(-5) Rz(10).
  const Eigen::Quaterniond spine_axis = Rot('x', 30) * Rot('y', -5) * Rot('z', 10);
  EXPECT_TRUE(
      SameRotation(take.rotation(0, 4), Conjugated(spine_axis, Rot('x', -25) * Rot('z', 15))));
  // Frame 2 lists its bones in another order.
  EXPECT_EQ(take.root_positions[1], Eigen::Vector3d(1.5, 2.5, 3.5));
  EXPECT_TRUE(SameRotation(take.rotation(1, 0), Rot('z', 31) * Rot('y', 21) * Rot('x', 11)));
  EXPECT_TRUE(SameRotation(take.rotation(1, 2),
                           Conjugated(Rot('z', 20), Rot('z', 11) * Rot('y', 6) * Rot('x', -31))));
  EXPECT_TRUE(
      SameRotation(take.rotation(1, 4), Conjugated(spine_axis, Rot('x', -24) * Rot('z', 16))));
}

TEST(AmcParser, HonoursTheRootOrderAndRadians) {
  std::string asf_text = ReadText(FixturePath("tiny.asf"));
  asf_text.replace(asf_text.find("order TX TY TZ RX RY RZ"), 23, "order RZ TY RX TX RY TZ");
  asf_text.replace(asf_text.find("angle deg"), 9, "angle rad");
  Result<AsfSkeleton> asf = ParseAsf(asf_text, "rad.asf");
  ASSERT_TRUE(asf.ok()) << asf.status().ToString();
  // Without :DEGREES/:RADIANS the ASF's unit (rad) applies; the axis angles are radians too.
  const std::string amc = "1\nroot 0.1 2 0.2 1 0.3 3\nthigh 0 0 0\nshin 0.5\nspine 0 0 0\n";
  Result<Take> take = ParseAmc(*asf, amc, "rad.amc", 60);
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  EXPECT_EQ(take->root_positions[0], Eigen::Vector3d(1, 2, 3));
  const double to_degrees = 180 / kPi;
  EXPECT_TRUE(SameRotation(
      take->rotation(0, 0),
      Rot('y', 0.3 * to_degrees) * Rot('x', 0.2 * to_degrees) * Rot('z', 0.1 * to_degrees)));
  EXPECT_TRUE(SameRotation(take->rotation(0, 3),
                           Conjugated(Rot('z', 20 * to_degrees), Rot('x', 0.5 * to_degrees))));
  EXPECT_DOUBLE_EQ(take->fps, 60);
  // :DEGREES in the AMC overrides the ASF's radians.
  Result<Take> degrees = ParseAmc(*asf, ":DEGREES\n" + amc, "deg.amc", 60);
  ASSERT_TRUE(degrees.ok());
  EXPECT_TRUE(SameRotation(degrees->rotation(0, 0), Rot('y', 0.3) * Rot('x', 0.2) * Rot('z', 0.1)));
}

TEST(AmcParser, FrameNumbersMayStartAnywhereButMustBeConsecutive) {
  const std::string frame = "root 0 0 0 0 0 0\nthigh 0 0 0\nshin 0\nspine 0 0 0\n";
  Result<Take> take = ParseAmc(TinyAsf(), "7\n" + frame + "8\n" + frame, "a.amc", 120);
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  EXPECT_EQ(take->frame_count(), 2u);
  Result<Take> gap = ParseAmc(TinyAsf(), "7\n" + frame + "9\n" + frame, "a.amc", 120);
  ASSERT_FALSE(gap.ok());
  EXPECT_NE(gap.status().message().find("a.amc:6: frame number 9 follows frame 7"),
            std::string::npos)
      << gap.status().message();
}

TEST(AmcParser, BonesWithoutDofMayBeListedWithoutValues) {
  const std::string amc = "1\nroot 0 0 0 0 0 0\nhip\nthigh 0 0 0\nshin 0\nspine 0 0 0\n";
  Result<Take> take = ParseAmc(TinyAsf(), amc, "a.amc", 120);
  ASSERT_TRUE(take.ok()) << take.status().ToString();
}

TEST(AmcParser, RejectsANonPositiveRate) {
  Result<Take> take = ParseAmc(TinyAsf(), ReadText(FixturePath("tiny_01.amc")), "a.amc", 0);
  ASSERT_FALSE(take.ok());
  EXPECT_TRUE(take.status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
