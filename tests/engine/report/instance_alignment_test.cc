#include "engine/report/instance_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace motif {
namespace {

// One weighted joint whose rotation about X sweeps through `angles` (radians); stride 8 floats.
std::vector<float> Rows(const std::vector<double>& angles) {
  std::vector<float> rows;
  for (double angle : angles) {
    const float row[8] = {static_cast<float>(std::cos(angle / 2)),
                          static_cast<float>(std::sin(angle / 2)), 0, 0, 0, 0, 0, 0};
    rows.insert(rows.end(), row, row + 8);
  }
  return rows;
}

Skeleton OneJoint() {
  Joint joint;
  joint.name = "root";
  joint.parent = -1;
  joint.weight = 1;
  return Skeleton("custom", {joint});
}

TEST(InstanceAlignment, AnInstanceAlignsToItselfOneToOne) {
  const std::vector<float> rows = Rows({0, 0.2, 0.4, 0.6, 0.8});
  EXPECT_EQ(AlignToReference(OneJoint(), 8, rows, 5, rows, 5),
            (std::vector<uint32_t>{0, 1, 2, 3, 4}));
}

TEST(InstanceAlignment, AnInstanceAtHalfTheSpeedShowsEveryOtherSample) {
  const std::vector<float> reference = Rows({0, 0.4, 0.8, 1.2});
  const std::vector<float> slow = Rows({0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2});
  EXPECT_EQ(AlignToReference(OneJoint(), 8, reference, 4, slow, 7),
            (std::vector<uint32_t>{0, 2, 4, 6}));
}

TEST(InstanceAlignment, APauseInTheInstanceIsSkipped) {
  // The instance holds its second pose three samples long; the reference does not.
  const std::vector<float> reference = Rows({0, 0.5, 1.0, 1.5});
  const std::vector<float> paused = Rows({0, 0.5, 0.5, 0.5, 1.0, 1.5});
  EXPECT_EQ(AlignToReference(OneJoint(), 8, reference, 4, paused, 6),
            (std::vector<uint32_t>{0, 1, 4, 5}));
}

TEST(InstanceAlignment, BeyondTheCellLimitTheAlignmentIsLinear) {
  const uint32_t n = 4096, m = 2048;  // 8 M cells > kMaxAlignmentCells
  ASSERT_GT(uint64_t{n} * m, kMaxAlignmentCells);
  const std::vector<float> a(n * 8, 0.5f), b(m * 8, 0.5f);
  const std::vector<uint32_t> map = AlignToReference(OneJoint(), 8, a, n, b, m);
  ASSERT_EQ(map.size(), n);
  EXPECT_EQ(map.front(), 0u);
  EXPECT_EQ(map.back(), m - 1);
  EXPECT_EQ(map[n / 2], static_cast<uint32_t>(std::llround((n / 2) * (m - 1.0) / (n - 1))));
}

}  // namespace
}  // namespace motif
