#include "engine/distance/joint_term.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace motif {
namespace {

struct Sums {
  float norm_q;
  float norm_p;
  float dot;
};

// Sums of unit-ish quaternions, their rounding-negative cases, zeros and a NaN.
std::vector<Sums> EdgeAndRandomSums() {
  std::vector<Sums> sums = {{1.0f, 1.0f, 1.0f},          {1.0f, 1.0f, -1.0f},
                            {1.0f, 1.0f, 1.0000001f},    {0.99999994f, 1.0f, -1.0f},
                            {0.0f, 0.0f, 0.0f},          {-0.0f, 0.0f, -0.0f},
                            {1.0f, 1.0f, 0.0f},          {std::nanf(""), 1.0f, 0.5f},
                            {1.0f, 1.0f, std::nanf("")}, {1e30f, 1e30f, 1e30f}};
  std::mt19937 random(7);
  std::uniform_real_distribution<float> norm(0.9998f, 1.0002f);
  std::uniform_real_distribution<float> dot(-1.0001f, 1.0001f);
  for (int idx = 0; idx < 2000; ++idx) sums.push_back({norm(random), norm(random), dot(random)});
  return sums;
}

TEST(JointTerm, IsMinOfTheDifferenceAndTheSumOfTwoQuaternions) {
  // q = (1, 0, 0, 0), p = (cos a, sin a, 0, 0): min(|q - p|, |q + p|) = 2 sin(min(a, pi - a) / 2).
  for (const float angle : {0.0f, 0.3f, 1.0f, 2.5f, 3.1f}) {
    const float dot = std::cos(angle);
    const float expected = 2.0f * std::sin(std::min(angle, 3.14159265f - angle) / 2.0f);
    EXPECT_NEAR(JointTermFromSums<ScalarLanes>(1.0f, 1.0f, dot), expected, 1e-3f) << angle;
  }
}

TEST(JointTerm, ClampsRoundingNegativesAndNanToZero) {
  EXPECT_EQ(JointTermFromSums<ScalarLanes>(1.0f, 1.0f, 1.0000001f), 0.0f);
  EXPECT_EQ(JointTermFromSums<ScalarLanes>(0.99999994f, 1.0f, -1.0f), 0.0f);
  EXPECT_EQ(JointTermFromSums<ScalarLanes>(std::nanf(""), 1.0f, 0.5f), 0.0f);
}

#if defined(__SSE2__)
// The LSH verification's SSE lanes give the scalar term bit for bit, edge cases included.
TEST(JointTerm, SseLanesAreBitIdenticalToTheScalarTerm) {
  const std::vector<Sums> sums = EdgeAndRandomSums();
  for (size_t first = 0; first + 4 <= sums.size(); first += 4) {
    alignas(16) float norm_q[4], norm_p[4], dot[4], lanes[4];
    for (int lane = 0; lane < 4; ++lane) {
      norm_q[lane] = sums[first + lane].norm_q;
      norm_p[lane] = sums[first + lane].norm_p;
      dot[lane] = sums[first + lane].dot;
    }
    _mm_store_ps(lanes, JointTermFromSums<SseLanes>(_mm_load_ps(norm_q), _mm_load_ps(norm_p),
                                                    _mm_load_ps(dot)));
    for (int lane = 0; lane < 4; ++lane) {
      const float scalar = JointTermFromSums<ScalarLanes>(norm_q[lane], norm_p[lane], dot[lane]);
      EXPECT_EQ(std::bit_cast<uint32_t>(lanes[lane]), std::bit_cast<uint32_t>(scalar))
          << "sums " << norm_q[lane] << " " << norm_p[lane] << " " << dot[lane];
    }
  }
}
#endif

}  // namespace
}  // namespace motif
