// The Python side of an archive's poses (docs/python.md, "Rebuilding a pose"): motifmine.Skeleton,
// and the methods of motifmine.Archive that give a clip range's root and its joints' world
// positions as numpy arrays (copies: they are computed, not views of the archive). Each call
// checks its arguments by name (keyword_arguments.h) and reads without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <motifmine/motifmine.h>

namespace motifmine_python {

// motifmine.Skeleton: family, joint_names, source_joint_names, parents, offsets (J, 3).
void BindSkeleton(pybind11::module_& module);

// Archive.skeleton, clip_skeleton, root_positions, root_rotations, headings, world_positions.
void AddPoseMethods(pybind11::class_<motifmine::Archive>& archive);

}  // namespace motifmine_python
