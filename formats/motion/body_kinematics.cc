#include "formats/motion/body_kinematics.h"

#include <algorithm>

#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat = Eigen::Matrix3d;

// The rotation whose columns are `primary` made unit, `secondary` made orthogonal to it, and
// their cross product. A secondary along the primary is replaced by any perpendicular.
Mat Frame(const Vec& primary, const Vec& secondary) {
  const Vec x = primary.normalized();
  Vec y = secondary - secondary.dot(x) * x;
  if (y.norm() < 1e-9 * std::max(1.0, secondary.norm())) y = x.unitOrthogonal();
  y.normalize();
  Mat frame;
  frame.col(0) = x;
  frame.col(1) = y;
  frame.col(2) = x.cross(y);
  return frame;
}

}  // namespace

int CanonicalJointIndex(const char* name) {
  const auto& names = CmuCanonicalJointNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

std::vector<Vec> JointPositions(const Skeleton& skeleton, const Vec& root, const Quat* local,
                                std::vector<Quat>* world) {
  std::vector<Vec> positions(skeleton.joint_count());
  world->assign(skeleton.joint_count(), Quat::Identity());
  for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
    const int parent = skeleton.joint(joint).parent;
    if (parent < 0) {
      positions[joint] = root;
      (*world)[joint] = local[joint];
      continue;
    }
    const auto& offset = skeleton.joint(joint).offset;
    positions[joint] = positions[parent] + (*world)[parent] * Vec(offset[0], offset[1], offset[2]);
    (*world)[joint] = (*world)[parent] * local[joint];
  }
  return positions;
}

Quat Orientation(const Vec& rest_bone, const Vec& rest_reference, const Vec& bone,
                 const Vec& reference) {
  const Mat rotation = Frame(bone, reference) * Frame(rest_bone, rest_reference).transpose();
  return Quat(rotation).normalized();
}

}  // namespace motif
