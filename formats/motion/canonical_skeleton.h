// The canonical CMU skeleton ("cmu31"): CMU's ASF/AMC files and the cgspeed BVH conversions
// describe the same 31 joints under different names (ASF bone "lfemur" is BVH joint
// "LeftUpLeg"). Takes of either kind are mapped onto one canonical joint set, named after the
// ASF bones and ordered as below, so that a BVH take and an AMC take can live in one archive.
//
//   root; lhipjoint lfemur ltibia lfoot ltoes; rhipjoint rfemur rtibia rfoot rtoes;
//   lowerback upperback thorax lowerneck upperneck head;
//   lclavicle lhumerus lradius lwrist lhand lfingers lthumb;
//   rclavicle rhumerus rradius rwrist rhand rfingers rthumb
//
// A skeleton whose joints all have a CMU name or alias and whose parents match becomes "cmu31";
// any other skeleton stays "custom" with its own names.
// Thread-safety: pure functions.
#pragma once

#include <string>
#include <vector>

#include "common/status.h"
#include "formats/motion/take.h"

namespace motif {

// The canonical joint names in canonical order, and the canonical parent of each.
const std::vector<std::string>& CmuCanonicalJointNames();
const std::vector<int>& CmuCanonicalParents();

// The canonical name for a joint name of either naming scheme (case-insensitive: "LeftUpLeg",
// "lfemur", "Hips", "root"), or "" if it is not a CMU joint name.
std::string CmuCanonicalName(const std::string& joint_name);

// If `take`'s skeleton is the CMU 31-joint skeleton under either naming, renames and reorders its
// joints (and the rotations) into canonical order, sets family "cmu31" and the default weights,
// and returns true. Otherwise leaves the joints as they are, sets family "custom" with default
// weights by name, and returns false.
bool CanonicalizeSkeleton(Take* take);

// Reorders `take`'s joints into the order of `target` (matching by name). InvalidArgument naming
// the take and the first joint that differs when the hierarchies are not the same joint set
// with the same parents. Used when a take is appended to an archive.
Status ConformToSkeleton(const Skeleton& target, Take* take);

}  // namespace motif
