// AMC parsing (Acclaim motion files): turns the text of an .amc file and its parsed ASF skeleton
// (asf_parser.h) into a Take on the ASF's joint skeleton (AsfToSkeleton), before
// canonicalisation and first-frame handling (take_importer.h does those).
//
// Layout accepted: '#' comment lines and ':' keyword lines (":FULLY-SPECIFIED", ":DEGREES",
// ":RADIANS"; others ignored) before the first frame; then for each frame a line holding only its
// number, followed by one line per bone that has dofs ("<bone> v0 v1 ..."), in any order. Frame
// numbers must be consecutive (the first may be any integer); every bone with dofs must appear
// exactly once per frame; a bone line has exactly as many values as the bone has dofs (the root:
// as many as its :root order). Angles are in degrees unless the file says :RADIANS (without
// either keyword the ASF's angle unit applies).
//
// Rotations (docs/import.md, "Conventions"; verified against the cgspeed BVH conversion,
// docs/design/algorithm.md section 6.1): for a bone
// with axis rotation C and rotation dofs d0 d1 d2 in listed order, M = R(d2) R(d1) R(d0) (the
// first-listed dof is applied first), and the joint's rest-aligned local rotation is C M C^-1.
// The root likewise with its :root order and axis/orientation. Translation and length dofs of
// bones (tx ty tz l) are read and ignored: a Take carries rotations only. The root position comes
// from the root's TX TY TZ values (a missing one from the ASF :root position), in ASF units.
// Bones without dofs keep the identity rotation.
// Errors are InvalidArgument "<file>:<line>: <problem>": unknown bone names, wrong value counts,
// non-finite numbers, a frame number out of sequence, a bone missing from a frame or given twice,
// a bone line before the first frame number, no frames at all.
// Thread-safety: a pure function.
#pragma once

#include <string>
#include <string_view>

#include "common/status.h"
#include "formats/import/asf_parser.h"
#include "formats/motion/take.h"

namespace motif {

// Parses `text`, the content of the AMC file `file_name`, against `asf`. The take's fps and
// source_fps are `fps` (> 0), meters_per_unit the ASF's, source_path `file_name`; name and
// content_hash are left unset; the skeleton has family "custom".
Result<Take> ParseAmc(const AsfSkeleton& asf, std::string_view text, const std::string& file_name,
                      double fps);

}  // namespace motif
