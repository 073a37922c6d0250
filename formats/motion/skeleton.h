// Skeleton: the joint hierarchy of a take or of an archive. Joints are stored parents first
// (joint 0 is the root, every parent index is smaller than its child's), each with its offset
// from the parent in the rest pose, an optional end site, the BVH channel layout used when the
// skeleton is written out, and its default weight in the pose distance D (docs/design/algorithm.md,
// step 1).
// `family` names the canonical joint set: "cmu31" for CMU's 31-joint skeleton (BVH
// MotionBuilder names and ASF bone names both map to it, see canonical_skeleton.h), "custom"
// for any other hierarchy, whose joint names are kept as found.
// Thread-safety: a value type.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"

namespace motif {

// The most joints a skeleton may have: the archive format's limit (formats/frame_file,
// kMaxJoints). Parsers stop as soon as a take crosses it, before reading the rest.
inline constexpr size_t kMaxSkeletonJoints = 4096;

// The family name of CMU's 31-joint skeleton in canonical (ASF bone) names.
inline constexpr char kCmuFamily[] = "cmu31";

// Pinned values: they are stored in the archive's skeleton table (docs/formats/frame_file.md).
enum class ChannelType : uint8_t {
  kXPosition = 0,
  kYPosition = 1,
  kZPosition = 2,
  kXRotation = 3,
  kYRotation = 4,
  kZRotation = 5,
};

// "Xposition", "Zrotation", ...; nullptr-safe parse returns false on an unknown name.
const char* ChannelTypeName(ChannelType type);
bool ParseChannelType(const std::string& name, ChannelType* type);

struct Joint {
  std::string name;
  int32_t parent = -1;             // index of the parent joint; -1 for the root only
  std::array<double, 3> offset{};  // from the parent's origin, rest pose, source length units
  bool has_end_site = false;
  std::array<double, 3> end_site{};   // offset of the end site from this joint, if any
  std::vector<ChannelType> channels;  // BVH channel layout (rotations in composition order)
  float weight = 0.0f;                // default weight w_k of this joint in the pose distance
};

class Skeleton {
 public:
  Skeleton() = default;
  Skeleton(std::string family, std::vector<Joint> joints)
      : family_(std::move(family)), joints_(std::move(joints)) {}

  const std::string& family() const { return family_; }
  void set_family(std::string family) { family_ = std::move(family); }
  const std::vector<Joint>& joints() const { return joints_; }
  std::vector<Joint>& mutable_joints() { return joints_; }
  size_t joint_count() const { return joints_.size(); }
  const Joint& joint(size_t joint_idx) const { return joints_[joint_idx]; }

  // Index of the joint named `name` (exact match), or -1.
  int FindJoint(const std::string& name) const;

  // Checks the invariants: at least one joint, joint 0 is the only root, parents come before
  // their children, names are unique and non-empty. InvalidArgument naming the first violation.
  Status Validate() const;

  // True if both have the same family, joint names and parents in the same order (offsets and
  // channel layouts may differ: different subjects have different bone lengths).
  bool SameHierarchy(const Skeleton& other) const;

 private:
  std::string family_ = "custom";
  std::vector<Joint> joints_;
};

// Default weight of a joint in the pose distance, by name (canonical CMU names, and the common
// names of other skeletons: hip/pelvis, abdomen/spine/chest, shoulder/upper arm, forearm/elbow,
// thigh/upper leg, shin/knee). 1 for those, 0 for toes, wrists, hands, fingers, head and neck.
// For the "cmu31" family only the canonical table applies.
float DefaultJointWeight(const std::string& family, const std::string& joint_name, bool is_root);

}  // namespace motif
