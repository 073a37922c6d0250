// Rotation helpers shared by the importers, the archive conversion, export and the synthesiser.
// Conventions (used everywhere in motifmine): Y is up; a quaternion is (w, x, y, z); a rotation
// list R(a0) R(a1) ... is composed left to right, so the last listed is applied first to a vector
// (BVH's channel order; ASF's "axis XYZ" means X applied first, i.e. Rz * Ry * Rx).
// Thread-safety: pure functions.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace motif {

enum class Axis : uint8_t { kX = 0, kY = 1, kZ = 2 };

inline Eigen::Vector3d AxisVector(Axis axis) {
  switch (axis) {
    case Axis::kX:
      return Eigen::Vector3d::UnitX();
    case Axis::kY:
      return Eigen::Vector3d::UnitY();
    case Axis::kZ:
      return Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::UnitX();
}

inline Eigen::Quaterniond AxisRotation(Axis axis, double angle_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, AxisVector(axis)));
}

// R(axes[0], angles[0]) * R(axes[1], angles[1]) * ... for `count` rotations.
inline Eigen::Quaterniond ComposeRotations(const Axis* axes, const double* angles_rad, int count) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int idx = 0; idx < count; ++idx) q = q * AxisRotation(axes[idx], angles_rad[idx]);
  return q;
}

constexpr double kPi = 3.14159265358979323846;
inline double DegreesToRadians(double degrees) { return degrees * (kPi / 180.0); }
inline double RadiansToDegrees(double radians) { return radians * (180.0 / kPi); }

// Wraps an angle to (-pi, pi].
inline double WrapAngle(double angle_rad) {
  double wrapped = std::remainder(angle_rad, 2.0 * kPi);
  return wrapped <= -kPi ? wrapped + 2.0 * kPi : wrapped;
}

// The heading of a root rotation: the angle of its twist about the vertical (Y) axis in the
// swing-twist decomposition q = Ry(heading) * swing, where swing has no Y component. In (-pi, pi].
inline double HeadingOf(const Eigen::Quaterniond& q) {
  return WrapAngle(2.0 * std::atan2(q.y(), q.w()));
}

// The swing part of q once its heading is removed: Ry(heading)^-1 * q.
inline Eigen::Quaterniond RemoveHeading(const Eigen::Quaterniond& q, double heading_rad) {
  return AxisRotation(Axis::kY, -heading_rad) * q;
}

// Distance between two rotations given as unit quaternions, independent of their signs:
// min(|a - b|, |a + b|), in [0, sqrt(2)].
inline double QuaternionDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

// The rotation angle (radians, in [0, pi]) between two rotations.
inline double RotationAngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  double dot = std::abs(a.dot(b)) / (a.norm() * b.norm());
  return 2.0 * std::acos(std::min(1.0, dot));
}

// q or -q, whichever is on the same side as `reference` (non-negative dot product).
inline Eigen::Quaterniond AlignSign(const Eigen::Quaterniond& q,
                                    const Eigen::Quaterniond& reference) {
  if (q.dot(reference) < 0) return Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z());
  return q;
}

// Euler angles (radians) for `q` in the order `axes` (three distinct axes), such that
// ComposeRotations(axes, result, 3) equals q. Of the two solutions, returns the one closest to
// `previous` (pass the previous frame's angles to keep exported channels continuous).
std::array<double, 3> QuaternionToEuler(const Eigen::Quaterniond& q,
                                        const std::array<Axis, 3>& axes,
                                        const std::array<double, 3>& previous = {0, 0, 0});

}  // namespace motif
