#include "engine/embedding/word_input.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "engine/distance/pose_features.h"

namespace motif {
namespace {

std::vector<int16_t> Quantised(const Eigen::Quaterniond& q, double sign = 1.0) {
  return {static_cast<int16_t>(std::lround(sign * q.w() * PoseFeatures::kQuantScale)),
          static_cast<int16_t>(std::lround(sign * q.x() * PoseFeatures::kQuantScale)),
          static_cast<int16_t>(std::lround(sign * q.y() * PoseFeatures::kQuantScale)),
          static_cast<int16_t>(std::lround(sign * q.z() * PoseFeatures::kQuantScale))};
}

TEST(WordInput, RotationChannelsAreTheFirstTwoColumnsOfTheMatrixWhateverTheSign) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const float root[4] = {1, 2, 3, 4};
  for (double sign : {1.0, -1.0}) {
    const std::vector<int16_t> features = Quantised(q, sign);
    std::vector<float> out(WordInputChannels(1));
    EncodeWordInput(features.data(), root, 1, 1, out.data());
    ASSERT_EQ(out.size(), 10u);
    for (int row = 0; row < 3; ++row) {
      EXPECT_NEAR(out[row], r(row, 0), 1e-4) << "column 0, row " << row;
      EXPECT_NEAR(out[3 + row], r(row, 1), 1e-4) << "column 1, row " << row;
    }
    EXPECT_EQ(out[6], 1.0f);
    EXPECT_EQ(out[9], 4.0f);
  }
}

TEST(WordInput, IdentityIsUnitColumns) {
  const std::vector<int16_t> features = Quantised(Eigen::Quaterniond::Identity());
  const float root[4] = {0, 0, 0, 0};
  std::vector<float> out(WordInputChannels(1));
  EncodeWordInput(features.data(), root, 1, 1, out.data());
  const float expected[6] = {1, 0, 0, 0, 1, 0};
  for (int idx = 0; idx < 6; ++idx) EXPECT_NEAR(out[idx], expected[idx], 1e-6);
}

TEST(WordInput, RootMotionScalesVelocityWithSpeedAndDifferencesTheHeading) {
  const FrameLayout layout{1};
  const uint32_t frames = 3;
  std::vector<float> rows(frames * layout.stride(), 0.0f);
  const float headings[3] = {0.5f, 0.75f, 1.25f};
  for (uint32_t frame = 0; frame < frames; ++frame) {
    float* row = &rows[frame * layout.stride()];
    row[layout.height_offset()] = 10.0f + frame;
    row[layout.velocity_offset()] = 2.0f;
    row[layout.velocity_offset() + 1] = -1.0f;
    row[layout.heading_offset()] = headings[frame];
  }
  std::vector<float> out(frames * kRootMotionChannels);
  RootMotionFromRows(layout, rows.data(), frames, 24.0, 1.25, out.data());
  EXPECT_EQ(out[0], 10.0f);
  EXPECT_EQ(out[1], 2.5f);
  EXPECT_EQ(out[2], -1.25f);
  EXPECT_NEAR(out[3], 0.25 * 24, 1e-5);     // frame 0: to frame 1
  EXPECT_NEAR(out[4 + 3], 0.5 * 24, 1e-5);  // frame 1: to frame 2
  EXPECT_NEAR(out[8 + 3], 0.5 * 24, 1e-5);  // frame 2 repeats frame 1
  EXPECT_EQ(out[8], 12.0f);
}

}  // namespace
}  // namespace motif
