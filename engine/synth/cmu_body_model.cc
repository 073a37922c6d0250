#include "engine/synth/cmu_body_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "common/status.h"
#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

struct DofLimit {
  char axis;  // 'x', 'y', 'z'; 0 ends the list
  double lo_deg;
  double hi_deg;
};

// One ASF bone: direction, length, axis (Euler XYZ, degrees) and DOFs with limits. Numbers from
// CMU subject 05's calibration (length unit 0.45 inch).
struct BoneSpec {
  const char* name;
  std::array<double, 3> direction;
  double length;
  std::array<double, 3> axis_deg;
  std::array<DofLimit, 3> dofs;
};

// clang-format off
constexpr BoneSpec kBones[] = {
    {"lhipjoint", {0.653368, -0.678499, 0.335782}, 2.51848, {0, 0, 0}, {}},
    {"lfemur", {0.34202, -0.939693, 0}, 6.57749, {0, 0, 20},
     {{{'x', -160, 20}, {'y', -70, 70}, {'z', -60, 70}}}},
    {"ltibia", {0.34202, -0.939693, 0}, 7.94618, {0, 0, 20}, {{{'x', -10, 170}}}},
    {"lfoot", {0.0811271, -0.222895, 0.971461}, 2.31339, {-90, 0, 20},
     {{{'x', -45, 90}, {'z', -70, 20}}}},
    {"ltoes", {0, 0, 1}, 1.15935, {-90, 0, 20}, {{{'x', -90, 20}}}},
    {"rhipjoint", {-0.640058, -0.688614, 0.340788}, 2.48149, {0, 0, 0}, {}},
    {"rfemur", {-0.34202, -0.939693, 0}, 6.57875, {0, 0, -20},
     {{{'x', -160, 20}, {'y', -70, 70}, {'z', -70, 60}}}},
    {"rtibia", {-0.34202, -0.939693, 0}, 7.977, {0, 0, -20}, {{{'x', -10, 170}}}},
    {"rfoot", {-0.0979793, -0.269196, 0.958089}, 2.19857, {-90, 0, -20},
     {{{'x', -45, 90}, {'z', -20, 70}}}},
    {"rtoes", {0, 0, 1}, 1.09838, {-90, 0, -20}, {{{'x', -90, 20}}}},
    {"lowerback", {0.0149039, 0.998517, -0.0523597}, 2.10809, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"upperback", {-0.00882659, 0.999418, -0.0329624}, 2.1102, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"thorax", {-0.0165585, 0.999826, -0.0085833}, 2.11039, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"lowerneck", {-0.0130877, 0.999911, 0.00260353}, 1.73253, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"upperneck", {-0.0348454, 0.928205, -0.370435}, 1.66692, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"head", {-0.00807754, 0.992494, -0.122026}, 1.72765, {0, 0, 0},
     {{{'x', -20, 45}, {'y', -30, 30}, {'z', -30, 30}}}},
    {"lclavicle", {0.987582, 0.144023, 0.0627671}, 3.49235, {0, 0, 0},
     {{{'y', -20, 10}, {'z', 0, 20}}}},
    {"lhumerus", {1, 0, 0}, 5.41917, {180, -30, -90},
     {{{'x', -60, 90}, {'y', -90, 90}, {'z', -90, 90}}}},
    {"lradius", {1, 0, 0}, 2.44373, {180, -30, -90}, {{{'x', -10, 170}}}},
    {"lwrist", {1, 0, 0}, 1.22186, {0, 90, 90}, {{{'y', -180, 0}}}},
    {"lhand", {1, 0, 0}, 0.727502, {0, 90, 90}, {{{'x', -90, 90}, {'z', -45, 45}}}},
    {"lfingers", {1, 0, 0}, 0.586531, {0, 90, 90}, {{{'x', 0, 90}}}},
    {"lthumb", {0.707107, 0, 0.707107}, 0.842145, {-90, 45, 0},
     {{{'x', -45, 45}, {'z', -45, 45}}}},
    {"rclavicle", {-0.980998, 0.169556, 0.0943023}, 3.29272, {0, 0, 0},
     {{{'y', -10, 20}, {'z', -20, 0}}}},
    {"rhumerus", {-1, -1.83355e-005, 2.45537e-005}, 5.58976, {-180, 30, 90},
     {{{'x', -90, 60}, {'y', -90, 90}, {'z', -90, 90}}}},
    {"rradius", {-1, 0, 0}, 2.4806, {-180, 30, 90}, {{{'x', -10, 170}}}},
    {"rwrist", {-1, 0, 0}, 1.2403, {0, -90, -90}, {{{'y', -180, 0}}}},
    {"rhand", {-1, 0, 0}, 0.816009, {0, -90, -90}, {{{'x', -90, 90}, {'z', -45, 45}}}},
    {"rfingers", {-1, 0, 0}, 0.657887, {0, -90, -90}, {{{'x', 0, 90}}}},
    {"rthumb", {-0.707107, 0, 0.707107}, 0.944599, {-90, -45, 0},
     {{{'x', -45, 45}, {'z', -45, 45}}}},
};
// clang-format on

// The root's tilt DOFs (the heading is free and carried separately): a person leans forward
// more than back, and sways less than that sideways.
constexpr DofLimit kRootDofs[] = {{'x', -20, 50}, {'y', -45, 45}, {'z', -25, 25}};

// Foot geometry for grounding: the heel sits this far below the ankle joint, the floor this far
// below the lowest foot point (skin and shoe), and the smooth minimum's softness.
constexpr double kHeelDepth = 0.45;
constexpr double kSoleDepth = 0.4;
constexpr double kSoftMinScale = 0.2;

Axis AxisOf(char axis) { return axis == 'x' ? Axis::kX : axis == 'y' ? Axis::kY : Axis::kZ; }

const BoneSpec* FindBone(const std::string& name) {
  for (const BoneSpec& bone : kBones) {
    if (name == bone.name) return &bone;
  }
  return nullptr;
}

std::array<double, 3> BoneVector(const BoneSpec& bone) {
  return {bone.direction[0] * bone.length, bone.direction[1] * bone.length,
          bone.direction[2] * bone.length};
}

Eigen::Vector3d ToVector(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

const CmuBodyModel& CmuBodyModel::Get() {
  static const CmuBodyModel* model = new CmuBodyModel();
  return *model;
}

CmuBodyModel::CmuBodyModel() {
  const std::vector<std::string>& names = CmuCanonicalJointNames();
  const std::vector<int>& parents = CmuCanonicalParents();
  std::vector<Joint> joints(names.size());
  joint_dofs_.resize(names.size());
  for (const DofLimit& limit : kRootDofs) {
    joint_dofs_[0].dof[static_cast<int>(AxisOf(limit.axis))] = static_cast<int>(dofs_.size());
    dofs_.push_back({0, AxisOf(limit.axis), limit.lo_deg, limit.hi_deg});
  }
  std::vector<bool> has_child(names.size(), false);
  for (size_t joint_idx = 1; joint_idx < names.size(); ++joint_idx)
    has_child[parents[joint_idx]] = true;
  for (size_t joint_idx = 0; joint_idx < names.size(); ++joint_idx) {
    Joint& joint = joints[joint_idx];
    joint.name = names[joint_idx];
    joint.parent = parents[joint_idx];
    joint.weight = DefaultJointWeight(kCmuFamily, joint.name, joint_idx == 0);
    if (joint_idx == 0) {
      joint.channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition,
                        ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
      continue;
    }
    joint.channels = {ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
    const BoneSpec* bone = FindBone(joint.name);
    MOTIF_CHECK(bone != nullptr);
    // The joint sits at the end of its parent's bone; the root's children sit at the root.
    if (joint.parent > 0) {
      const BoneSpec* parent_bone = FindBone(names[joint.parent]);
      MOTIF_CHECK(parent_bone != nullptr);
      joint.offset = BoneVector(*parent_bone);
    }
    if (!has_child[joint_idx]) {
      joint.has_end_site = true;
      joint.end_site = BoneVector(*bone);
    }
    JointDofs& joint_dofs = joint_dofs_[joint_idx];
    const double deg = kPi / 180.0;
    joint_dofs.axis_rotation = AxisRotation(Axis::kZ, bone->axis_deg[2] * deg) *
                               AxisRotation(Axis::kY, bone->axis_deg[1] * deg) *
                               AxisRotation(Axis::kX, bone->axis_deg[0] * deg);
    joint_dofs.axis_inverse = joint_dofs.axis_rotation.conjugate();
    for (const DofLimit& limit : bone->dofs) {
      if (limit.axis == 0) break;
      joint_dofs.dof[static_cast<int>(AxisOf(limit.axis))] = static_cast<int>(dofs_.size());
      dofs_.push_back(
          {static_cast<int>(joint_idx), AxisOf(limit.axis), limit.lo_deg, limit.hi_deg});
    }
  }
  skeleton_ = Skeleton(kCmuFamily, std::move(joints));
  MOTIF_CHECK(skeleton_.Validate().ok());
  const char* sides[2] = {"l", "r"};
  for (int side = 0; side < 2; ++side) {
    const std::string prefix = sides[side];
    legs_[side].hip = skeleton_.FindJoint(prefix + "hipjoint");
    legs_[side].femur = skeleton_.FindJoint(prefix + "femur");
    legs_[side].tibia = skeleton_.FindJoint(prefix + "tibia");
    legs_[side].foot = skeleton_.FindJoint(prefix + "foot");
    legs_[side].toes = skeleton_.FindJoint(prefix + "toes");
    MOTIF_CHECK(legs_[side].hip > 0 && legs_[side].toes > 0);
  }
}

int CmuBodyModel::FindDof(std::string_view joint_name, Axis axis) const {
  const int joint_idx = skeleton_.FindJoint(std::string(joint_name));
  if (joint_idx < 0) return -1;
  return joint_dofs_[joint_idx].dof[static_cast<int>(axis)];
}

int CmuBodyModel::MirrorDof(size_t dof_idx, double* sign) const {
  const BodyDof& body_dof = dofs_[dof_idx];
  std::string name = skeleton_.joint(body_dof.joint).name;
  if (name[0] == 'l' && name != "lowerback" && name != "lowerneck") {
    name[0] = 'r';
  } else if (name[0] == 'r' && name != "root") {
    name[0] = 'l';
  }
  *sign = body_dof.axis == Axis::kX ? 1.0 : -1.0;
  return FindDof(name, body_dof.axis);
}

double CmuBodyModel::SoftClamp(double x, double lo, double hi) {
  const double margin = std::min(10.0, 0.25 * (hi - lo));
  const double inner_lo = lo + margin;
  const double inner_hi = hi - margin;
  if (x > inner_hi) return inner_hi + margin * std::tanh((x - inner_hi) / margin);
  if (x < inner_lo) return inner_lo + margin * std::tanh((x - inner_lo) / margin);
  return x;
}

double CmuBodyModel::ClampedAngle(size_t dof_idx, double raw_deg) const {
  return SoftClamp(raw_deg, dofs_[dof_idx].lo_deg, dofs_[dof_idx].hi_deg);
}

void CmuBodyModel::Pose(const double* params, Eigen::Quaterniond* rotations) const {
  const double deg = kPi / 180.0;
  double angles[3];
  for (size_t joint_idx = 0; joint_idx < joint_dofs_.size(); ++joint_idx) {
    const JointDofs& joint_dofs = joint_dofs_[joint_idx];
    for (int axis = 0; axis < 3; ++axis) {
      const int dof_idx = joint_dofs.dof[axis];
      angles[axis] = dof_idx < 0 ? 0.0 : ClampedAngle(dof_idx, params[dof_idx]) * deg;
    }
    if (joint_idx == 0) {
      // Swing: yaw wiggle about the heading, then pitch, then roll (applied first).
      rotations[0] = AxisRotation(Axis::kY, angles[1]) * AxisRotation(Axis::kX, angles[0]) *
                     AxisRotation(Axis::kZ, angles[2]);
      continue;
    }
    Eigen::Quaterniond local = Eigen::Quaterniond::Identity();
    if (joint_dofs.dof[2] >= 0) local = local * AxisRotation(Axis::kZ, angles[2]);
    if (joint_dofs.dof[1] >= 0) local = local * AxisRotation(Axis::kY, angles[1]);
    if (joint_dofs.dof[0] >= 0) local = local * AxisRotation(Axis::kX, angles[0]);
    rotations[joint_idx] = joint_dofs.axis_rotation * local * joint_dofs.axis_inverse;
  }
}

double CmuBodyModel::GroundedRootHeight(const Eigen::Quaterniond* rotations) const {
  // Heights (y, relative to the root) of each foot's heel, ball and toe tip.
  double heights[6] = {};
  int count = 0;
  for (const LegChain& leg : legs_) {
    auto offset = [&](int joint_idx) { return ToVector(skeleton_.joint(joint_idx).offset); };
    Eigen::Quaterniond frame = rotations[0] * rotations[leg.hip];
    Eigen::Vector3d position = rotations[0] * offset(leg.hip);
    position += frame * offset(leg.femur);
    frame = frame * rotations[leg.femur];
    position += frame * offset(leg.tibia);
    frame = frame * rotations[leg.tibia];
    position += frame * offset(leg.foot);  // the ankle
    heights[count++] = position.y() - kHeelDepth;
    frame = frame * rotations[leg.foot];
    position += frame * offset(leg.toes);  // the ball of the foot
    heights[count++] = position.y();
    frame = frame * rotations[leg.toes];
    position += frame * ToVector(skeleton_.joint(leg.toes).end_site);
    heights[count++] = position.y();
  }
  const double lowest = *std::min_element(heights, heights + count);
  double sum = 0;
  for (int idx = 0; idx < count; ++idx) sum += std::exp(-(heights[idx] - lowest) / kSoftMinScale);
  const double soft_lowest = lowest - kSoftMinScale * std::log(sum);
  return kSoleDepth - soft_lowest;
}

std::array<double, 3> CmuBodyModel::DofAngles(size_t joint_idx,
                                              const Eigen::Quaterniond& local) const {
  const JointDofs& joint_dofs = joint_dofs_[joint_idx];
  const Eigen::Quaterniond asf = joint_dofs.axis_inverse * local * joint_dofs.axis_rotation;
  const std::array<double, 3> zyx = QuaternionToEuler(asf, {Axis::kZ, Axis::kY, Axis::kX});
  return {RadiansToDegrees(zyx[2]), RadiansToDegrees(zyx[1]), RadiansToDegrees(zyx[0])};
}

}  // namespace motif
