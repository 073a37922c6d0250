// Cross-format agreement on the takes the data holds in both forms (../shared/data/mocap README:
// 05_01, 05_02, 05_03, 05_16 with asfamc/05/05.asf, 07_05 with 07-walk.asf, 09_06 with
// 09-run.asf). The cgspeed BVH is B. Hahne's amc2bvh conversion of the same AMC data.
//
// Findings (6 takes, 3,338 frame pairs, BVH frame k + 1 = AMC frame k; distances are
// QuaternionDistance, sign-independent, between the BVH local rotation and C * M * C^-1 of the
// AMC rotation M, after both takes are canonicalised):
//
//   joint      max      mean   |  joint      max      mean   |  joint      max      mean
//   root      8.0e-07  2.7e-07 |  lowerback 7.5e-07  3.8e-07 |  lclavicle 2.8e-15  3.5e-16
//   lhipjoint 0        0       |  upperback 7.5e-07  3.8e-07 |  lhumerus  9.0e-07  4.2e-07
//   lfemur    7.6e-07  4.2e-07 |  thorax    7.5e-07  4.0e-07 |  lradius   8.8e-07  4.1e-07
//   ltibia    8.1e-07  3.7e-07 |  lowerneck 7.4e-07  3.2e-07 |  lwrist    4.4e-07  1.0e-07
//   lfoot     8.7e-07  4.2e-07 |  upperneck 7.4e-07  2.9e-07 |  lhand     8.2e-07  4.1e-07
//   ltoes     7.3e-07  4.2e-07 |  head      7.9e-07  3.6e-07 |  lfingers  1.8e-07  1.8e-07
//   rhipjoint 0        0       |                             |  lthumb    8.6e-07  4.1e-07
//   rfemur    7.8e-07  4.2e-07 |                             |  (right arm: the same figures,
//   rtibia    7.8e-07  4.1e-07 |                             |   max 9.0e-07)
//   rfoot     8.3e-07  4.1e-07 |                             |
//   rtoes     7.6e-07  4.2e-07 |                             |
//
// So every one of the 31 joints agrees, fingers, thumbs, hands and the root included, to the
// precision of the BVH text (4 decimals of a degree: 0.5e-4 deg is 4.4e-7 in quaternion distance
// per channel). Joints without dofs (lhipjoint, rhipjoint, lclavicle, rclavicle) are the
// identity in both. The root translation agrees to 7.1e-5 units (the BVH rounds to 4 decimals,
// the AMC keeps 6 significant digits), in the same units.
//
// What does differ is the skeleton, not the motion: amc2bvh puts every child of a bone that has
// several children at the start of that bone (OFFSET 0 0 0) instead of at its end. The ASF
// thorax's children lowerneck, lclavicle, rclavicle (BVH Neck, LeftShoulder, RightShoulder) and
// the wrists' children lhand, lthumb, rhand, rthumb (BVH Left/RightFingerBase, L/RThumb) sit at
// the thorax/wrist origin in the BVH, while the ASF places them at the end of the thorax (2.11
// units up, about 12 cm) and of the wrist. All other offsets and all 7 end sites agree to 1e-4.
// For the root's children (lhipjoint, rhipjoint, lowerback) both give 0.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "formats/import/take_importer.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

struct TakePair {
  const char* bvh;
  const char* amc;
  const char* asf;
};

const TakePair kPairs[] = {
    {"bvh/05_01.bvh", "asfamc/05/05_01.amc", "asfamc/05/05.asf"},
    {"bvh/05_02.bvh", "asfamc/05/05_02.amc", "asfamc/05/05.asf"},
    {"bvh/05_03.bvh", "asfamc/05/05_03.amc", "asfamc/05/05.asf"},
    {"bvh/05_16.bvh", "asfamc/05/05_16.amc", "asfamc/05/05.asf"},
    {"bvh/07_05.bvh", "asfamc/07/07_05-walk.amc", "asfamc/07/07-walk.asf"},
    {"bvh/09_06.bvh", "asfamc/09/09_06-run.amc", "asfamc/09/09-run.asf"},
};

struct Imported {
  Take bvh;
  Take amc;
};

Imported ImportPair(const TakePair& pair, FirstFramePolicy policy = FirstFramePolicy::kAuto) {
  const std::string dir = testing::MocapDir() + "/";
  ImportOptions options;
  options.first_frame = policy;
  TakeSource bvh;
  bvh.path = dir + pair.bvh;
  TakeSource amc;
  amc.format = TakeFormat::kAmc;
  amc.path = dir + pair.amc;
  amc.asf_path = dir + pair.asf;
  Result<Take> bvh_take = ImportTake(bvh, options);
  Result<Take> amc_take = ImportTake(amc, options);
  EXPECT_TRUE(bvh_take.ok()) << bvh_take.status().ToString();
  EXPECT_TRUE(amc_take.ok()) << amc_take.status().ToString();
  if (!bvh_take.ok() || !amc_take.ok()) return {};
  return {std::move(bvh_take).value(), std::move(amc_take).value()};
}

// The pose distance D (docs/design/algorithm.md step 1) over the weighted joints (weight 1: the
// root with its heading removed, the back, shoulders, elbows, hips and knees).
double PoseDistance(const Take& a, size_t frame_a, const Take& b, size_t frame_b) {
  double distance = 0;
  for (size_t joint_idx = 0; joint_idx < a.joint_count(); ++joint_idx) {
    const float weight = a.skeleton.joint(joint_idx).weight;
    if (weight == 0) continue;
    Eigen::Quaterniond qa = a.rotation(frame_a, joint_idx);
    Eigen::Quaterniond qb = b.rotation(frame_b, joint_idx);
    if (joint_idx == 0) {
      qa = RemoveHeading(qa, HeadingOf(qa));
      qb = RemoveHeading(qb, HeadingOf(qb));
    }
    distance += weight * QuaternionDistance(qa, qb);
  }
  return distance;
}

TEST(CrossFormat, EveryJointAgreesFrameForFrame) {
  MOTIF_REQUIRE_MOCAP_DATA();
  for (const TakePair& pair : kPairs) {
    SCOPED_TRACE(pair.bvh);
    Imported takes = ImportPair(pair);
    ASSERT_EQ(takes.bvh.skeleton.family(), "cmu31");
    ASSERT_EQ(takes.amc.skeleton.family(), "cmu31");
    ASSERT_EQ(takes.bvh.frame_count(), takes.amc.frame_count());
    ASSERT_GT(takes.bvh.frame_count(), 100u);
    double max_position = 0;
    for (size_t frame_idx = 0; frame_idx < takes.bvh.frame_count(); ++frame_idx) {
      max_position = std::max(
          max_position, (takes.bvh.root_positions[frame_idx] - takes.amc.root_positions[frame_idx])
                            .cwiseAbs()
                            .maxCoeff());
    }
    EXPECT_LT(max_position, 1e-4);
    for (size_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
      double max_distance = 0;
      for (size_t frame_idx = 0; frame_idx < takes.bvh.frame_count(); ++frame_idx) {
        max_distance =
            std::max(max_distance, QuaternionDistance(takes.bvh.rotation(frame_idx, joint_idx),
                                                      takes.amc.rotation(frame_idx, joint_idx)));
      }
      EXPECT_LT(max_distance, 2e-6) << takes.bvh.skeleton.joint(joint_idx).name;
    }
  }
}

TEST(CrossFormat, BvhFrameKPlusOneIsAmcFrameK) {
  MOTIF_REQUIRE_MOCAP_DATA();
  Imported takes = ImportPair(kPairs[0], FirstFramePolicy::kKeep);
  ASSERT_EQ(takes.bvh.frame_count(), takes.amc.frame_count() + 1);
  const size_t lfemur = 2;
  ASSERT_EQ(takes.bvh.skeleton.joint(lfemur).name, "lfemur");
  for (size_t frame_idx = 0; frame_idx < takes.amc.frame_count(); ++frame_idx) {
    ASSERT_LT(QuaternionDistance(takes.bvh.rotation(frame_idx + 1, lfemur),
                                 takes.amc.rotation(frame_idx, lfemur)),
              2e-6);
  }
  // Without the shift they do not match: the take moves.
  EXPECT_GT(QuaternionDistance(takes.bvh.rotation(100, lfemur), takes.amc.rotation(100, lfemur)),
            1e-4);
}

TEST(CrossFormat, PairwisePoseDistancesAgree) {
  MOTIF_REQUIRE_MOCAP_DATA();
  std::mt19937_64 rng(42);
  for (const TakePair& pair : kPairs) {
    SCOPED_TRACE(pair.bvh);
    Imported takes = ImportPair(pair);
    ASSERT_EQ(takes.bvh.frame_count(), takes.amc.frame_count());
    int weighted = 0;
    for (const Joint& joint : takes.bvh.skeleton.joints()) weighted += joint.weight > 0;
    ASSERT_EQ(weighted, 12);
    const size_t frame_count = takes.bvh.frame_count();
    double max_difference = 0;
    double mean_distance = 0;
    constexpr int kPairsPerTake = 2000;
    for (int sample = 0; sample < kPairsPerTake; ++sample) {
      const size_t frame_i = rng() % frame_count;
      const size_t frame_j = rng() % frame_count;
      const double bvh_distance = PoseDistance(takes.bvh, frame_i, takes.bvh, frame_j);
      const double amc_distance = PoseDistance(takes.amc, frame_i, takes.amc, frame_j);
      max_difference = std::max(max_difference, std::abs(bvh_distance - amc_distance));
      mean_distance += bvh_distance / kPairsPerTake;
    }
    EXPECT_LT(max_difference, 2e-5);
    EXPECT_GT(mean_distance, 0.5);  // the pairs are far apart: the agreement is not trivial
  }
}

TEST(CrossFormat, SkeletonsAgreeExceptWhereAmc2bvhMovesBranchChildren) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::set<std::string> moved = {"lowerneck", "lclavicle", "rclavicle", "lhand",
                                       "lthumb",    "rhand",     "rthumb"};
  for (const TakePair& pair : kPairs) {
    SCOPED_TRACE(pair.bvh);
    Imported takes = ImportPair(pair);
    for (size_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
      const Joint& bvh_joint = takes.bvh.skeleton.joint(joint_idx);
      const Joint& amc_joint = takes.amc.skeleton.joint(joint_idx);
      SCOPED_TRACE(bvh_joint.name);
      const Eigen::Vector3d bvh_offset(bvh_joint.offset.data());
      const Eigen::Vector3d amc_offset(amc_joint.offset.data());
      if (moved.count(bvh_joint.name)) {
        EXPECT_EQ(bvh_offset, Eigen::Vector3d::Zero());
        // The ASF puts it at the end of its parent bone.
        EXPECT_GT(amc_offset.norm(), 1.0);
        const Joint& parent = takes.bvh.skeleton.joint(bvh_joint.parent);
        EXPECT_TRUE(parent.name == "thorax" || parent.name == "lwrist" || parent.name == "rwrist");
      } else {
        EXPECT_LT((bvh_offset - amc_offset).cwiseAbs().maxCoeff(), 1e-4);
      }
      ASSERT_EQ(bvh_joint.has_end_site, amc_joint.has_end_site);
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(bvh_joint.end_site[axis], amc_joint.end_site[axis], 1e-4);
      }
    }
  }
}

}  // namespace
}  // namespace motif
