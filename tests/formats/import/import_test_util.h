// Helpers shared by the importer tests: fixture paths, file writing, and rotation comparison.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <string>

#include "formats/motion/quaternion_math.h"

namespace motif::import_test {

// The hand-written fixtures in tests/data/import.
// Fixtures are stored as "<name>.txt" (hand-written text, kept apart from real mocap files,
// which never enter the repository).
inline std::string FixturePath(const std::string& name) {
  return std::string(MOTIF_IMPORT_TEST_DATA) + "/" + name + ".txt";
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// R(axis0, a0) * R(axis1, a1) * ... with angles in degrees, built directly from Eigen so the
// expectations do not depend on the code under test.
inline Eigen::Quaterniond Rot(char axis, double degrees) {
  const Eigen::Vector3d vector = axis == 'x'   ? Eigen::Vector3d::UnitX()
                                 : axis == 'y' ? Eigen::Vector3d::UnitY()
                                               : Eigen::Vector3d::UnitZ();
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kPi / 180.0, vector));
}

inline ::testing::AssertionResult SameRotation(const Eigen::Quaterniond& actual,
                                               const Eigen::Quaterniond& expected,
                                               double tolerance = 1e-9) {
  const double distance = QuaternionDistance(actual.normalized(), expected.normalized());
  if (distance <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "rotations differ by " << distance << " (tolerance " << tolerance << "): actual ("
         << actual.w() << ", " << actual.x() << ", " << actual.y() << ", " << actual.z()
         << "), expected (" << expected.w() << ", " << expected.x() << ", " << expected.y() << ", "
         << expected.z() << ")";
}

}  // namespace motif::import_test
