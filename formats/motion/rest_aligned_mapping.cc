#include "formats/motion/rest_aligned_mapping.h"

#include <cmath>
#include <string>
#include <utility>

#include "formats/motion/body_kinematics.h"
#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// Each canonical joint's source joint (-1: none), for the rest-aligned mapping.
std::vector<int> SourceOfCanonical(const BodyLandmarks& body) {
  std::vector<int> source(CmuCanonicalJointNames().size(), -1);
  const auto map = [&](const std::string& name, int joint) {
    if (joint >= 0) source[CanonicalJointIndex(name.c_str())] = joint;
  };
  map("root", body.pelvis);
  if (!body.spine.empty()) map("lowerback", body.spine[0]);
  if (body.spine.size() >= 2) map("upperback", body.spine[1]);
  map("thorax", body.chest);
  if (!body.neck.empty()) map("lowerneck", body.neck[0]);
  if (body.neck.size() >= 2) map("upperneck", body.neck[1]);
  map("head", body.head);
  // The hip joints and clavicles stay unmapped: rigs split the pelvis-to-thigh and
  // chest-to-arm turn between those and the limb differently (a Daz collar turns far more than
  // a CMU clavicle), and the distance weighs the limb relative to its parent. Following the
  // pelvis and chest, the limb's rotation carries the whole turn.
  for (const auto& [prefix, limbs] : {std::pair{"l", &body.left}, std::pair{"r", &body.right}}) {
    const std::string side = prefix;
    map(side + "femur", limbs->hip);
    map(side + "tibia", limbs->knee);
    map(side + "foot", limbs->ankle);
    map(side + "toes", limbs->toes);
    map(side + "humerus", limbs->upper_arm);
    map(side + "radius", limbs->elbow);
    map(side + "wrist", limbs->wrist);
  }
  return source;
}

// The canonical joint that carries a joint's bone on (its main child), or -1.
int CanonicalChainChild(int canonical) {
  static const std::vector<int> children = [] {
    const std::pair<const char*, const char*> chains[] = {
        {"lhipjoint", "lfemur"}, {"lfemur", "ltibia"},      {"ltibia", "lfoot"},
        {"lfoot", "ltoes"},      {"rhipjoint", "rfemur"},   {"rfemur", "rtibia"},
        {"rtibia", "rfoot"},     {"rfoot", "rtoes"},        {"lowerback", "upperback"},
        {"upperback", "thorax"}, {"thorax", "lowerneck"},   {"lowerneck", "upperneck"},
        {"upperneck", "head"},   {"lclavicle", "lhumerus"}, {"lhumerus", "lradius"},
        {"lradius", "lwrist"},   {"rclavicle", "rhumerus"}, {"rhumerus", "rradius"},
        {"rradius", "rwrist"}};
    std::vector<int> table(CmuCanonicalJointNames().size(), -1);
    for (const auto& [joint, child] : chains)
      table[CanonicalJointIndex(joint)] = CanonicalJointIndex(child);
    return table;
  }();
  return children[canonical];
}

}  // namespace

bool StandsUprightAtRest(const BodyLandmarks& body, const std::vector<Vec>& rest) {
  const auto within = [](const Vec& direction, const Vec& axis) {
    return direction.norm() > 0 && direction.normalized().dot(axis) > std::cos(M_PI / 4);
  };
  return within(rest[body.chest] - rest[body.pelvis], Vec::UnitY()) &&
         within(rest[body.left.ankle] - rest[body.left.hip], -Vec::UnitY()) &&
         within(rest[body.right.ankle] - rest[body.right.hip], -Vec::UnitY());
}

RestAlignedMapping::RestAlignedMapping(const BodyLandmarks& body,
                                       const std::vector<Vec>& source_rest,
                                       const std::vector<Vec>& canonical_rest)
    : source_of_(SourceOfCanonical(body)), corrections_(source_of_.size()) {
  const auto frame_of = [&](const std::vector<Vec>& at, int pelvis, int chest, int lhip, int rhip) {
    return std::pair{at[chest] - at[pelvis], at[lhip] - at[rhip]};
  };
  const auto [rest_up, rest_left] =
      frame_of(canonical_rest, 0, CanonicalJointIndex("thorax"), CanonicalJointIndex("lfemur"),
               CanonicalJointIndex("rfemur"));
  const auto [up, left] =
      frame_of(source_rest, body.pelvis, body.chest, body.left.hip, body.right.hip);
  const Quat body_frame = Orientation(rest_up, rest_left, up, left);
  for (size_t joint = 0; joint < source_of_.size(); ++joint) {
    corrections_[joint] = body_frame;
    if (source_of_[joint] < 0) continue;
    for (int child = CanonicalChainChild(static_cast<int>(joint)); child >= 0;
         child = CanonicalChainChild(child)) {
      if (source_of_[child] < 0) continue;
      const Vec rest_bone = canonical_rest[child] - canonical_rest[joint];
      const Vec bone = source_rest[source_of_[child]] - source_rest[source_of_[joint]];
      if (rest_bone.norm() > 1e-9 && bone.norm() > 1e-9) {
        corrections_[joint] = Quat::FromTwoVectors(body_frame * rest_bone, bone) * body_frame;
      }
      break;
    }
  }
}

void RestAlignedMapping::Pose(const std::vector<Quat>& source_world, std::vector<Quat>* world,
                              std::vector<bool>* set) const {
  for (size_t joint = 0; joint < source_of_.size(); ++joint) {
    if (source_of_[joint] < 0) continue;
    (*world)[joint] = source_world[source_of_[joint]] * corrections_[joint];
    (*set)[joint] = true;
  }
}

}  // namespace motif
