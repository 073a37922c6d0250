#include "formats/import/asf_parser.h"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>
#include <utility>

#include "formats/import/text_scanner.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

using import_internal::EqualsIgnoreCase;
using import_internal::LineCursor;
using import_internal::NextWord;
using import_internal::ParseDouble;
using import_internal::ParseInt64;
using import_internal::Printable;
using import_internal::Quoted;

enum class Section { kNone, kSkipped, kUnits, kRoot, kBoneData, kHierarchy };

struct RawAxis {
  std::array<double, 3> angles{};                              // in the ASF's angle unit
  std::array<Axis, 3> order = {Axis::kX, Axis::kY, Axis::kZ};  // application order
};

bool ParseAxisOrder(std::string_view text, std::array<Axis, 3>* order) {
  if (text.size() != 3) return false;
  bool seen[3] = {false, false, false};
  for (int idx = 0; idx < 3; ++idx) {
    const char c = text[idx];
    int axis = -1;
    if (c == 'x' || c == 'X') axis = 0;
    if (c == 'y' || c == 'Y') axis = 1;
    if (c == 'z' || c == 'Z') axis = 2;
    if (axis < 0 || seen[axis]) return false;
    seen[axis] = true;
    (*order)[idx] = static_cast<Axis>(axis);
  }
  return true;
}

bool ParseDof(std::string_view text, AsfDof* dof) {
  static const std::pair<const char*, AsfDof> kNames[] = {
      {"rx", AsfDof::kRx}, {"ry", AsfDof::kRy}, {"rz", AsfDof::kRz},   {"tx", AsfDof::kTx},
      {"ty", AsfDof::kTy}, {"tz", AsfDof::kTz}, {"l", AsfDof::kLength}};
  for (const auto& [name, value] : kNames) {
    if (EqualsIgnoreCase(text, name)) {
      *dof = value;
      return true;
    }
  }
  return false;
}

// C for angles applied in `order` (first listed applied first): R(order[2]) R(order[1])
// R(order[0]).
Eigen::Quaterniond AxisRotationOf(const RawAxis& raw, bool degrees) {
  const Axis axes[3] = {raw.order[2], raw.order[1], raw.order[0]};
  double angles[3] = {raw.angles[2], raw.angles[1], raw.angles[0]};
  if (degrees) {
    for (double& angle : angles) angle = DegreesToRadians(angle);
  }
  return ComposeRotations(axes, angles, 3).normalized();
}

class AsfParser {
 public:
  AsfParser(std::string_view text, const std::string& file_name)
      : lines_(text), file_name_(file_name) {}

  Result<AsfSkeleton> Parse() {
    asf_.file_name = file_name_;
    std::string_view line;
    while (lines_.Next(&line)) {
      std::string_view rest = line;
      std::string_view word;
      if (!NextWord(&rest, &word) || word[0] == '#') continue;
      if (word[0] == ':') {
        MOTIF_RETURN_IF_ERROR(StartSection(word, rest));
        continue;
      }
      switch (section_) {
        case Section::kNone:
          return Error("expected a ':' section keyword, found " + Quoted(word) +
                       " (not an ASF file?)");
        case Section::kSkipped:
          break;
        case Section::kUnits:
          MOTIF_RETURN_IF_ERROR(ParseUnitsLine(word, rest));
          break;
        case Section::kRoot:
          MOTIF_RETURN_IF_ERROR(ParseRootLine(word, rest));
          break;
        case Section::kBoneData:
          MOTIF_RETURN_IF_ERROR(ParseBoneLine(word, rest));
          break;
        case Section::kHierarchy:
          MOTIF_RETURN_IF_ERROR(ParseHierarchyLine(word, rest));
          break;
      }
    }
    if (in_bone_)
      return Error("file ends inside the bone that begins at line " +
                   std::to_string(bone_begin_line_) + " (truncated file?)");
    if (!seen_bonedata_) return Error("no :bonedata section");
    if (!seen_hierarchy_) return Error("no :hierarchy section");
    if (hierarchy_state_ != HierarchyState::kDone) {
      return Error(":hierarchy has no 'end' (truncated file?)");
    }
    MOTIF_RETURN_IF_ERROR(Finish());
    return std::move(asf_);
  }

 private:
  enum class HierarchyState { kBeforeBegin, kInside, kDone };

  Status Error(const std::string& problem) const { return ErrorAt(lines_.line_number(), problem); }
  Status ErrorAt(int line, const std::string& problem) const {
    return Status::InvalidArgument(file_name_ + ":" + std::to_string(line) + ": " + problem);
  }

  Status StartSection(std::string_view word, std::string_view rest) {
    if (in_bone_) {
      return Error(std::string(word) + " inside the bone that begins at line " +
                   std::to_string(bone_begin_line_) + " ('end' missing)");
    }
    if (EqualsIgnoreCase(word, ":units")) {
      section_ = Section::kUnits;
    } else if (EqualsIgnoreCase(word, ":root")) {
      section_ = Section::kRoot;
    } else if (EqualsIgnoreCase(word, ":bonedata")) {
      if (seen_bonedata_) return Error("a second :bonedata section");
      seen_bonedata_ = true;
      section_ = Section::kBoneData;
    } else if (EqualsIgnoreCase(word, ":hierarchy")) {
      if (seen_hierarchy_) return Error("a second :hierarchy section");
      seen_hierarchy_ = true;
      section_ = Section::kHierarchy;
    } else {
      // :version, :name, :documentation, :skin and anything newer: not needed for motion.
      section_ = Section::kSkipped;
    }
    return Status::Ok();
  }

  Status ReadNumbers(std::string_view* rest, const std::string& what, double* values, int count) {
    for (int idx = 0; idx < count; ++idx) {
      std::string_view word;
      if (!NextWord(rest, &word)) {
        return Error(what + " needs " + std::to_string(count) + " numbers, found " +
                     std::to_string(idx));
      }
      if (!ParseDouble(word, &values[idx])) {
        return Error(what + ": " + Quoted(word) + " is not a finite number");
      }
    }
    return Status::Ok();
  }

  Status ExpectEnd(std::string_view rest, const std::string& what) {
    std::string_view word;
    if (NextWord(&rest, &word)) return Error("unexpected " + Quoted(word) + " after " + what);
    return Status::Ok();
  }

  Status ParseUnitsLine(std::string_view word, std::string_view rest) {
    std::string_view value;
    if (!NextWord(&rest, &value)) return Error(":units " + Quoted(word) + " has no value");
    if (EqualsIgnoreCase(word, "length")) {
      double length = 0;
      if (!ParseDouble(value, &length) || length <= 0) {
        return Error(":units length must be a positive number, found " + Quoted(value));
      }
      asf_.length_unit = length;
      asf_.meters_per_unit = 0.0254 / length;
    } else if (EqualsIgnoreCase(word, "angle")) {
      if (EqualsIgnoreCase(value, "deg")) {
        asf_.angles_in_degrees = true;
      } else if (EqualsIgnoreCase(value, "rad")) {
        asf_.angles_in_degrees = false;
      } else {
        return Error(":units angle must be 'deg' or 'rad', found " + Quoted(value));
      }
    }
    // mass and any other unit do not affect motion.
    return Status::Ok();
  }

  Status ParseRootLine(std::string_view word, std::string_view rest) {
    if (EqualsIgnoreCase(word, "order")) {
      asf_.root_order.clear();
      std::string_view name;
      while (NextWord(&rest, &name)) {
        AsfDof dof;
        if (!ParseDof(name, &dof) || dof == AsfDof::kLength) {
          return Error(":root order: " + Quoted(name) + " is not one of TX TY TZ RX RY RZ");
        }
        if (std::find(asf_.root_order.begin(), asf_.root_order.end(), dof) !=
            asf_.root_order.end()) {
          return Error(":root order lists " + Quoted(name) + " twice");
        }
        asf_.root_order.push_back(dof);
      }
      seen_root_order_ = true;
    } else if (EqualsIgnoreCase(word, "axis")) {
      std::string_view order;
      if (!NextWord(&rest, &order) || !ParseAxisOrder(order, &root_axis_.order)) {
        return Error(":root axis must be an order such as XYZ, found " + Quoted(order));
      }
      return ExpectEnd(rest, ":root axis");
    } else if (EqualsIgnoreCase(word, "position")) {
      double values[3];
      MOTIF_RETURN_IF_ERROR(ReadNumbers(&rest, ":root position", values, 3));
      asf_.root_position = Eigen::Vector3d(values[0], values[1], values[2]);
      return ExpectEnd(rest, ":root position");
    } else if (EqualsIgnoreCase(word, "orientation")) {
      MOTIF_RETURN_IF_ERROR(ReadNumbers(&rest, ":root orientation", root_axis_.angles.data(), 3));
      return ExpectEnd(rest, ":root orientation");
    } else {
      return Error("unknown :root field " + Quoted(word));
    }
    return Status::Ok();
  }

  Status ParseBoneLine(std::string_view word, std::string_view rest) {
    if (!in_bone_) {
      if (!EqualsIgnoreCase(word, "begin")) {
        return Error("expected 'begin' of a bone in :bonedata, found " + Quoted(word));
      }
      in_bone_ = true;
      in_limits_ = false;
      bone_begin_line_ = lines_.line_number();
      bone_ = AsfBone();
      bone_.line = bone_begin_line_;
      bone_axis_ = RawAxis();
      bone_has_ = {false, false, false};
      return ExpectEnd(rest, "begin");
    }
    const std::string where = bone_.name.empty() ? "bone" : "bone '" + Printable(bone_.name) + "'";
    if (word[0] == '(' && in_limits_) return Status::Ok();  // further limits lines
    in_limits_ = false;
    if (EqualsIgnoreCase(word, "end")) return FinishBone();
    if (EqualsIgnoreCase(word, "id")) {
      std::string_view id;
      int64_t value = 0;
      if (!NextWord(&rest, &id) || !ParseInt64(id, &value)) {
        return Error(where + ": id must be an integer, found " + Quoted(id));
      }
    } else if (EqualsIgnoreCase(word, "name")) {
      std::string_view name;
      if (!NextWord(&rest, &name)) return Error("bone name is empty");
      bone_.name = std::string(name);
      bone_has_[0] = true;
      return ExpectEnd(rest, "the bone name");
    } else if (EqualsIgnoreCase(word, "direction")) {
      MOTIF_RETURN_IF_ERROR(ReadNumbers(&rest, where + " direction", bone_.direction.data(), 3));
      bone_has_[1] = true;
      return ExpectEnd(rest, where + " direction");
    } else if (EqualsIgnoreCase(word, "length")) {
      MOTIF_RETURN_IF_ERROR(ReadNumbers(&rest, where + " length", &bone_.length, 1));
      if (bone_.length < 0) return Error(where + " has a negative length");
      bone_has_[2] = true;
      return ExpectEnd(rest, where + " length");
    } else if (EqualsIgnoreCase(word, "axis")) {
      MOTIF_RETURN_IF_ERROR(ReadNumbers(&rest, where + " axis", bone_axis_.angles.data(), 3));
      std::string_view order;
      if (!NextWord(&rest, &order) || !ParseAxisOrder(order, &bone_axis_.order)) {
        return Error(where + " axis: the angles must be followed by an order such as XYZ, found " +
                     Quoted(order));
      }
      return ExpectEnd(rest, where + " axis");
    } else if (EqualsIgnoreCase(word, "dof")) {
      std::string_view name;
      bone_.dofs.clear();
      while (NextWord(&rest, &name)) {
        AsfDof dof;
        if (!ParseDof(name, &dof)) {
          return Error(where + " dof: " + Quoted(name) + " is not one of rx ry rz tx ty tz l");
        }
        if (std::find(bone_.dofs.begin(), bone_.dofs.end(), dof) != bone_.dofs.end()) {
          return Error(where + " dof lists " + Quoted(name) + " twice");
        }
        bone_.dofs.push_back(dof);
      }
    } else if (EqualsIgnoreCase(word, "limits")) {
      in_limits_ = true;  // limits constrain capture, not playback: not needed here
    } else if (EqualsIgnoreCase(word, "bodymass") || EqualsIgnoreCase(word, "cofmass")) {
      // Dynamics data: not needed for motion.
    } else {
      return Error("unknown field " + Quoted(word) + " in " + where);
    }
    return Status::Ok();
  }

  Status FinishBone() {
    in_bone_ = false;
    if (!bone_has_[0]) return ErrorAt(bone_begin_line_, "bone without a name");
    const std::string where = "bone '" + Printable(bone_.name) + "'";
    if (!bone_has_[1]) return ErrorAt(bone_begin_line_, where + " has no direction");
    if (!bone_has_[2]) return ErrorAt(bone_begin_line_, where + " has no length");
    if (EqualsIgnoreCase(bone_.name, "root")) {
      return ErrorAt(bone_begin_line_, "a bone may not be called 'root'");
    }
    if (asf_.bones.size() + 1 >= kMaxSkeletonJoints) {  // + 1: the root
      return ErrorAt(bone_begin_line_, "more than " + std::to_string(kMaxSkeletonJoints) +
                                           " joints, the most an archive holds");
    }
    // A map, not AsfSkeleton::FindBone's scan: 100,000 bones took 44 s with the scan.
    if (!bone_index_.emplace(bone_.name, static_cast<int>(asf_.bones.size())).second) {
      return ErrorAt(bone_begin_line_, where + " is defined twice");
    }
    bone_.axis_rotation = Eigen::Quaterniond::Identity();
    raw_axes_.push_back(bone_axis_);
    asf_.bones.push_back(std::move(bone_));
    return Status::Ok();
  }

  Status ParseHierarchyLine(std::string_view word, std::string_view rest) {
    if (hierarchy_state_ == HierarchyState::kBeforeBegin) {
      if (!EqualsIgnoreCase(word, "begin")) {
        return Error("expected 'begin' in :hierarchy, found " + Quoted(word));
      }
      hierarchy_state_ = HierarchyState::kInside;
      parent_of_.assign(asf_.bones.size(), -2);  // -2: not attached yet
      children_.assign(asf_.bones.size() + 1, {});
      return ExpectEnd(rest, "begin");
    }
    if (hierarchy_state_ == HierarchyState::kDone) {
      return Error("unexpected " + Quoted(word) + " after the end of :hierarchy");
    }
    if (EqualsIgnoreCase(word, "end")) {
      hierarchy_state_ = HierarchyState::kDone;
      return ExpectEnd(rest, "end");
    }
    // children_[0] lists the root's children, children_[k + 1] bone k's.
    int parent = -1;
    if (!EqualsIgnoreCase(word, "root")) {
      parent = BoneIndex(word);
      if (parent < 0) return Error(":hierarchy names an unknown bone " + Quoted(word));
    }
    std::string_view name;
    while (NextWord(&rest, &name)) {
      const int child = BoneIndex(name);
      if (child < 0) return Error(":hierarchy names an unknown bone " + Quoted(name));
      if (parent_of_[child] != -2) {
        return Error("bone " + Quoted(name) + " is given a second parent in :hierarchy");
      }
      parent_of_[child] = parent;
      children_[parent + 1].push_back(child);
    }
    return Status::Ok();
  }

  // Orders the bones depth-first from the root and computes the axis rotations.
  Status Finish() {
    std::vector<int> order;  // new index -> old index
    std::vector<int> stack(children_[0].rbegin(), children_[0].rend());
    while (!stack.empty()) {
      const int bone_idx = stack.back();
      stack.pop_back();
      order.push_back(bone_idx);
      const auto& children = children_[bone_idx + 1];
      stack.insert(stack.end(), children.rbegin(), children.rend());
    }
    if (order.size() != asf_.bones.size()) {
      for (size_t bone_idx = 0; bone_idx < asf_.bones.size(); ++bone_idx) {
        if (std::find(order.begin(), order.end(), static_cast<int>(bone_idx)) == order.end()) {
          return ErrorAt(asf_.bones[bone_idx].line,
                         "bone '" + Printable(asf_.bones[bone_idx].name) +
                             "' is not connected to the root in :hierarchy");
        }
      }
    }
    std::vector<int> new_index(asf_.bones.size());
    for (size_t new_idx = 0; new_idx < order.size(); ++new_idx) {
      new_index[order[new_idx]] = static_cast<int>(new_idx);
    }
    std::vector<AsfBone> bones;
    bones.reserve(order.size());
    for (int old_idx : order) {
      AsfBone bone = std::move(asf_.bones[old_idx]);
      bone.parent = parent_of_[old_idx] < 0 ? -1 : new_index[parent_of_[old_idx]];
      bone.axis_rotation = AxisRotationOf(raw_axes_[old_idx], asf_.angles_in_degrees);
      bones.push_back(std::move(bone));
    }
    asf_.bones = std::move(bones);
    asf_.root_axis_rotation = AxisRotationOf(root_axis_, asf_.angles_in_degrees);
    if (!seen_root_order_) {
      asf_.root_order = {AsfDof::kTx, AsfDof::kTy, AsfDof::kTz,
                         AsfDof::kRx, AsfDof::kRy, AsfDof::kRz};
    }
    return Status::Ok();
  }

  LineCursor lines_;
  const std::string& file_name_;
  AsfSkeleton asf_;
  Section section_ = Section::kNone;
  bool seen_bonedata_ = false;
  bool seen_hierarchy_ = false;
  bool seen_root_order_ = false;
  RawAxis root_axis_;
  // The bone being read.
  bool in_bone_ = false;
  bool in_limits_ = false;
  int bone_begin_line_ = 0;
  AsfBone bone_;
  RawAxis bone_axis_;
  std::array<bool, 3> bone_has_{};  // name, direction, length
  std::vector<RawAxis> raw_axes_;   // per bone, in definition order
  // The hierarchy.
  HierarchyState hierarchy_state_ = HierarchyState::kBeforeBegin;
  // Index of a bone by name (definition order), -1 if none.
  int BoneIndex(std::string_view name) const {
    auto it = bone_index_.find(std::string(name));
    return it == bone_index_.end() ? -1 : it->second;
  }

  std::unordered_map<std::string, int> bone_index_;  // name -> definition-order index
  std::vector<int> parent_of_;              // per bone (definition order): -1 root, -2 none
  std::vector<std::vector<int>> children_;  // [0] root, [k + 1] bone k
};

}  // namespace

int AsfSkeleton::FindBone(std::string_view name) const {
  for (size_t bone_idx = 0; bone_idx < bones.size(); ++bone_idx) {
    if (bones[bone_idx].name == name) return static_cast<int>(bone_idx);
  }
  return -1;
}

Result<AsfSkeleton> ParseAsf(std::string_view text, const std::string& file_name) {
  AsfParser parser(text, file_name);
  return parser.Parse();
}

Skeleton AsfToSkeleton(const AsfSkeleton& asf) {
  std::vector<Joint> joints(asf.bones.size() + 1);
  std::vector<bool> has_children(asf.bones.size(), false);
  for (const AsfBone& bone : asf.bones) {
    if (bone.parent >= 0) has_children[bone.parent] = true;
  }
  joints[0].name = "root";
  joints[0].parent = -1;
  joints[0].channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition,
                        ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
  for (size_t bone_idx = 0; bone_idx < asf.bones.size(); ++bone_idx) {
    const AsfBone& bone = asf.bones[bone_idx];
    Joint& joint = joints[bone_idx + 1];
    joint.name = bone.name;
    joint.parent = bone.parent + 1;
    const Eigen::Vector3d offset =
        bone.parent < 0
            ? asf.root_position
            : Eigen::Vector3d(asf.bones[bone.parent].direction * asf.bones[bone.parent].length);
    joint.offset = {offset.x(), offset.y(), offset.z()};
    if (!has_children[bone_idx]) {
      const Eigen::Vector3d end = bone.direction * bone.length;
      joint.has_end_site = true;
      joint.end_site = {end.x(), end.y(), end.z()};
    }
    joint.channels = {ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
  }
  return Skeleton("custom", std::move(joints));
}

}  // namespace motif
