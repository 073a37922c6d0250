#include "archive_pose.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "keyword_arguments.h"
#include "reprs.h"
#include "status_error.h"

namespace motifmine_python {
namespace {

constexpr uint64_t kAnyFrame = UINT64_MAX;  // checked against the clip when it is read

// `values` handed to numpy without a copy, the array owning them.
py::array_t<double> OwnedArray(std::vector<double> values, std::vector<py::ssize_t> shape) {
  auto* data = new std::vector<double>(std::move(values));
  py::capsule owner(data, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(shape, data->data(), owner);
}

struct ClipRange {
  std::string clip;
  uint64_t start = 0;
  uint64_t end = 0;
  py::ssize_t frames() const { return static_cast<py::ssize_t>(end - start); }
};

// The (clip, start, end) arguments of `function`, each checked by name.
ClipRange RangeArguments(const char* function, const GivenStr& clip, const GivenInt& start,
                         const GivenInt& end) {
  return {TextArgument({function, "clip"}, clip),
          WholeArgument({function, "start"}, start, 0, kAnyFrame),
          WholeArgument({function, "end"}, end, 0, kAnyFrame)};
}

motifmine::RootMotion ReadRoot(const motifmine::Archive& archive, const ClipRange& range) {
  motifmine::RootMotion root;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = archive.Root(range.clip, range.start, range.end, &root);
  }
  Check(status);
  return root;
}

py::array_t<double> RootPositions(const motifmine::Archive& archive, const GivenStr& clip,
                                  const GivenInt& start, const GivenInt& end) {
  const ClipRange range = RangeArguments("root_positions()", clip, start, end);
  return OwnedArray(ReadRoot(archive, range).positions, {range.frames(), 3});
}

py::array_t<double> RootRotations(const motifmine::Archive& archive, const GivenStr& clip,
                                  const GivenInt& start, const GivenInt& end) {
  const ClipRange range = RangeArguments("root_rotations()", clip, start, end);
  return OwnedArray(ReadRoot(archive, range).rotations, {range.frames(), 4});
}

py::array_t<double> Headings(const motifmine::Archive& archive, const GivenStr& clip,
                             const GivenInt& start, const GivenInt& end) {
  const ClipRange range = RangeArguments("headings()", clip, start, end);
  return OwnedArray(ReadRoot(archive, range).headings, {range.frames()});
}

py::array_t<double> WorldPositions(const motifmine::Archive& archive, const GivenStr& clip,
                                   const GivenInt& start, const GivenInt& end) {
  const ClipRange range = RangeArguments("world_positions()", clip, start, end);
  std::vector<double> positions;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = archive.WorldPositions(range.clip, range.start, range.end, &positions);
  }
  Check(status);
  const auto joints = static_cast<py::ssize_t>(archive.joint_names().size());
  return OwnedArray(std::move(positions), {range.frames(), joints, 3});
}

motifmine::Skeleton ClipSkeleton(const motifmine::Archive& archive, const GivenStr& clip) {
  motifmine::Skeleton skeleton;
  Check(archive.ClipSkeleton(TextArgument({"clip_skeleton()", "clip"}, clip), &skeleton));
  return skeleton;
}

py::array_t<double> Offsets(const motifmine::Skeleton& skeleton) {
  std::vector<double> values;
  for (const auto& offset : skeleton.offsets)
    values.insert(values.end(), offset.begin(), offset.end());
  return OwnedArray(std::move(values), {static_cast<py::ssize_t>(skeleton.offsets.size()), 3});
}

}  // namespace

void BindSkeleton(py::module_& module) {
  py::class_<motifmine::Skeleton>(module, "Skeleton")
      .def_readonly("family", &motifmine::Skeleton::family)
      .def_readonly("joint_names", &motifmine::Skeleton::joint_names,
                    "the archive's (canonical) names: 'lfemur'")
      .def_readonly("source_joint_names", &motifmine::Skeleton::source_joint_names,
                    "the imported file's names ('LeftUpLeg' in a BVH take), as export writes them")
      .def_readonly("parents", &motifmine::Skeleton::parents, "each joint's parent; -1: the root")
      .def_property_readonly("offsets", &Offsets,
                             "float64 array (joints, 3): each joint's rest offset from its parent")
      .def("__repr__", &SkeletonRepr);
}

void AddPoseMethods(py::class_<motifmine::Archive>& archive) {
  archive
      .def_property_readonly("skeleton", &motifmine::Archive::skeleton,
                             "the archive's Skeleton (its rest offsets; source_joint_names those "
                             "its clips share)")
      .def("clip_skeleton", &ClipSkeleton, py::arg("clip"),
           "the clip's own Skeleton: its source joint names and bone offsets, as export writes")
      .def("root_positions", &RootPositions, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float64 array (frames, 3): the root's world position, integrated from the clip's "
           "first frame as `motifmine export` does")
      .def("root_rotations", &RootRotations, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float64 array (frames, 4): the root's world rotation (w, x, y, z), heading included")
      .def("headings", &Headings, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float64 array (frames,): the root's heading about the vertical Y axis, radians, "
           "unwrapped along the clip")
      .def("world_positions", &WorldPositions, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float64 array (frames, joints, 3): every joint's world position (forward kinematics "
           "over clip_skeleton(clip), the root at root_positions)");
}

}  // namespace motifmine_python
