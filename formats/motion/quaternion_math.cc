#include "formats/motion/quaternion_math.h"

namespace motif {

std::array<double, 3> QuaternionToEuler(const Eigen::Quaterniond& q,
                                        const std::array<Axis, 3>& axes,
                                        const std::array<double, 3>& previous) {
  // Tait-Bryan decomposition M = R_i(a) R_j(b) R_k(c) for distinct axes i, j, k. With parity
  // sign s = +1 for cyclic (x,y,z), (y,z,x), (z,x,y) and -1 otherwise:
  //   b = asin(s * M(i,k)), a = atan2(-s * M(j,k), M(k,k)), c = atan2(-s * M(i,j), M(i,i)).
  const Eigen::Matrix3d m = q.normalized().toRotationMatrix();
  const int i = static_cast<int>(axes[0]);
  const int j = static_cast<int>(axes[1]);
  const int k = static_cast<int>(axes[2]);
  const double s = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;
  // b from atan2 with cos(b) = |(M(j,k), M(k,k))| stays accurate near +-90 degrees, where
  // asin loses precision; the lock branch is needed only when cos(b) vanishes.
  const double cos_b = std::hypot(m(j, k), m(k, k));
  std::array<double, 3> first;
  first[1] = std::atan2(s * m(i, k), cos_b);
  if (cos_b > 1e-7) {
    first[0] = std::atan2(-s * m(j, k), m(k, k));
    first[2] = std::atan2(-s * m(i, j), m(i, i));
  } else {
    // Gimbal lock: only a combination of a and c is determined; keep c at its previous value and
    // solve R_i(a) R_j(b) = M R_k(-c) for a. R_j(b) fixes e_j, so column j is R_i(a) e_j
    // = cos(a) e_j + s sin(a) e_k.
    first[2] = previous[2];
    const Eigen::Matrix3d n = m * AxisRotation(axes[2], -first[2]).toRotationMatrix();
    first[0] = std::atan2(s * n(k, j), n(j, j));
  }
  // The other solution: (a + pi, pi - b, c + pi).
  std::array<double, 3> second = {first[0] + kPi, kPi - first[1], first[2] + kPi};
  auto unwrap_near = [&](std::array<double, 3>& angles) {
    double cost = 0;
    for (int idx = 0; idx < 3; ++idx) {
      angles[idx] = previous[idx] + WrapAngle(angles[idx] - previous[idx]);
      cost += std::abs(angles[idx] - previous[idx]);
    }
    return cost;
  };
  double cost_first = unwrap_near(first);
  double cost_second = unwrap_near(second);
  return cost_second < cost_first ? second : first;
}

}  // namespace motif
