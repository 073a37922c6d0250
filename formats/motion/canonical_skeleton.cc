#include "formats/motion/canonical_skeleton.h"

#include <algorithm>
#include <cctype>
#include <unordered_map>

namespace motif {
namespace {

struct CanonicalJoint {
  const char* name;
  const char* parent;
  const char* bvh_name;  // the cgspeed MotionBuilder-friendly BVH name
};

constexpr CanonicalJoint kCmuJoints[] = {
    {"root", "", "Hips"},
    {"lhipjoint", "root", "LHipJoint"},
    {"lfemur", "lhipjoint", "LeftUpLeg"},
    {"ltibia", "lfemur", "LeftLeg"},
    {"lfoot", "ltibia", "LeftFoot"},
    {"ltoes", "lfoot", "LeftToeBase"},
    {"rhipjoint", "root", "RHipJoint"},
    {"rfemur", "rhipjoint", "RightUpLeg"},
    {"rtibia", "rfemur", "RightLeg"},
    {"rfoot", "rtibia", "RightFoot"},
    {"rtoes", "rfoot", "RightToeBase"},
    {"lowerback", "root", "LowerBack"},
    {"upperback", "lowerback", "Spine"},
    {"thorax", "upperback", "Spine1"},
    {"lowerneck", "thorax", "Neck"},
    {"upperneck", "lowerneck", "Neck1"},
    {"head", "upperneck", "Head"},
    {"lclavicle", "thorax", "LeftShoulder"},
    {"lhumerus", "lclavicle", "LeftArm"},
    {"lradius", "lhumerus", "LeftForeArm"},
    {"lwrist", "lradius", "LeftHand"},
    {"lhand", "lwrist", "LeftFingerBase"},
    {"lfingers", "lhand", "LeftHandIndex1"},
    {"lthumb", "lwrist", "LThumb"},
    {"rclavicle", "thorax", "RightShoulder"},
    {"rhumerus", "rclavicle", "RightArm"},
    {"rradius", "rhumerus", "RightForeArm"},
    {"rwrist", "rradius", "RightHand"},
    {"rhand", "rwrist", "RightFingerBase"},
    {"rfingers", "rhand", "RightHandIndex1"},
    {"rthumb", "rwrist", "RThumb"},
};

std::string Lower(const std::string& text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

const std::unordered_map<std::string, std::string>& AliasTable() {
  static const auto* table = [] {
    auto* map = new std::unordered_map<std::string, std::string>();
    for (const CanonicalJoint& joint : kCmuJoints) {
      (*map)[joint.name] = joint.name;
      (*map)[Lower(joint.bvh_name)] = joint.name;
    }
    return map;
  }();
  return *table;
}

// Applies `order` (new index -> old index) to the take's joints and rotations.
void ReorderJoints(const std::vector<int>& order, std::vector<Joint> new_joints, Take* take) {
  const size_t joint_count = order.size();
  std::vector<Eigen::Quaterniond> rotations(take->rotations.size());
  for (size_t frame_idx = 0; frame_idx < take->frame_count(); ++frame_idx) {
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      rotations[frame_idx * joint_count + joint_idx] =
          take->rotations[frame_idx * joint_count + order[joint_idx]];
    }
  }
  take->rotations = std::move(rotations);
  take->skeleton = Skeleton(take->skeleton.family(), std::move(new_joints));
  if (!take->source_joint_names.empty()) {
    std::vector<std::string> names(joint_count);
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      names[joint_idx] = take->source_joint_names[order[joint_idx]];
    }
    take->source_joint_names = std::move(names);
  }
}

void SetDefaultWeights(Skeleton* skeleton) {
  for (size_t joint_idx = 0; joint_idx < skeleton->joint_count(); ++joint_idx) {
    Joint& joint = skeleton->mutable_joints()[joint_idx];
    joint.weight = DefaultJointWeight(skeleton->family(), joint.name, joint_idx == 0);
  }
}

}  // namespace

const std::vector<std::string>& CmuCanonicalJointNames() {
  static const auto* names = [] {
    auto* list = new std::vector<std::string>();
    for (const CanonicalJoint& joint : kCmuJoints) list->push_back(joint.name);
    return list;
  }();
  return *names;
}

const std::vector<int>& CmuCanonicalParents() {
  static const auto* parents = [] {
    auto* list = new std::vector<int>();
    const auto& names = CmuCanonicalJointNames();
    for (const CanonicalJoint& joint : kCmuJoints) {
      auto it = std::find(names.begin(), names.end(), joint.parent);
      list->push_back(it == names.end() ? -1 : static_cast<int>(it - names.begin()));
    }
    return list;
  }();
  return *parents;
}

std::string CmuCanonicalName(const std::string& joint_name) {
  const auto& table = AliasTable();
  auto it = table.find(Lower(joint_name));
  return it == table.end() ? std::string() : it->second;
}

bool CanonicalizeSkeleton(Take* take) {
  const auto& names = CmuCanonicalJointNames();
  const auto& parents = CmuCanonicalParents();
  const Skeleton& skeleton = take->skeleton;
  bool is_cmu = skeleton.joint_count() == names.size();
  std::vector<int> order(names.size(), -1);  // canonical index -> take index
  std::vector<std::string> canonical_of(skeleton.joint_count());
  for (size_t joint_idx = 0; is_cmu && joint_idx < skeleton.joint_count(); ++joint_idx) {
    canonical_of[joint_idx] = CmuCanonicalName(skeleton.joint(joint_idx).name);
    auto it = std::find(names.begin(), names.end(), canonical_of[joint_idx]);
    if (it == names.end() || order[it - names.begin()] != -1) {
      is_cmu = false;
      break;
    }
    order[it - names.begin()] = static_cast<int>(joint_idx);
  }
  for (size_t canonical_idx = 0; is_cmu && canonical_idx < names.size(); ++canonical_idx) {
    const int parent = skeleton.joint(order[canonical_idx]).parent;
    const std::string parent_name = parent < 0 ? "" : canonical_of[parent];
    const std::string expected = parents[canonical_idx] < 0 ? "" : names[parents[canonical_idx]];
    if (parent_name != expected) is_cmu = false;
  }
  if (!is_cmu) {
    take->skeleton.set_family("custom");
    SetDefaultWeights(&take->skeleton);
    return false;
  }
  // The source's names, kept when they are not the canonical ones (BVH: "LeftUpLeg").
  bool renamed = false;
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    renamed = renamed || skeleton.joint(joint_idx).name != canonical_of[joint_idx];
  }
  if (renamed && take->source_joint_names.empty()) {
    for (const Joint& joint : skeleton.joints()) take->source_joint_names.push_back(joint.name);
  }
  std::vector<Joint> joints;
  for (size_t canonical_idx = 0; canonical_idx < names.size(); ++canonical_idx) {
    Joint joint = skeleton.joint(order[canonical_idx]);
    joint.name = names[canonical_idx];
    joint.parent = parents[canonical_idx];
    joints.push_back(std::move(joint));
  }
  take->skeleton.set_family(kCmuFamily);
  ReorderJoints(order, std::move(joints), take);
  SetDefaultWeights(&take->skeleton);
  return true;
}

Status ConformToSkeleton(const Skeleton& target, Take* take) {
  const Skeleton& skeleton = take->skeleton;
  auto mismatch = [&](const std::string& what) {
    return Status::InvalidArgument(
        take->source_path + ": its skeleton (" + skeleton.family() + ", " +
        std::to_string(skeleton.joint_count()) + " joints) does not match the archive's (" +
        target.family() + ", " + std::to_string(target.joint_count()) + " joints): " + what);
  };
  if (skeleton.family() != target.family()) return mismatch("different skeleton family");
  if (skeleton.joint_count() != target.joint_count()) return mismatch("different joint count");
  std::vector<int> order(target.joint_count(), -1);
  for (size_t joint_idx = 0; joint_idx < target.joint_count(); ++joint_idx) {
    const Joint& wanted = target.joint(joint_idx);
    const int found = skeleton.FindJoint(wanted.name);
    if (found < 0) return mismatch("no joint named '" + wanted.name + "'");
    order[joint_idx] = found;
  }
  for (size_t joint_idx = 0; joint_idx < target.joint_count(); ++joint_idx) {
    const int wanted_parent = target.joint(joint_idx).parent;
    const int parent = skeleton.joint(order[joint_idx]).parent;
    const std::string parent_name = parent < 0 ? "" : skeleton.joint(parent).name;
    const std::string wanted_name = wanted_parent < 0 ? "" : target.joint(wanted_parent).name;
    if (parent_name != wanted_name) {
      return mismatch("joint '" + target.joint(joint_idx).name + "' has parent '" + parent_name +
                      "', the archive's has '" + wanted_name + "'");
    }
  }
  std::vector<Joint> joints;
  for (size_t joint_idx = 0; joint_idx < target.joint_count(); ++joint_idx) {
    Joint joint = skeleton.joint(order[joint_idx]);
    joint.parent = target.joint(joint_idx).parent;
    joint.weight = target.joint(joint_idx).weight;
    joints.push_back(std::move(joint));
  }
  ReorderJoints(order, std::move(joints), take);
  take->skeleton.set_family(target.family());
  return Status::Ok();
}

}  // namespace motif
