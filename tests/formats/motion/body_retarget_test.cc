// Finding the body parts of skeletons of several namings (body_landmarks.h) and mapping a take
// onto the CMU body (body_retarget.h): every bone the distance weighs points where the source's
// does, whatever the source's rest pose, and the elbows and knees stay hinges.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/body_kinematics.h"
#include "formats/motion/body_landmarks.h"
#include "formats/motion/body_retarget.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/cmu_rest_pose.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

struct JointSpec {
  const char* name;
  const char* parent;
  Vec offset;
};

Skeleton Build(const std::vector<JointSpec>& specs) {
  std::vector<Joint> joints;
  for (const JointSpec& spec : specs) {
    Joint joint;
    joint.name = spec.name;
    for (size_t index = 0; index < joints.size(); ++index) {
      if (joints[index].name == spec.parent) joint.parent = static_cast<int>(index);
    }
    joint.offset = {spec.offset.x(), spec.offset.y(), spec.offset.z()};
    joints.push_back(joint);
  }
  return Skeleton("custom", std::move(joints));
}

// A Daz-like T-pose (cgspeed's Daz BVH names).
Skeleton DazLike() {
  return Build({{"hip", "", {0, 0, 0}},
                {"abdomen", "hip", {0, 2, 0}},
                {"chest", "abdomen", {0, 2, 0}},
                {"neck", "chest", {0, 2, 0}},
                {"head", "neck", {0, 1, 0}},
                {"lCollar", "chest", {0.5, 1.8, 0}},
                {"lShldr", "lCollar", {1, 0, 0}},
                {"lForeArm", "lShldr", {3, 0, 0}},
                {"lHand", "lForeArm", {3, 0, 0}},
                {"rCollar", "chest", {-0.5, 1.8, 0}},
                {"rShldr", "rCollar", {-1, 0, 0}},
                {"rForeArm", "rShldr", {-3, 0, 0}},
                {"rHand", "rForeArm", {-3, 0, 0}},
                {"lButtock", "hip", {1, -0.5, 0}},
                {"lThigh", "lButtock", {0, -0.5, 0}},
                {"lShin", "lThigh", {0, -4, 0}},
                {"lFoot", "lShin", {0, -4, 0}},
                {"rButtock", "hip", {-1, -0.5, 0}},
                {"rThigh", "rButtock", {0, -0.5, 0}},
                {"rShin", "rThigh", {0, -4, 0}},
                {"rFoot", "rShin", {0, -4, 0}}});
}

// A studio rig whose zero rotations fold the body up: every bone along +x or -x of its parent,
// as when a rig's joint orients live in the motion (names as ../shared/data/bandai2's).
Skeleton FoldedStudioRig() {
  return Build({{"Hips", "", {0, 0, 0}},
                {"Spine", "Hips", {2, 0, 0}},
                {"Chest", "Spine", {2, 0, 0}},
                {"Neck", "Chest", {2, 0, 0}},
                {"Head", "Neck", {1, 0, 0}},
                {"Shoulder_L", "Chest", {1.8, 0, 0.5}},
                {"UpperArm_L", "Shoulder_L", {1, 0, 0}},
                {"LowerArm_L", "UpperArm_L", {3, 0, 0}},
                {"Hand_L", "LowerArm_L", {3, 0, 0}},
                {"Shoulder_R", "Chest", {1.8, 0, -0.5}},
                {"UpperArm_R", "Shoulder_R", {-1, 0, 0}},
                {"LowerArm_R", "UpperArm_R", {-3, 0, 0}},
                {"Hand_R", "LowerArm_R", {-3, 0, 0}},
                {"UpperLeg_L", "Hips", {-0.2, -1, 0}},
                {"LowerLeg_L", "UpperLeg_L", {4, 0, 0}},
                {"Foot_L", "LowerLeg_L", {4, 0, 0}},
                {"Toes_L", "Foot_L", {1, 0, 0}},
                {"UpperLeg_R", "Hips", {-0.2, 1, 0}},
                {"LowerLeg_R", "UpperLeg_R", {-4, 0, 0}},
                {"Foot_R", "LowerLeg_R", {-4, 0, 0}},
                {"Toes_R", "Foot_R", {-1, 0, 0}}});
}

int Index(const Skeleton& skeleton, const char* name) { return skeleton.FindJoint(name); }

TEST(BodyLandmarks, FindsTheDazNames) {
  const Skeleton daz = DazLike();
  Result<BodyLandmarks> body = FindBodyLandmarks(daz);
  ASSERT_TRUE(body.ok()) << body.status().ToString();
  EXPECT_EQ(body->pelvis, 0);
  EXPECT_EQ(body->spine, std::vector<int>{Index(daz, "abdomen")});
  EXPECT_EQ(body->chest, Index(daz, "chest"));
  EXPECT_EQ(body->neck, std::vector<int>{Index(daz, "neck")});
  EXPECT_EQ(body->head, Index(daz, "head"));
  EXPECT_EQ(body->left.clavicle, Index(daz, "lCollar"));
  EXPECT_EQ(body->left.upper_arm, Index(daz, "lShldr"));
  EXPECT_EQ(body->left.elbow, Index(daz, "lForeArm"));
  EXPECT_EQ(body->left.wrist, Index(daz, "lHand"));
  EXPECT_EQ(body->right.hip, Index(daz, "rThigh"));
  EXPECT_EQ(body->right.knee, Index(daz, "rShin"));
  EXPECT_EQ(body->right.ankle, Index(daz, "rFoot"));
  EXPECT_EQ(body->right.toes, -1);
}

TEST(BodyLandmarks, FindsTheStudioAndCmuNames) {
  const Skeleton rig = FoldedStudioRig();
  Result<BodyLandmarks> body = FindBodyLandmarks(rig);
  ASSERT_TRUE(body.ok()) << body.status().ToString();
  EXPECT_EQ(body->left.clavicle, Index(rig, "Shoulder_L"));
  EXPECT_EQ(body->left.upper_arm, Index(rig, "UpperArm_L"));
  EXPECT_EQ(body->right.toes, Index(rig, "Toes_R"));
  EXPECT_EQ(body->chest, Index(rig, "Chest"));

  const Skeleton& cmu = CmuRestSkeleton();
  body = FindBodyLandmarks(cmu);
  ASSERT_TRUE(body.ok()) << body.status().ToString();
  EXPECT_EQ(body->spine, (std::vector<int>{Index(cmu, "lowerback"), Index(cmu, "upperback")}));
  EXPECT_EQ(body->chest, Index(cmu, "thorax"));
  EXPECT_EQ(body->neck, (std::vector<int>{Index(cmu, "lowerneck"), Index(cmu, "upperneck")}));
  EXPECT_EQ(body->left.upper_arm, Index(cmu, "lhumerus"));
  EXPECT_EQ(body->left.wrist, Index(cmu, "lwrist"));
  EXPECT_EQ(body->right.hip, Index(cmu, "rfemur"));
  EXPECT_EQ(body->right.toes, Index(cmu, "rtoes"));
}

TEST(BodyLandmarks, SaysWhichPartIsMissing) {
  Skeleton armless = Build({{"Hips", "", {0, 0, 0}},
                            {"Spine", "Hips", {0, 1, 0}},
                            {"LeftArm", "Spine", {1, 0, 0}},
                            {"LeftForeArm", "LeftArm", {1, 0, 0}},
                            {"LeftHand", "LeftForeArm", {1, 0, 0}}});
  Result<BodyLandmarks> body = FindBodyLandmarks(armless);
  ASSERT_FALSE(body.ok());
  EXPECT_NE(body.status().message().find("no left thigh: no joint named like LeftUpLeg"),
            std::string::npos)
      << body.status().message();
  body = FindBodyLandmarks(Build({{"Hips", "", {0, 0, 0}}}));
  ASSERT_FALSE(body.ok());
  EXPECT_NE(body.status().message().find("no left upper arm"), std::string::npos);
}

// Joint world positions and rotations of frame `frame` of `take`.
std::vector<Vec> Positions(const Take& take, size_t frame, std::vector<Quat>* world) {
  return JointPositions(take.skeleton, take.root_positions[frame], &take.rotation(frame, 0), world);
}

Quat RandomRotation(std::mt19937* random, double max_angle) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(-max_angle, max_angle);
  const Vec axis = Vec(normal(*random), normal(*random), normal(*random)).normalized();
  return Quat(Eigen::AngleAxisd(angle(*random), axis));
}

// Frames of random rotations on `skeleton`; `rest` rotations are applied first (a folded rig's
// joint orients, which its motion carries).
Take RandomTake(const Skeleton& skeleton, const std::vector<Quat>& rest, uint32_t seed) {
  std::mt19937 random(seed);
  Take take;
  take.name = "random";
  take.source_path = "random.bvh";
  take.skeleton = skeleton;
  for (int frame = 0; frame < 50; ++frame) {
    take.root_positions.push_back(Vec(frame * 0.1, 4.5, 0));
    for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
      take.rotations.push_back(rest[joint] * RandomRotation(&random, 1.2));
    }
  }
  return take;
}

// `folded`: the source's zero rotations do not stand upright, so the torso too is placed from
// the joints' positions and the joints it lacks keep their rest rotation.
void ExpectBonesFollow(const Take& source, bool folded) {
  Result<Take> mapped = RetargetToCmuBody(source);
  ASSERT_TRUE(mapped.ok()) << mapped.status().ToString();
  ASSERT_EQ(mapped->skeleton.family(), kCmuFamily);
  ASSERT_EQ(mapped->frame_count(), source.frame_count());
  const BodyLandmarks body = *FindBodyLandmarks(source.skeleton);
  const Skeleton& cmu = mapped->skeleton;
  struct Bone {
    const char* from;
    const char* to;
    int source_from;
    int source_to;
  };
  const std::vector<Bone> bones = {{"lhumerus", "lradius", body.left.upper_arm, body.left.elbow},
                                   {"lradius", "lwrist", body.left.elbow, body.left.wrist},
                                   {"rhumerus", "rradius", body.right.upper_arm, body.right.elbow},
                                   {"rradius", "rwrist", body.right.elbow, body.right.wrist},
                                   {"lfemur", "ltibia", body.left.hip, body.left.knee},
                                   {"ltibia", "lfoot", body.left.knee, body.left.ankle},
                                   {"rfemur", "rtibia", body.right.hip, body.right.knee},
                                   {"rtibia", "rfoot", body.right.knee, body.right.ankle},
                                   {"lowerback", "thorax", body.spine[0], body.chest}};
  const auto& axes = CmuRestHingeAxes();
  for (size_t frame = 0; frame < source.frame_count(); ++frame) {
    std::vector<Quat> source_world;
    std::vector<Quat> world;
    const std::vector<Vec> from = Positions(source, frame, &source_world);
    const std::vector<Vec> to = Positions(*mapped, frame, &world);
    EXPECT_LT(
        (to[0] - from[0] * (mapped->root_positions[1].x() / source.root_positions[1].x())).norm(),
        1e-12);
    for (const Bone& bone : bones) {
      const Vec expected = (from[bone.source_to] - from[bone.source_from]).normalized();
      const Vec got = (to[Index(cmu, bone.to)] - to[Index(cmu, bone.from)]).normalized();
      EXPECT_LT((got - expected).norm(), 1e-9) << bone.from << " frame " << frame;
    }
    // The elbows and knees turn about their rest hinge axis alone.
    const Vec upper = from[body.left.elbow] - from[body.left.upper_arm];
    const Vec lower = from[body.left.wrist] - from[body.left.elbow];
    if (upper.cross(lower).norm() > 0.3 * upper.norm() * lower.norm()) {
      const Quat elbow = mapped->rotation(frame, Index(cmu, "lradius"));
      EXPECT_LT((elbow * axes.left_elbow - axes.left_elbow).norm(), 1e-9) << frame;
    }
    if (!folded) continue;
    const Vec neck = (to[Index(cmu, "head")] - to[Index(cmu, "thorax")]).normalized();
    EXPECT_LT((neck - (from[body.head] - from[body.chest]).normalized()).norm(), 1e-9);
    EXPECT_LT(mapped->rotation(frame, Index(cmu, "lwrist")).angularDistance(Quat::Identity()),
              1e-12);
  }
}

TEST(BodyRetarget, BonesPointWhereTheDazBonesPoint) {
  const Skeleton daz = DazLike();
  ExpectBonesFollow(RandomTake(daz, std::vector<Quat>(daz.joint_count(), Quat::Identity()), 1),
                    false);
}

TEST(BodyRetarget, BonesPointWhereAFoldedRigsBonesPoint) {
  const Skeleton rig = FoldedStudioRig();
  std::mt19937 random(7);
  std::vector<Quat> orients;
  for (size_t joint = 0; joint < rig.joint_count(); ++joint) {
    orients.push_back(RandomRotation(&random, 3.1));
  }
  ExpectBonesFollow(RandomTake(rig, orients, 2), true);
}

TEST(BodyRetarget, KeepsTheTakeAtTheRestBodysSize) {
  const Skeleton daz = DazLike();
  Take take = RandomTake(daz, std::vector<Quat>(daz.joint_count(), Quat::Identity()), 3);
  take.fps = 30;
  take.source_first_frame = 1;
  take.description = "a test";
  take.source_joint_names = {"x"};
  Result<Take> mapped = RetargetToCmuBody(take);
  ASSERT_TRUE(mapped.ok());
  EXPECT_EQ(mapped->name, "random");
  EXPECT_EQ(mapped->fps, 30);
  EXPECT_EQ(mapped->source_first_frame, 1u);
  EXPECT_EQ(mapped->description, "a test");
  EXPECT_TRUE(mapped->source_joint_names.empty());
  EXPECT_EQ(mapped->skeleton.joint_count(), 31u);
  EXPECT_EQ(mapped->skeleton.joint(0).weight, 1.0f);
  // Legs of 8 units each, and the rest body's: the root travels as far in leg lengths.
  const auto length = [](const Skeleton& skeleton, const char* name) {
    const auto& o = skeleton.joint(Index(skeleton, name)).offset;
    return Vec(o[0], o[1], o[2]).norm();
  };
  const Skeleton& rest = CmuRestSkeleton();
  const double rest_legs = length(rest, "ltibia") + length(rest, "lfoot") + length(rest, "rtibia") +
                           length(rest, "rfoot");
  EXPECT_NEAR(length(mapped->skeleton, "ltibia"), length(rest, "ltibia"), 1e-12);
  for (size_t frame = 0; frame < take.frame_count(); ++frame) {
    EXPECT_LT(
        (mapped->root_positions[frame] - take.root_positions[frame] * rest_legs / 16.0).norm(),
        1e-12);
  }

  take.skeleton = Build({{"Hips", "", {0, 0, 0}}});
  take.rotations.assign(take.frame_count(), Quat::Identity());
  mapped = RetargetToCmuBody(take);
  ASSERT_FALSE(mapped.ok());
  EXPECT_EQ(
      mapped.status().message().rfind("random.bvh: its skeleton (1 joints) cannot be mapped", 0),
      0u)
      << mapped.status().message();
}

}  // namespace
}  // namespace motif
