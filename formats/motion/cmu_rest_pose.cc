#include "formats/motion/cmu_rest_pose.h"

#include <array>

#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

struct RestJoint {
  std::array<double, 3> offset;
  bool has_end_site;
  std::array<double, 3> end_site;
};

// In canonical order (canonical_skeleton.h).
constexpr RestJoint kRest[] = {
    {{0, 0, 0}, false, {}},                            // root
    {{0, 0, 0}, false, {}},                            // lhipjoint
    {{1.66, -1.80, 0.62}, false, {}},                  // lfemur
    {{2.60, -7.14, 0}, false, {}},                     // ltibia
    {{2.49, -6.85, 0}, false, {}},                     // lfoot
    {{0.20, -0.54, 2.15}, true, {0, 0, 1.11}},         // ltoes
    {{0, 0, 0}, false, {}},                            // rhipjoint
    {{-1.61, -1.80, 0.62}, false, {}},                 // rfemur
    {{-2.60, -7.13, 0}, false, {}},                    // rtibia
    {{-2.47, -6.78, 0}, false, {}},                    // rfoot
    {{-0.23, -0.63, 2.13}, true, {0, 0, 1.12}},        // rtoes
    {{0, 0, 0}, false, {}},                            // lowerback
    {{0.02, 2.05, -0.14}, false, {}},                  // upperback
    {{0.01, 2.06, -0.06}, false, {}},                  // thorax
    {{0, 0, 0}, false, {}},                            // lowerneck
    {{0.01, 1.57, 0.15}, false, {}},                   // upperneck
    {{0.03, 1.56, -0.10}, true, {0.01, 1.63, -0.05}},  // head
    {{0, 0, 0}, false, {}},                            // lclavicle
    {{3.54, 0.90, -0.17}, false, {}},                  // lhumerus
    {{4.87, 0, 0}, false, {}},                         // lradius
    {{3.36, 0, 0}, false, {}},                         // lwrist
    {{0, 0, 0}, false, {}},                            // lhand
    {{0.66, 0, 0}, true, {0.53, 0, 0}},                // lfingers
    {{0, 0, 0}, true, {0.54, 0, 0.54}},                // lthumb
    {{0, 0, 0}, false, {}},                            // rclavicle
    {{-3.50, 0.76, -0.33}, false, {}},                 // rhumerus
    {{-5.03, 0, 0}, false, {}},                        // rradius
    {{-3.36, 0, 0}, false, {}},                        // rwrist
    {{0, 0, 0}, false, {}},                            // rhand
    {{-0.73, 0, 0}, true, {-0.59, 0, 0}},              // rfingers
    {{0, 0, 0}, true, {-0.60, 0, 0.60}},               // rthumb
};

Skeleton BuildRestSkeleton() {
  const auto& names = CmuCanonicalJointNames();
  const auto& parents = CmuCanonicalParents();
  std::vector<Joint> joints;
  for (size_t index = 0; index < names.size(); ++index) {
    Joint joint;
    joint.name = names[index];
    joint.parent = parents[index];
    joint.offset = kRest[index].offset;
    joint.has_end_site = kRest[index].has_end_site;
    joint.end_site = kRest[index].end_site;
    if (index == 0) {
      joint.channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition};
    }
    for (ChannelType rotation :
         {ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation}) {
      joint.channels.push_back(rotation);
    }
    joint.weight = DefaultJointWeight(kCmuFamily, joint.name, index == 0);
    joints.push_back(std::move(joint));
  }
  return Skeleton(kCmuFamily, std::move(joints));
}

}  // namespace

const Skeleton& CmuRestSkeleton() {
  static_assert(std::size(kRest) == 31, "one rest joint per canonical joint");
  static const Skeleton* skeleton = new Skeleton(BuildRestSkeleton());
  return *skeleton;
}

const CmuHingeAxes& CmuRestHingeAxes() {
  // Measured on CMU takes (docs/design/mixed_skeletons.md): the ASF's elbow axes lean 30
  // degrees and its knee axes 20 degrees from the rest pose's axes.
  static const CmuHingeAxes* axes =
      new CmuHingeAxes{Eigen::Vector3d(0, -0.8660, 0.5), Eigen::Vector3d(0, 0.8660, -0.5),
                       Eigen::Vector3d(0.9397, 0.3420, 0), Eigen::Vector3d(0.9397, -0.3420, 0)};
  return *axes;
}

}  // namespace motif
