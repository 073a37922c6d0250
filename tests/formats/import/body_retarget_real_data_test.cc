// Mapping real takes of other skeleton families onto the CMU body (formats/motion/body_retarget.h):
//   - a CMU take mapped as if it were another family keeps its own poses (the rule reads CMU's
//     names too), so the mapping adds little of its own;
//   - the Daz conversion of CMU take 02_01 lands on the cgspeed conversion of the same capture:
//     frame by frame far nearer than the same take a second later;
//   - the CMU elbows and knees are hinges about the axes the mapping uses;
//   - the studio rig's takes map, standing.
// Figures: docs/design/mixed_skeletons.md. Skips when the data is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <vector>

#include "formats/import/take_importer.h"
#include "formats/motion/body_kinematics.h"
#include "formats/motion/body_retarget.h"
#include "formats/motion/cmu_rest_pose.h"
#include "formats/motion/pose_frames.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

Take Import(const std::string& path) {
  TakeSource source;
  source.path = path;
  Result<Take> take = ImportTake(source, ImportOptions());
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? *take : Take();
}

Take Retarget(const Take& take) {
  Result<Take> mapped = RetargetToCmuBody(take);
  EXPECT_TRUE(mapped.ok()) << mapped.status().ToString();
  return mapped.ok() ? *mapped : Take();
}

// The pose distance D of motifmine (engine/distance/pose_features.h) between frame a of `x` and
// frame b of `y`, both on the CMU body, with the weights of `x`.
double PoseDistance(const Take& x, const ClipFrames& xf, size_t a, const ClipFrames& yf, size_t b) {
  const FrameLayout layout{static_cast<uint32_t>(x.joint_count())};
  double sum = 0;
  for (size_t joint = 0; joint < x.joint_count(); ++joint) {
    const float weight = x.skeleton.joint(joint).weight;
    if (weight == 0) continue;
    const float* p = &xf.rows[a * layout.stride() + layout.quaternion_offset(joint)];
    const float* q = &yf.rows[b * layout.stride() + layout.quaternion_offset(joint)];
    double minus = 0;
    double plus = 0;
    for (int c = 0; c < 4; ++c) {
      minus += (p[c] - q[c]) * (p[c] - q[c]);
      plus += (p[c] + q[c]) * (p[c] + q[c]);
    }
    sum += weight * std::sqrt(std::min(minus, plus));
  }
  return sum;
}

// The median over frames of D(x[t], y[t + shift]).
double MedianDistance(const Take& x, const Take& y, long shift) {
  const ClipFrames xf = TakeToClipFrames(x);
  const ClipFrames yf = TakeToClipFrames(y);
  std::vector<double> distances;
  for (size_t t = 0; t < x.frame_count(); ++t) {
    const long u = static_cast<long>(t) + shift;
    if (u < 0 || u >= static_cast<long>(y.frame_count())) continue;
    distances.push_back(PoseDistance(x, xf, t, yf, static_cast<size_t>(u)));
  }
  if (distances.empty()) return NAN;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2];
}

TEST(BodyRetargetRealData, ACmuTakeMappedKeepsItsPoses) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  // 02_01 is the rest body's own subject: its mapping is exact up to the hinge rule.
  for (const auto& [name, share] :
       {std::pair{"bvh/02_01.bvh", 0.01}, std::pair{"bvh/05_01.bvh", 0.1},
        std::pair{"bvh/06_13.bvh", 0.2}}) {
    const Take native = Import(dir + "/" + name);
    ASSERT_EQ(native.skeleton.family(), "cmu31");
    const Take mapped = Retarget(native);
    ASSERT_EQ(mapped.frame_count(), native.frame_count());
    EXPECT_LT(MedianDistance(native, mapped, 0), share * MedianDistance(native, native, 60))
        << name;
  }
}

TEST(BodyRetargetRealData, DazAndCgspeedConversionsOfOneCaptureMeet) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  const Take daz_source = Import(dir + "/bvh_daz/02_01.bvh");
  ASSERT_EQ(daz_source.skeleton.family(), "custom");
  const Take daz = Retarget(daz_source);
  const Take cmu = Import(dir + "/bvh/02_01.bvh");
  ASSERT_EQ(daz.frame_count(), cmu.frame_count());
  const double same = MedianDistance(daz, cmu, 0);
  for (long shift : {-2L, -1L, 1L, 2L}) EXPECT_LT(same, MedianDistance(daz, cmu, shift)) << shift;
  // Half a second apart in this walk is the other foot forward.
  EXPECT_LT(same, 0.4 * MedianDistance(cmu, cmu, 60));
}

// Joint world positions and rotations of frame `frame` of `take`.
std::vector<Eigen::Vector3d> Positions(const Take& take, size_t frame,
                                       std::vector<Eigen::Quaterniond>* world) {
  return JointPositions(take.skeleton, take.root_positions[frame], &take.rotation(frame, 0), world);
}

// The elbows and knees of CMU takes turn about one axis each, CmuRestHingeAxes(), in the upper
// bone's frame: the axes the mapping gives every other family.
TEST(BodyRetargetRealData, CmuElbowsAndKneesTurnAboutTheRestHingeAxes) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  const CmuHingeAxes& axes = CmuRestHingeAxes();
  struct Hinge {
    const char* upper;
    const char* middle;
    const char* end;
    Eigen::Vector3d axis;
  };
  const Hinge hinges[] = {{"lhumerus", "lradius", "lwrist", axes.left_elbow},
                          {"rhumerus", "rradius", "rwrist", axes.right_elbow},
                          {"lfemur", "ltibia", "lfoot", axes.left_knee},
                          {"rfemur", "rtibia", "rfoot", axes.right_knee}};
  for (const char* name : {"bvh/02_01.bvh", "bvh/06_13.bvh", "bvh/09_01.bvh"}) {
    const Take take = Import(dir + "/" + name);
    for (const Hinge& hinge : hinges) {
      const int upper_joint = CanonicalJointIndex(hinge.upper);
      const int middle_joint = CanonicalJointIndex(hinge.middle);
      const int end_joint = CanonicalJointIndex(hinge.end);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int bent = 0;
      for (size_t frame = 0; frame < take.frame_count(); ++frame) {
        std::vector<Eigen::Quaterniond> world;
        const std::vector<Eigen::Vector3d> at = Positions(take, frame, &world);
        const Eigen::Vector3d upper = at[middle_joint] - at[upper_joint];
        const Eigen::Vector3d lower = at[end_joint] - at[middle_joint];
        const Eigen::Vector3d cross = upper.cross(lower);
        if (cross.norm() < 0.5 * upper.norm() * lower.norm()) continue;  // under 30 degrees
        sum += world[upper_joint].conjugate() * cross.normalized();
        ++bent;
      }
      ASSERT_GT(bent, 50) << name << " " << hinge.middle;
      EXPECT_LT((sum / bent - hinge.axis).norm(), 0.01) << name << " " << hinge.middle;
    }
  }
}

// The studio rig's zero rotations fold its body up, so it is placed from its joints' positions:
// every take maps, and stands (the head above the pelvis, the feet below it).
TEST(BodyRetargetRealData, TheStudioRigMapsStanding) {
  MOTIF_REQUIRE_STUDIO_RIG_DATA();
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(testing::StudioRigDir() + "/bvh")) {
    paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  ASSERT_FALSE(paths.empty());
  for (size_t at = 0; at < paths.size(); at += 9) {  // a sample across contents and styles
    const Take mapped = Retarget(Import(paths[at]));
    ASSERT_EQ(mapped.skeleton.family(), "cmu31");
    size_t standing = 0;
    for (size_t frame = 0; frame < mapped.frame_count(); ++frame) {
      std::vector<Eigen::Quaterniond> world;
      const std::vector<Eigen::Vector3d> where = Positions(mapped, frame, &world);
      const double pelvis = where[0].y();
      standing += where[CanonicalJointIndex("head")].y() > pelvis &&
                  where[CanonicalJointIndex("lfoot")].y() < pelvis &&
                  where[CanonicalJointIndex("rfoot")].y() < pelvis;
    }
    EXPECT_GT(standing, 0.9 * mapped.frame_count()) << paths[at];
  }
}

}  // namespace
}  // namespace motif
