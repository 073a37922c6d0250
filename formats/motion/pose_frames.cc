#include "formats/motion/pose_frames.h"

#include "formats/motion/quaternion_math.h"

namespace motif {

ClipFrames TakeToClipFrames(const Take& take) {
  const FrameLayout layout{static_cast<uint32_t>(take.joint_count())};
  const size_t stride = layout.stride();
  const size_t frame_count = take.frame_count();
  const size_t joint_count = take.joint_count();

  ClipFrames clip;
  ClipInfo& info = clip.info;
  info.name = take.name;
  info.source_path = take.source_path;
  info.frame_count = frame_count;
  info.fps = take.fps;
  info.source_fps = take.source_fps;
  info.meters_per_unit = take.meters_per_unit;
  info.content_hash = take.content_hash;
  info.source_first_frame = take.source_first_frame;
  info.source_joint_names = take.source_joint_names;
  info.description = take.description;
  if (frame_count > 0) {
    const Eigen::Vector3d& start = take.root_positions[0];
    info.start_position = {start.x(), start.y(), start.z()};
  }
  for (const Joint& joint : take.skeleton.joints()) {
    info.joint_offsets.push_back({static_cast<float>(joint.offset[0]),
                                  static_cast<float>(joint.offset[1]),
                                  static_cast<float>(joint.offset[2])});
    info.end_sites.push_back({static_cast<float>(joint.end_site[0]),
                              static_cast<float>(joint.end_site[1]),
                              static_cast<float>(joint.end_site[2])});
  }

  clip.rows.assign(frame_count * stride, 0.0f);
  std::vector<Eigen::Quaterniond> previous(joint_count, Eigen::Quaterniond::Identity());
  double previous_heading = 0;
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    float* row = &clip.rows[frame_idx * stride];
    const Eigen::Quaterniond root = take.rotation(frame_idx, 0).normalized();
    double heading = HeadingOf(root);
    // Unwrap: the stored heading moves continuously along the clip.
    if (frame_idx > 0) heading = previous_heading + WrapAngle(heading - previous_heading);
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      Eigen::Quaterniond q = joint_idx == 0 ? RemoveHeading(root, heading)
                                            : take.rotation(frame_idx, joint_idx).normalized();
      if (frame_idx == 0) {
        if (q.w() < 0) q.coeffs() = -q.coeffs();
      } else {
        q = AlignSign(q, previous[joint_idx]);
      }
      previous[joint_idx] = q;
      float* out = row + layout.quaternion_offset(joint_idx);
      out[0] = static_cast<float>(q.w());
      out[1] = static_cast<float>(q.x());
      out[2] = static_cast<float>(q.y());
      out[3] = static_cast<float>(q.z());
    }
    const Eigen::Vector3d& position = take.root_positions[frame_idx];
    row[layout.height_offset()] = static_cast<float>(position.y());
    if (frame_idx > 0) {
      Eigen::Vector3d world_velocity = (position - take.root_positions[frame_idx - 1]) * take.fps;
      Eigen::Vector3d local = AxisRotation(Axis::kY, -heading) * world_velocity;
      row[layout.velocity_offset()] = static_cast<float>(local.x());
      row[layout.velocity_offset() + 1] = static_cast<float>(local.z());
    }
    row[layout.heading_offset()] = static_cast<float>(heading);
    previous_heading = heading;
  }
  if (frame_count > 1) {  // frame 0 has no predecessor: repeat frame 1's velocity
    clip.rows[layout.velocity_offset()] = clip.rows[stride + layout.velocity_offset()];
    clip.rows[layout.velocity_offset() + 1] = clip.rows[stride + layout.velocity_offset() + 1];
  }
  return clip;
}

Take ClipFramesToTake(const Skeleton& skeleton, const ClipInfo& info, const float* rows,
                      size_t frame_count) {
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  const size_t stride = layout.stride();
  const size_t joint_count = skeleton.joint_count();
  Take take;
  take.name = info.name;
  take.source_path = info.source_path;
  take.fps = info.fps;
  take.source_fps = info.source_fps;
  take.meters_per_unit = info.meters_per_unit;
  take.content_hash = info.content_hash;
  take.source_first_frame = info.source_first_frame;
  take.source_joint_names = info.source_joint_names;
  take.description = info.description;
  take.skeleton = skeleton;
  for (size_t joint_idx = 0; joint_idx < joint_count && joint_idx < info.joint_offsets.size();
       ++joint_idx) {
    Joint& joint = take.skeleton.mutable_joints()[joint_idx];
    for (int axis = 0; axis < 3; ++axis) {
      joint.offset[axis] = info.joint_offsets[joint_idx][axis];
      if (joint_idx < info.end_sites.size()) joint.end_site[axis] = info.end_sites[joint_idx][axis];
    }
  }
  take.root_positions.resize(frame_count);
  take.rotations.resize(frame_count * joint_count);
  Eigen::Vector3d position(info.start_position[0], info.start_position[1], info.start_position[2]);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const float* row = rows + frame_idx * stride;
    const double heading = row[layout.heading_offset()];
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      const float* q = row + layout.quaternion_offset(joint_idx);
      Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
      rotation.normalize();
      if (joint_idx == 0) rotation = AxisRotation(Axis::kY, heading) * rotation;
      take.rotation(frame_idx, joint_idx) = rotation;
    }
    if (frame_idx > 0) {
      Eigen::Vector3d local(row[layout.velocity_offset()], 0.0, row[layout.velocity_offset() + 1]);
      position += AxisRotation(Axis::kY, heading) * local / info.fps;
    }
    position.y() = row[layout.height_offset()];
    take.root_positions[frame_idx] = position;
  }
  return take;
}

}  // namespace motif
