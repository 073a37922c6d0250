// ASF parsing (Acclaim skeleton files, as CMU ships them): the bones, their rest directions,
// lengths, axis rotations and degrees of freedom, the root's channel order and the hierarchy, and
// the joint skeleton built from them. The AMC parser (amc_parser.h) uses the AsfSkeleton to turn
// motion lines into rotations.
//
// Sections read: :units (length, angle deg|rad; mass ignored), :root (order, axis, position,
// orientation), :bonedata (begin/end blocks with id, name, direction, length, axis a b c ORDER,
// dof, limits; bodymass/cofmass ignored), :hierarchy (begin, "parent child child ...", end).
// :version, :name, :documentation, :skin and unknown sections are skipped; '#' starts a comment
// line. Keywords are case-insensitive.
//
// Conventions (quaternion_math.h): "axis a b c XYZ" gives one angle per letter, in the letters'
// order, and the rotations are applied in that order: XYZ means x first, so C = Rz(c) Ry(b) Rx(a).
// The root's "orientation" with its "axis" order gives the root's C likewise.
//
// The joint skeleton (AsfToSkeleton): joint 0 is "root", then one joint per bone named after it,
// in the order of AsfSkeleton::bones (depth-first over :hierarchy, children in listed order).
// A joint's offset is its parent bone's direction * length, or the :root position for children of
// the root (normally 0); a bone with no children gets an end site at its own direction * length.
// Lengths stay in the ASF's own units (the cgspeed BVH offsets use the same units);
// meters_per_unit = 0.0254 / length (CMU: "length 0.45" -> 0.056444 m per unit).
// Thread-safety: pure functions and a value type.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/status.h"
#include "formats/motion/skeleton.h"

namespace motif {

// One degree of freedom of a bone or of the root, in the order AMC lists its values.
enum class AsfDof : uint8_t { kRx, kRy, kRz, kTx, kTy, kTz, kLength };

struct AsfBone {
  std::string name;
  int line = 0;                                         // line of the bone's "begin" (for messages)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // rest direction, world axes
  double length = 0;                                    // ASF length units
  Eigen::Quaterniond axis_rotation = Eigen::Quaterniond::Identity();  // C
  std::vector<AsfDof> dofs;  // AMC value order; empty for a bone without motion
  int parent = -1;           // index into AsfSkeleton::bones; -1 when the parent is the root
};

struct AsfSkeleton {
  std::string file_name;
  double length_unit = 0;      // the ":units length" value; 0 if absent
  double meters_per_unit = 0;  // 0.0254 / length_unit, 0 if unknown
  bool angles_in_degrees = true;
  std::vector<AsfDof> root_order;  // AMC value order of the root line
  Eigen::Quaterniond root_axis_rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d root_position = Eigen::Vector3d::Zero();
  std::vector<AsfBone> bones;  // parents before children

  // Index into bones of the bone called `name` (exact match), or -1.
  int FindBone(std::string_view name) const;
};

// Parses the text of the ASF file `file_name` (named in messages). InvalidArgument
// "<file>:<line>: <problem>" for malformed input: unknown keywords, non-numeric or non-finite
// values, a bad axis order or dof name, duplicate bone names, a hierarchy that names an unknown
// bone, gives a bone two parents, or leaves a bone unattached to the root.
Result<AsfSkeleton> ParseAsf(std::string_view text, const std::string& file_name);

// The joint skeleton of `asf` (family "custom", weights unset): joint 0 "root", joint k + 1 is
// bone k. Root channels Xposition Yposition Zposition Zrotation Yrotation Xrotation, other
// joints Zrotation Yrotation Xrotation (the layout of the cgspeed BVH conversion).
Skeleton AsfToSkeleton(const AsfSkeleton& asf);

}  // namespace motif
