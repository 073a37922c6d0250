// CmuBodyModel: the body the procedural synthesiser animates, CMU's 31-joint skeleton ("cmu31")
// in canonical joint order, with bone directions, lengths, bone axes and per-DOF joint limits of a
// real CMU subject (subject 05's ASF calibration). Joint offsets follow the ASF anatomy: a joint
// sits at the end of its parent's bone (direction * length); the seven leaves carry end sites.
//
// Motion is described by a parameter vector (`params`, param_count() doubles per frame):
//   [0, dof_count())  raw DOF angles in degrees: root pitch (rx), yaw (ry), roll (rz), then
//                     each bone's ASF DOFs (e.g. lfemur rx ry rz, ltibia rx, ...)
//   heading rate      degrees per second, about the vertical axis
//   forward, side     root speed in the heading frame, length units per second
//   jump              height above the grounded root height, length units (>= 0)
// Raw angles may be blended and perturbed freely: Pose() passes each through a smooth saturating
// clamp that is the identity inside the limits' interior and approaches the limit only
// asymptotically, so every produced rotation lies within its joint's limits (knees and elbows
// bend one way only) and blended or noisy parameters stay smooth.
// A bone's rest-aligned local rotation is C * Rz(rz) Ry(ry) Rx(rx) * C^-1 with C its ASF axis
// rotation (as the importers produce for AMC takes).
// Thread-safety: an immutable singleton; const methods are safe from many threads.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "formats/motion/quaternion_math.h"
#include "formats/motion/skeleton.h"

namespace motif {

struct BodyDof {
  int joint = 0;  // canonical joint index (0 = root)
  Axis axis = Axis::kX;
  double lo_deg = 0;  // ASF limits, degrees
  double hi_deg = 0;
};

class CmuBodyModel {
 public:
  static const CmuBodyModel& Get();

  // "cmu31", canonical order, default weights, BVH-style channels, ASF length units.
  const Skeleton& skeleton() const { return skeleton_; }
  // Metres per length unit of the skeleton (CMU: 0.45 inch units, 0.0564 m).
  static constexpr double kMetersPerUnit = 2.54 / 100.0 / 0.45;

  size_t joint_count() const { return skeleton_.joint_count(); }
  size_t dof_count() const { return dofs_.size(); }
  size_t param_count() const { return dofs_.size() + 4; }
  size_t heading_rate_param() const { return dofs_.size(); }
  size_t forward_speed_param() const { return dofs_.size() + 1; }
  size_t side_speed_param() const { return dofs_.size() + 2; }
  size_t jump_param() const { return dofs_.size() + 3; }
  const BodyDof& dof(size_t dof_idx) const { return dofs_[dof_idx]; }

  // Index of `joint_name`'s DOF about `axis` ("root" for the root's tilt DOFs), or -1.
  int FindDof(std::string_view joint_name, Axis axis) const;
  // The DOF of the mirrored joint (lfemur <-> rfemur; central joints map to themselves) and the
  // sign that mirrors an angle of it: +1 for rx, -1 for ry and rz (a reflection through the
  // sagittal plane). Returns -1 if the mirrored joint lacks that DOF.
  int MirrorDof(size_t dof_idx, double* sign) const;

  // The limit-respecting angle (degrees) for a raw value of DOF `dof_idx`.
  double ClampedAngle(size_t dof_idx, double raw_deg) const;
  // Identity on [lo + m, hi - m] with m = min(10, (hi - lo) / 4); beyond it, approaches lo or hi
  // along a tanh (continuous in value, slope and curvature). Always within [lo, hi] (strictly
  // inside unless x is hundreds of degrees out).
  static double SoftClamp(double x, double lo, double hi);

  // Local rest-aligned rotations of every joint from `params`; rotations[0] is the root's swing
  // (pitch, yaw wiggle and roll; no heading). `rotations` has joint_count() entries.
  void Pose(const double* params, Eigen::Quaterniond* rotations) const;
  // The root height that puts the lowest point of either foot (heel, ball, toe tip) on the floor
  // y = 0 for the pose `rotations` (a smooth minimum, so the height is smooth too).
  double GroundedRootHeight(const Eigen::Quaterniond* rotations) const;

  // The inverse of Pose() for one bone (joint_idx > 0): its ASF DOF angles (rx, ry, rz, degrees)
  // from its rest-aligned local rotation, by the Euler decomposition Rz Ry Rx of C^-1 q C. A DOF
  // the bone lacks comes out near 0. For checking motion against the joint limits.
  std::array<double, 3> DofAngles(size_t joint_idx, const Eigen::Quaterniond& local) const;

 private:
  CmuBodyModel();

  struct JointDofs {
    int dof[3] = {-1, -1, -1};  // DOF index per axis x, y, z, or -1
    Eigen::Quaterniond axis_rotation = Eigen::Quaterniond::Identity();  // C
    Eigen::Quaterniond axis_inverse = Eigen::Quaterniond::Identity();   // C^-1
  };
  struct LegChain {
    int hip = 0, femur = 0, tibia = 0, foot = 0, toes = 0;
  };

  Skeleton skeleton_;
  std::vector<BodyDof> dofs_;
  std::vector<JointDofs> joint_dofs_;
  LegChain legs_[2];
};

}  // namespace motif
