#include "engine/synth/cmu_body_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/synth/activity_library.h"
#include "engine/synth/synth_random.h"
#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

// World positions of every joint for `params` (root at the grounded height, heading 0).
std::vector<Eigen::Vector3d> JointPositions(const std::vector<double>& params) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  const Skeleton& skeleton = body.skeleton();
  std::vector<Eigen::Quaterniond> local(skeleton.joint_count());
  body.Pose(params.data(), local.data());
  std::vector<Eigen::Vector3d> position(skeleton.joint_count());
  std::vector<Eigen::Quaterniond> frame(skeleton.joint_count());
  position[0] = Eigen::Vector3d(0, body.GroundedRootHeight(local.data()), 0);
  frame[0] = local[0];
  for (size_t joint_idx = 1; joint_idx < skeleton.joint_count(); ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    position[joint_idx] =
        position[joint.parent] +
        frame[joint.parent] * Eigen::Vector3d(joint.offset[0], joint.offset[1], joint.offset[2]);
    frame[joint_idx] = frame[joint.parent] * local[joint_idx];
  }
  return position;
}

std::vector<double> StandingParams() {
  const ActivityLibrary library = ActivityLibrary::Create(1, ActivityLibrary::ArchetypeCount());
  for (size_t idx = 0; idx < library.size(); ++idx) {
    if (library.activity(idx).name == "idle") return library.activity(idx).mean;
  }
  ADD_FAILURE() << "no idle activity";
  return {};
}

TEST(CmuBodyModel, SkeletonIsTheCanonicalCmuSkeleton) {
  const Skeleton& skeleton = CmuBodyModel::Get().skeleton();
  EXPECT_EQ(skeleton.family(), kCmuFamily);
  ASSERT_EQ(skeleton.joint_count(), 31u);
  EXPECT_TRUE(skeleton.Validate().ok());
  int end_sites = 0;
  int weighted = 0;
  for (size_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    EXPECT_EQ(joint.name, CmuCanonicalJointNames()[joint_idx]);
    EXPECT_EQ(joint.parent, CmuCanonicalParents()[joint_idx]);
    EXPECT_EQ(joint.weight, DefaultJointWeight(kCmuFamily, joint.name, joint_idx == 0));
    EXPECT_EQ(joint.channels.size(), joint_idx == 0 ? 6u : 3u);
    end_sites += joint.has_end_site;
    weighted += joint.weight > 0;
  }
  EXPECT_EQ(end_sites, 7);  // toes x2, head, fingers x2, thumbs x2
  EXPECT_EQ(weighted, 12);
  // A joint sits at the end of its parent's bone: the knee is a thigh length below the hip.
  const Joint& knee = skeleton.joint(skeleton.FindJoint("ltibia"));
  EXPECT_NEAR(std::hypot(knee.offset[0], knee.offset[1], knee.offset[2]), 6.57749, 1e-4);
  EXPECT_LT(knee.offset[1], -6.0);
  // Taking the skeleton through the canonicaliser changes nothing.
  Take take;
  take.skeleton = skeleton;
  EXPECT_TRUE(CanonicalizeSkeleton(&take));
  EXPECT_TRUE(take.skeleton.SameHierarchy(skeleton));
}

TEST(CmuBodyModel, SoftClampIsIdentityInsideAndNeverReachesTheLimits) {
  EXPECT_DOUBLE_EQ(CmuBodyModel::SoftClamp(45, -10, 170), 45);
  EXPECT_DOUBLE_EQ(CmuBodyModel::SoftClamp(0, -10, 170), 0);
  double previous = CmuBodyModel::SoftClamp(-400.5, -10, 170);
  for (double x = -400; x <= 400; x += 0.5) {
    const double y = CmuBodyModel::SoftClamp(x, -10, 170);
    EXPECT_GE(y, -10);
    EXPECT_LE(y, 170);
    if (x > -100 && x < 280) {  // strictly inside unless the input is absurd
      EXPECT_GT(y, -10);
      EXPECT_LT(y, 170);
    }
    EXPECT_GE(y, previous);               // monotone
    EXPECT_LE(y - previous, 0.5 + 1e-9);  // slope at most 1: continuous
    previous = y;
  }
}

TEST(CmuBodyModel, PoseInvertsThroughDofAngles) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  SynthRandom random(4);
  std::vector<double> params(body.param_count(), 0.0);
  std::vector<Eigen::Quaterniond> local(body.joint_count());
  for (int trial = 0; trial < 50; ++trial) {
    for (size_t dof_idx = 0; dof_idx < body.dof_count(); ++dof_idx) {
      const BodyDof& dof = body.dof(dof_idx);
      // Stay clear of gimbal lock (|ry| near 90) for the decomposition.
      const double lo = dof.axis == Axis::kY ? std::max(dof.lo_deg, -75.0) : dof.lo_deg;
      const double hi = dof.axis == Axis::kY ? std::min(dof.hi_deg, 75.0) : dof.hi_deg;
      params[dof_idx] = random.Uniform(lo, hi);
    }
    body.Pose(params.data(), local.data());
    for (size_t joint_idx = 1; joint_idx < body.joint_count(); ++joint_idx) {
      const std::array<double, 3> angles = body.DofAngles(joint_idx, local[joint_idx]);
      const Axis axes[3] = {Axis::kX, Axis::kY, Axis::kZ};
      for (int axis = 0; axis < 3; ++axis) {
        const int dof_idx = body.FindDof(body.skeleton().joint(joint_idx).name, axes[axis]);
        const double expected = dof_idx < 0 ? 0.0 : body.ClampedAngle(dof_idx, params[dof_idx]);
        EXPECT_NEAR(angles[axis], expected, 1e-6) << body.skeleton().joint(joint_idx).name;
      }
    }
  }
}

TEST(CmuBodyModel, MirrorDofMapsLeftToRight) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  double sign = 0;
  EXPECT_EQ(body.MirrorDof(body.FindDof("lfemur", Axis::kX), &sign),
            body.FindDof("rfemur", Axis::kX));
  EXPECT_EQ(sign, 1.0);
  EXPECT_EQ(body.MirrorDof(body.FindDof("rhumerus", Axis::kZ), &sign),
            body.FindDof("lhumerus", Axis::kZ));
  EXPECT_EQ(sign, -1.0);
  EXPECT_EQ(body.MirrorDof(body.FindDof("lowerback", Axis::kY), &sign),
            body.FindDof("lowerback", Axis::kY));
  EXPECT_EQ(body.FindDof("lhipjoint", Axis::kX), -1);
}

// Standing puts the feet on the floor and the head up; bending the knee (positive rx, the only
// way the ASF limits allow) swings the shin backwards; bending the elbow brings the forearm
// forwards (+z is forward).
TEST(CmuBodyModel, StandingPoseIsUprightAndKneesBendBackwards) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  const Skeleton& skeleton = body.skeleton();
  std::vector<double> params = StandingParams();
  ASSERT_EQ(params.size(), body.param_count());
  std::vector<Eigen::Vector3d> standing = JointPositions(params);
  const int head = skeleton.FindJoint("head");
  const int lfoot = skeleton.FindJoint("lfoot");
  const int ltibia = skeleton.FindJoint("ltibia");
  EXPECT_GT(standing[0].y(), 15.5);  // hip height of a CMU subject: 16-18 units
  EXPECT_LT(standing[0].y(), 17.5);
  EXPECT_GT(standing[head].y(), 27.0);
  EXPECT_LT(standing[lfoot].y(), 1.5);
  EXPECT_GT(standing[lfoot].y(), 0.0);

  params[body.FindDof("ltibia", Axis::kX)] = 90;
  std::vector<Eigen::Vector3d> bent = JointPositions(params);
  EXPECT_LT(bent[lfoot].z(), bent[ltibia].z() - 5.0) << "the shin swings backwards";
  // The other foot still stands: the root height is unchanged.
  EXPECT_NEAR(bent[0].y(), standing[0].y(), 0.3);

  params = StandingParams();
  params[body.FindDof("lradius", Axis::kX)] = 90;
  std::vector<Eigen::Vector3d> elbow = JointPositions(params);
  const int lwrist = skeleton.FindJoint("lwrist");
  const int lradius = skeleton.FindJoint("lradius");
  EXPECT_GT(elbow[lwrist].z(), elbow[lradius].z() + 1.5) << "the forearm comes forward";

  // Squatting (both hips and knees bent) lowers the root.
  params = StandingParams();
  for (const char* side : {"l", "r"}) {
    params[body.FindDof(std::string(side) + "femur", Axis::kX)] = -70;
    params[body.FindDof(std::string(side) + "tibia", Axis::kX)] = 90;
  }
  EXPECT_LT(JointPositions(params)[0].y(), standing[0].y() - 3.0);
}

}  // namespace
}  // namespace motif
