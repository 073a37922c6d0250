#include "bench/studies/body_frame_features.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Geometry>

namespace motif::testing {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

Vector3d ToVector(const std::array<float, 3>& value) {
  return Vector3d(value[0], value[1], value[2]);
}

Vector3d ToVector(const std::array<double, 3>& value) {
  return Vector3d(value[0], value[1], value[2]);
}

// The skeleton's bone offsets and end sites as the clip has them (subjects differ in bone
// lengths; ClipFramesToTake does the same).
struct Bones {
  std::vector<int32_t> parents;
  std::vector<Vector3d> offsets;
  std::vector<bool> has_end_site;
  std::vector<Vector3d> end_sites;
};

Bones ClipBones(const Skeleton& skeleton, const ClipInfo& clip) {
  Bones bones;
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    bones.parents.push_back(joint.parent);
    const bool own = joint_idx < clip.joint_offsets.size();
    bones.offsets.push_back(own ? ToVector(clip.joint_offsets[joint_idx]) : ToVector(joint.offset));
    bones.has_end_site.push_back(joint.has_end_site);
    const bool own_end = joint_idx < clip.end_sites.size();
    bones.end_sites.push_back(own_end ? ToVector(clip.end_sites[joint_idx])
                                      : ToVector(joint.end_site));
  }
  return bones;
}

// Highest minus lowest point of the rest pose (every rotation the identity), end sites included.
double RestHeight(const Bones& bones) {
  std::vector<Vector3d> origin(bones.parents.size(), Vector3d::Zero());
  double low = 0;
  double high = 0;
  for (size_t joint_idx = 0; joint_idx < bones.parents.size(); ++joint_idx) {
    if (bones.parents[joint_idx] >= 0) {
      origin[joint_idx] = origin[bones.parents[joint_idx]] + bones.offsets[joint_idx];
    }
    low = std::min(low, origin[joint_idx].y());
    high = std::max(high, origin[joint_idx].y());
    if (bones.has_end_site[joint_idx]) {
      const double end = (origin[joint_idx] + bones.end_sites[joint_idx]).y();
      low = std::min(low, end);
      high = std::max(high, end);
    }
  }
  return high - low;
}

std::vector<uint32_t> SubtreeSizes(const std::vector<int32_t>& parents) {
  std::vector<uint32_t> sizes(parents.size(), 1);
  for (size_t joint_idx = parents.size(); joint_idx-- > 1;) {  // children after parents
    if (parents[joint_idx] >= 0) sizes[parents[joint_idx]] += sizes[joint_idx];
  }
  return sizes;
}

std::vector<uint32_t> Children(const std::vector<int32_t>& parents, uint32_t joint) {
  std::vector<uint32_t> children;
  for (uint32_t idx = 0; idx < parents.size(); ++idx) {
    if (parents[idx] == static_cast<int32_t>(joint)) children.push_back(idx);
  }
  return children;
}

bool InSubtree(const std::vector<int32_t>& parents, uint32_t joint, uint32_t top) {
  for (int32_t at = static_cast<int32_t>(joint); at >= 0; at = parents[at]) {
    if (at == static_cast<int32_t>(top)) return true;
  }
  return false;
}

// The legs' and the arms' subtree tops and the chest joint, as the header describes.
struct Topology {
  std::vector<uint32_t> leg_tops;
  std::vector<uint32_t> arm_tops;
  uint32_t chest = 0;
};

Result<Topology> FindTopology(const std::vector<int32_t>& parents) {
  const std::vector<uint32_t> sizes = SubtreeSizes(parents);
  std::vector<uint32_t> root_children = Children(parents, 0);
  if (root_children.size() < 2) {
    return Status::InvalidArgument("body parts: the root has fewer than two subtrees");
  }
  std::sort(root_children.begin(), root_children.end(),
            [&](uint32_t a, uint32_t b) { return sizes[a] > sizes[b]; });
  Topology topology;
  topology.leg_tops.assign(root_children.begin() + 1, root_children.end());
  uint32_t at = root_children[0];
  while (Children(parents, at).size() < 3) {
    const std::vector<uint32_t> next = Children(parents, at);
    if (next.empty()) return Status::InvalidArgument("body parts: no chest joint on the spine");
    at = *std::max_element(next.begin(), next.end(),
                           [&](uint32_t a, uint32_t b) { return sizes[a] < sizes[b]; });
  }
  topology.chest = at;
  std::vector<uint32_t> chest_children = Children(parents, at);
  std::sort(chest_children.begin(), chest_children.end(),
            [&](uint32_t a, uint32_t b) { return sizes[a] > sizes[b]; });
  topology.arm_tops.assign(chest_children.begin(), chest_children.begin() + 2);
  return topology;
}

BodyPart PartOf(const std::vector<int32_t>& parents, const Topology& topology, uint32_t joint) {
  for (uint32_t top : topology.leg_tops) {
    if (InSubtree(parents, joint, top)) return BodyPart::kLeg;
  }
  for (uint32_t top : topology.arm_tops) {
    if (InSubtree(parents, joint, top)) return BodyPart::kArm;
  }
  return BodyPart::kTrunk;
}

// The header's points: origins of weighted joints and of their children, not on the root.
std::vector<uint32_t> ChoosePoints(const Skeleton& skeleton, const Bones& bones) {
  std::vector<Vector3d> origin(bones.parents.size(), Vector3d::Zero());
  std::vector<uint32_t> points;
  for (uint32_t joint_idx = 1; joint_idx < bones.parents.size(); ++joint_idx) {
    origin[joint_idx] = origin[bones.parents[joint_idx]] + bones.offsets[joint_idx];
    const bool weighted = skeleton.joint(joint_idx).weight > 0;
    const bool parent_weighted = skeleton.joint(bones.parents[joint_idx]).weight > 0;
    if ((weighted || parent_weighted) && origin[joint_idx].norm() > 1e-6) {
      points.push_back(joint_idx);
    }
  }
  return points;
}

// World rotations and origins of every joint of one frame, the root at the origin with its
// stored (heading-free) rotation.
void Pose(const Bones& bones, const float* row, std::vector<Quaterniond>* world,
          std::vector<Vector3d>* origin) {
  for (size_t joint_idx = 0; joint_idx < bones.parents.size(); ++joint_idx) {
    const float* q = row + 4 * joint_idx;
    const Quaterniond local = Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    const int32_t parent = bones.parents[joint_idx];
    if (parent < 0) {
      (*world)[joint_idx] = local;
      (*origin)[joint_idx] = Vector3d::Zero();
    } else {
      (*world)[joint_idx] = (*world)[parent] * local;
      (*origin)[joint_idx] = (*origin)[parent] + (*world)[parent] * bones.offsets[joint_idx];
    }
  }
}

}  // namespace

Result<BodyFrameFeatures> BodyFrameFeatures::Compute(const Skeleton& skeleton, const ClipInfo& clip,
                                                     const std::vector<float>& rows, double fps) {
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  const Bones bones = ClipBones(skeleton, clip);
  MOTIF_ASSIGN_OR_RETURN(const Topology topology, FindTopology(bones.parents));
  BodyFrameFeatures out;
  out.body_height_ = std::max(RestHeight(bones), 1e-9);
  out.point_joints_ = ChoosePoints(skeleton, bones);
  if (out.point_joints_.empty()) return Status::InvalidArgument("body frame: no weighted joint");
  for (uint32_t point = 0; point < out.point_joints_.size(); ++point) {
    out.point_parts_.push_back(PartOf(bones.parents, topology, out.point_joints_[point]));
    if (out.point_parts_.back() == BodyPart::kArm) out.arm_points_.push_back(point);
  }
  out.frame_count_ = rows.size() / layout.stride();
  out.values_per_frame_ = out.root_motion_offset() + 3;
  out.values_.assign(out.frame_count_ * out.values_per_frame_, 0.0f);
  const double scale = 1.0 / out.body_height_;
  std::vector<Quaterniond> world(skeleton.joint_count());
  std::vector<Vector3d> origin(skeleton.joint_count());
  for (uint64_t frame_idx = 0; frame_idx < out.frame_count_; ++frame_idx) {
    Pose(bones, &rows[frame_idx * layout.stride()], &world, &origin);
    float* values = &out.values_[frame_idx * out.values_per_frame_];
    for (size_t point = 0; point < out.point_joints_.size(); ++point) {
      const Vector3d p = origin[out.point_joints_[point]] * scale;
      for (int axis = 0; axis < 3; ++axis) values[3 * point + axis] = static_cast<float>(p[axis]);
    }
    const Quaterniond chest_inverse = world[topology.chest].conjugate();
    for (size_t arm = 0; arm < out.arm_points_.size(); ++arm) {
      const Vector3d p = chest_inverse *
                         (origin[out.point_joints_[out.arm_points_[arm]]] - origin[topology.chest]);
      for (int axis = 0; axis < 3; ++axis) {
        values[out.arm_offset() + 3 * arm + axis] = static_cast<float>(p[axis] * scale);
      }
    }
  }
  // Displacements over 0.1 s, from the positions just computed and the rows' root motion.
  const int64_t half = std::max<int64_t>(1, std::lround(0.05 * fps));
  const int64_t last = static_cast<int64_t>(out.frame_count_) - 1;
  for (int64_t frame_idx = 0; frame_idx <= last; ++frame_idx) {
    const float* after = out.frame(static_cast<uint64_t>(std::min(last, frame_idx + half)));
    const float* before = out.frame(static_cast<uint64_t>(std::max<int64_t>(0, frame_idx - half)));
    float* values = &out.values_[static_cast<uint64_t>(frame_idx) * out.values_per_frame_];
    for (uint32_t idx = 0; idx < out.velocity_offset(); ++idx) {
      values[out.velocity_offset() + idx] = after[idx] - before[idx];
    }
    for (uint32_t idx = 0; idx < 3 * out.arm_points_.size(); ++idx) {
      values[out.arm_velocity_offset() + idx] =
          after[out.arm_offset() + idx] - before[out.arm_offset() + idx];
    }
    const float* row = &rows[static_cast<uint64_t>(frame_idx) * layout.stride()];
    const float* row_after =
        &rows[static_cast<uint64_t>(std::min(last, frame_idx + half)) * layout.stride()];
    const float* row_before =
        &rows[static_cast<uint64_t>(std::max<int64_t>(0, frame_idx - half)) * layout.stride()];
    values[out.root_motion_offset()] =
        static_cast<float>(row[layout.velocity_offset()] * 0.1 * scale);
    values[out.root_motion_offset() + 1] =
        static_cast<float>(row[layout.velocity_offset() + 1] * 0.1 * scale);
    values[out.root_motion_offset() + 2] = static_cast<float>(
        (row_after[layout.height_offset()] - row_before[layout.height_offset()]) * scale);
  }
  return out;
}

ChannelSet BodyFrameFeatures::Positions() const {
  ChannelSet channels(velocity_offset());
  std::iota(channels.begin(), channels.end(), 0u);
  return channels;
}

ChannelSet BodyFrameFeatures::PositionsAndVelocities() const {
  ChannelSet channels(arm_offset());
  std::iota(channels.begin(), channels.end(), 0u);
  for (uint32_t idx = 0; idx < 3; ++idx) channels.push_back(root_motion_offset() + idx);
  return channels;
}

ChannelSet BodyFrameFeatures::Arms() const {
  ChannelSet channels(6 * arm_points_.size());
  std::iota(channels.begin(), channels.end(), arm_offset());
  return channels;
}

ChannelSet BodyFrameFeatures::Legs() const {
  ChannelSet channels;
  for (uint32_t point = 0; point < point_joints_.size(); ++point) {
    if (point_parts_[point] != BodyPart::kLeg) continue;
    for (uint32_t axis = 0; axis < 3; ++axis) {
      channels.push_back(3 * point + axis);
      channels.push_back(velocity_offset() + 3 * point + axis);
    }
  }
  for (uint32_t idx = 0; idx < 3; ++idx) channels.push_back(root_motion_offset() + idx);
  return channels;
}

ChannelSet BodyFrameFeatures::ArmVelocities() const {
  ChannelSet channels(3 * arm_points_.size());
  std::iota(channels.begin(), channels.end(), arm_velocity_offset());
  return channels;
}

ChannelSet BodyFrameFeatures::LegVelocities() const {
  ChannelSet channels;
  for (uint32_t point = 0; point < point_joints_.size(); ++point) {
    if (point_parts_[point] != BodyPart::kLeg) continue;
    for (uint32_t axis = 0; axis < 3; ++axis)
      channels.push_back(velocity_offset() + 3 * point + axis);
  }
  for (uint32_t idx = 0; idx < 3; ++idx) channels.push_back(root_motion_offset() + idx);
  return channels;
}

std::string BodyFrameFeatures::Describe(const Skeleton& skeleton) const {
  std::string text = "body height " + std::to_string(body_height_) + "; points";
  const char* part_names[] = {"trunk", "arm", "leg"};
  for (size_t point = 0; point < point_joints_.size(); ++point) {
    text += " " + skeleton.joint(point_joints_[point]).name + "(" +
            part_names[static_cast<int>(point_parts_[point])] + ")";
  }
  return text;
}

}  // namespace motif::testing
