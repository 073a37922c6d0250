#include "engine/report/forward_kinematics.h"

namespace motif {

namespace {

Eigen::Vector3d ToVector(const std::array<double, 3>& value) {
  return Eigen::Vector3d(value[0], value[1], value[2]);
}

}  // namespace

size_t PosePointCount(const Skeleton& skeleton) {
  size_t count = skeleton.joint_count();
  for (const Joint& joint : skeleton.joints()) count += joint.has_end_site ? 1 : 0;
  return count;
}

std::vector<Eigen::Vector3d> ForwardKinematics(const Skeleton& skeleton,
                                               const Eigen::Vector3d& root_position,
                                               const Eigen::Quaterniond* rotations) {
  const size_t joint_count = skeleton.joint_count();
  std::vector<Eigen::Vector3d> points(PosePointCount(skeleton));
  std::vector<Eigen::Quaterniond> world(joint_count);
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    if (joint.parent < 0) {
      world[joint_idx] = rotations[joint_idx];
      points[joint_idx] = root_position;
    } else {
      const size_t parent = static_cast<size_t>(joint.parent);
      world[joint_idx] = world[parent] * rotations[joint_idx];
      points[joint_idx] = points[parent] + world[parent] * ToVector(joint.offset);
    }
  }
  size_t point_idx = joint_count;
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    if (!joint.has_end_site) continue;
    points[point_idx++] = points[joint_idx] + world[joint_idx] * ToVector(joint.end_site);
  }
  return points;
}

std::vector<Eigen::Vector3d> TakeFramePositions(const Take& take, size_t frame_idx) {
  return ForwardKinematics(take.skeleton, take.root_positions[frame_idx],
                           &take.rotations[frame_idx * take.joint_count()]);
}

std::vector<Eigen::Vector3d> RestPosePositions(const Skeleton& skeleton) {
  const std::vector<Eigen::Quaterniond> identity(skeleton.joint_count(),
                                                 Eigen::Quaterniond::Identity());
  return ForwardKinematics(skeleton, Eigen::Vector3d::Zero(), identity.data());
}

}  // namespace motif
