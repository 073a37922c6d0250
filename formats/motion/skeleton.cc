#include "formats/motion/skeleton.h"

#include <algorithm>
#include <cctype>
#include <unordered_set>

namespace motif {

const char* ChannelTypeName(ChannelType type) {
  switch (type) {
    case ChannelType::kXPosition:
      return "Xposition";
    case ChannelType::kYPosition:
      return "Yposition";
    case ChannelType::kZPosition:
      return "Zposition";
    case ChannelType::kXRotation:
      return "Xrotation";
    case ChannelType::kYRotation:
      return "Yrotation";
    case ChannelType::kZRotation:
      return "Zrotation";
  }
  return "?";
}

bool ParseChannelType(const std::string& name, ChannelType* type) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::pair<const char*, ChannelType> kNames[] = {
      {"xposition", ChannelType::kXPosition}, {"yposition", ChannelType::kYPosition},
      {"zposition", ChannelType::kZPosition}, {"xrotation", ChannelType::kXRotation},
      {"yrotation", ChannelType::kYRotation}, {"zrotation", ChannelType::kZRotation}};
  for (const auto& [text, value] : kNames) {
    if (lower == text) {
      *type = value;
      return true;
    }
  }
  return false;
}

int Skeleton::FindJoint(const std::string& name) const {
  for (size_t joint_idx = 0; joint_idx < joints_.size(); ++joint_idx) {
    if (joints_[joint_idx].name == name) return static_cast<int>(joint_idx);
  }
  return -1;
}

Status Skeleton::Validate() const {
  if (joints_.empty()) return Status::InvalidArgument("skeleton has no joints");
  std::unordered_set<std::string> names;
  for (size_t joint_idx = 0; joint_idx < joints_.size(); ++joint_idx) {
    const Joint& joint = joints_[joint_idx];
    if (joint.name.empty()) {
      return Status::InvalidArgument("joint " + std::to_string(joint_idx) + " has no name");
    }
    if (!names.insert(joint.name).second) {
      return Status::InvalidArgument("joint name '" + joint.name + "' appears twice");
    }
    if (joint_idx == 0 && joint.parent != -1) {
      return Status::InvalidArgument("joint 0 ('" + joint.name + "') must be the root");
    }
    if (joint_idx > 0 && (joint.parent < 0 || joint.parent >= static_cast<int>(joint_idx))) {
      return Status::InvalidArgument("joint '" + joint.name + "' has parent index " +
                                     std::to_string(joint.parent) +
                                     ": parents must come before their children");
    }
  }
  return Status::Ok();
}

bool Skeleton::SameHierarchy(const Skeleton& other) const {
  if (family_ != other.family_ || joints_.size() != other.joints_.size()) return false;
  for (size_t joint_idx = 0; joint_idx < joints_.size(); ++joint_idx) {
    if (joints_[joint_idx].name != other.joints_[joint_idx].name ||
        joints_[joint_idx].parent != other.joints_[joint_idx].parent) {
      return false;
    }
  }
  return true;
}

float DefaultJointWeight(const std::string& family, const std::string& joint_name, bool is_root) {
  if (is_root) return 1.0f;
  std::string name(joint_name);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // Canonical CMU names (docs/design/algorithm.md step 1: root, lower and upper back, shoulders,
  // elbows, hips, knees).
  static const char* kCmuWeighted[] = {"lowerback", "upperback", "thorax",  "lhumerus",
                                       "rhumerus",  "lradius",   "rradius", "lfemur",
                                       "rfemur",    "ltibia",    "rtibia"};
  for (const char* weighted : kCmuWeighted) {
    if (name == weighted) return 1.0f;
  }
  if (family == kCmuFamily) return 0.0f;
  // Other skeletons: match common naming schemes by substring. Exclusions first, since "hand"
  // and "foot" names often contain "arm" or "leg" prefixes (e.g. "LeftHandIndex", "LeftFoot").
  static const char* kExcluded[] = {"hand",  "finger", "thumb", "index",  "middle",   "ring",
                                    "pinky", "toe",    "foot",  "wrist",  "ankle",    "head",
                                    "neck",  "eye",    "jaw",   "collar", "clavicle", "end"};
  for (const char* excluded : kExcluded) {
    if (name.find(excluded) != std::string::npos) return 0.0f;
  }
  static const char* kWeighted[] = {"hip",     "pelvis", "abdomen",  "spine",    "chest",
                                    "back",    "shldr",  "shoulder", "upperarm", "arm",
                                    "forearm", "elbow",  "thigh",    "upleg",    "upperleg",
                                    "leg",     "shin",   "knee",     "calf"};
  for (const char* weighted : kWeighted) {
    if (name.find(weighted) != std::string::npos) return 1.0f;
  }
  return 0.0f;
}

}  // namespace motif
