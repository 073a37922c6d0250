#include "formats/import/animated_root.h"

#include <cmath>

namespace motif {
namespace {

// Equal as a capture writes a constant channel: the file's digits, read again (1e-6 of the
// value, or of a unit); rotations within 1e-6 radians whatever their sign.
bool SameTranslation(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() <= 1e-6 * (1.0 + a.norm());
}

bool SameRotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::abs(a.dot(b)) >= 1.0 - 1e-12;
}

bool IsStatic(const RootChainMotion& chain, const Take& take, size_t chain_joint) {
  const size_t frame_count = take.frame_count();
  for (size_t frame_idx = 1; frame_idx < frame_count; ++frame_idx) {
    if (!SameTranslation(chain.translations[frame_idx * chain.count + chain_joint],
                         chain.translations[chain_joint]) ||
        !SameRotation(take.rotation(frame_idx, chain_joint), take.rotation(0, chain_joint))) {
      return false;
    }
  }
  return true;
}

Eigen::Vector3d ToVector(const std::array<double, 3>& offset) {
  return {offset[0], offset[1], offset[2]};
}

}  // namespace

size_t StaticJointsAboveRoot(const RootChainMotion& chain, const Take& take) {
  if (take.frame_count() == 0) return 0;
  size_t static_count = 0;
  while (static_count + 1 < chain.count && IsStatic(chain, take, static_count)) ++static_count;
  return static_count;
}

void MoveRootBelowStaticJoints(const RootChainMotion& chain, size_t static_count, Take* take) {
  if (static_count == 0) return;
  const size_t joint_count = take->joint_count();
  const size_t frame_count = take->frame_count();
  // The static joints' transform, from frame 0 (every frame has the same).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
  for (size_t joint_idx = 0; joint_idx < static_count; ++joint_idx) {
    origin += turn * chain.translations[joint_idx];
    turn = turn * take->rotation(0, joint_idx);
  }
  const size_t kept = joint_count - static_count;
  std::vector<Eigen::Quaterniond> rotations;
  rotations.reserve(frame_count * kept);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    take->root_positions[frame_idx] =
        origin + turn * chain.translations[frame_idx * chain.count + static_count];
    rotations.push_back((turn * take->rotation(frame_idx, static_count)).normalized());
    for (size_t joint_idx = static_count + 1; joint_idx < joint_count; ++joint_idx) {
      rotations.push_back(take->rotation(frame_idx, joint_idx));
    }
  }
  std::vector<Joint> joints(take->skeleton.joints().begin() + static_count,
                            take->skeleton.joints().end());
  const Eigen::Vector3d root_offset = origin + turn * ToVector(joints[0].offset);
  joints[0].offset = {root_offset.x(), root_offset.y(), root_offset.z()};
  for (Joint& joint : joints) joint.parent -= static_cast<int32_t>(static_count);
  joints[0].parent = -1;
  take->skeleton = Skeleton(take->skeleton.family(), std::move(joints));
  take->rotations = std::move(rotations);
}

}  // namespace motif
