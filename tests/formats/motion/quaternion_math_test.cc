#include "formats/motion/quaternion_math.h"

#include <random>

#include <gtest/gtest.h>

namespace motif {
namespace {

const std::array<Axis, 3> kOrders[] = {
    {Axis::kX, Axis::kY, Axis::kZ}, {Axis::kX, Axis::kZ, Axis::kY}, {Axis::kY, Axis::kX, Axis::kZ},
    {Axis::kY, Axis::kZ, Axis::kX}, {Axis::kZ, Axis::kX, Axis::kY}, {Axis::kZ, Axis::kY, Axis::kX}};

TEST(QuaternionToEuler, RoundTripsEveryOrder) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (const auto& order : kOrders) {
    for (int trial = 0; trial < 500; ++trial) {
      Eigen::Quaterniond q(angle(rng), angle(rng), angle(rng), angle(rng));
      q.normalize();
      std::array<double, 3> euler = QuaternionToEuler(q, order);
      Eigen::Quaterniond back = ComposeRotations(order.data(), euler.data(), 3);
      EXPECT_LT(QuaternionDistance(q, back), 1e-9);
    }
  }
}

TEST(QuaternionToEuler, HandlesGimbalLockAndStaysNearPrevious) {
  for (const auto& order : kOrders) {
    const double angles[3] = {0.3, kPi / 2, -0.2};
    Eigen::Quaterniond q = ComposeRotations(order.data(), angles, 3);
    std::array<double, 3> euler = QuaternionToEuler(q, order, {0.3, 1.5, -0.2});
    EXPECT_LT(QuaternionDistance(q, ComposeRotations(order.data(), euler.data(), 3)), 1e-9);
  }
  // A small step from the previous angles gives angles near them, not a wrapped equivalent.
  const std::array<Axis, 3> zyx = {Axis::kZ, Axis::kY, Axis::kX};
  const double angles[3] = {3.1, 0.2, -3.1};
  std::array<double, 3> euler =
      QuaternionToEuler(ComposeRotations(zyx.data(), angles, 3), zyx, {3.05, 0.2, -3.05});
  EXPECT_NEAR(euler[0], 3.1, 1e-9);
  EXPECT_NEAR(euler[2], -3.1, 1e-9);
}

TEST(Heading, SwingTwistSplitsOffTheVerticalRotation) {
  const double tilt[2] = {0.4, -0.3};
  const Axis tilt_axes[2] = {Axis::kX, Axis::kZ};
  Eigen::Quaterniond swing = ComposeRotations(tilt_axes, tilt, 2);
  // Remove any Y part the tilt composition has, so swing is a pure swing.
  swing = RemoveHeading(swing, HeadingOf(swing));
  EXPECT_NEAR(swing.y(), 0.0, 1e-12);
  for (double heading : {-3.0, -1.0, 0.0, 0.5, 2.9}) {
    Eigen::Quaterniond q = AxisRotation(Axis::kY, heading) * swing;
    EXPECT_NEAR(HeadingOf(q), heading, 1e-12);
    EXPECT_LT(QuaternionDistance(RemoveHeading(q, HeadingOf(q)), swing), 1e-12);
  }
}

TEST(QuaternionDistance, IgnoresSign) {
  Eigen::Quaterniond q = AxisRotation(Axis::kX, 0.7);
  Eigen::Quaterniond minus_q(-q.w(), -q.x(), -q.y(), -q.z());
  EXPECT_NEAR(QuaternionDistance(q, minus_q), 0.0, 1e-15);
  EXPECT_NEAR(RotationAngleBetween(q, AxisRotation(Axis::kX, 0.2)), 0.5, 1e-12);
}

}  // namespace
}  // namespace motif
