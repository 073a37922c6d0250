#include "engine/report/forward_kinematics.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// root -> "upper" (offset 0 1 0) -> "lower" (offset 1 0 0, end site 0 0 2).
Skeleton TwoBoneChain() {
  std::vector<Joint> joints(3);
  joints[0].name = "root";
  joints[0].offset = {5, 5, 5};  // ignored: the root sits at the root position
  joints[1].name = "upper";
  joints[1].parent = 0;
  joints[1].offset = {0, 1, 0};
  joints[2].name = "lower";
  joints[2].parent = 1;
  joints[2].offset = {1, 0, 0};
  joints[2].has_end_site = true;
  joints[2].end_site = {0, 0, 2};
  return Skeleton("custom", joints);
}

void ExpectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, 1e-12)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

TEST(ForwardKinematics, TwoBoneChainGivesExactPositions) {
  const Skeleton skeleton = TwoBoneChain();
  ASSERT_EQ(PosePointCount(skeleton), 4u);
  // Root turned 90 degrees about Y, the upper joint bent 90 degrees about Z.
  const Eigen::Quaterniond rotations[3] = {AxisRotation(Axis::kY, kPi / 2),
                                           AxisRotation(Axis::kZ, kPi / 2),
                                           Eigen::Quaterniond::Identity()};
  const std::vector<Eigen::Vector3d> points =
      ForwardKinematics(skeleton, Eigen::Vector3d(1, 2, 3), rotations);
  ASSERT_EQ(points.size(), 4u);
  ExpectNear(points[0], {1, 2, 3});
  ExpectNear(points[1], {1, 3, 3});  // Ry(90) leaves (0 1 0) alone
  ExpectNear(points[2], {1, 4, 3});  // Ry(90) Rz(90) (1 0 0) = (0 1 0)
  ExpectNear(points[3], {3, 4, 3});  // Ry(90) Rz(90) (0 0 2) = (2 0 0)
}

TEST(ForwardKinematics, RestPoseAddsTheOffsets) {
  const std::vector<Eigen::Vector3d> points = RestPosePositions(TwoBoneChain());
  ExpectNear(points[0], {0, 0, 0});
  ExpectNear(points[1], {0, 1, 0});
  ExpectNear(points[2], {1, 1, 0});
  ExpectNear(points[3], {1, 1, 2});
}

TEST(ForwardKinematics, TakeFramePositionsUsesTheFrame) {
  Take take;
  take.skeleton = TwoBoneChain();
  take.root_positions = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 10, 0)};
  take.rotations.assign(6, Eigen::Quaterniond::Identity());
  take.rotation(1, 1) = AxisRotation(Axis::kZ, kPi / 2);
  const std::vector<Eigen::Vector3d> points = TakeFramePositions(take, 1);
  ExpectNear(points[2], {0, 12, 0});
  ExpectNear(points[3], {0, 12, 2});
}

// A real BVH take, stored in an archive (quantised rotations, integrated root) and read back
// through ClipFramesToTake, puts every joint where the BVH's own motion does.
TEST(ForwardKinematics, ArchivedRealTakeMatchesTheBvhPositions) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string bvh = testing::MocapDir() + "/bvh/05_01.bvh";
  if (!std::filesystem::exists(bvh)) GTEST_SKIP() << bvh << " not found";
  Result<Take> take = ImportTake({TakeFormat::kBvh, bvh, "", ""}, {});
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  {
    auto writer = FrameFileWriter::Create(archive, take->skeleton, take->fps);
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    ASSERT_TRUE((*writer)->AppendClip(TakeToClipFrames(*take)).ok());
    ASSERT_TRUE((*writer)->Commit().ok());
  }
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  const ClipInfo& clip = (*reader)->clips()[0];
  std::vector<float> rows;
  ASSERT_TRUE((*reader)->ReadFrames(0, clip.frame_count, &rows).ok());
  const Take back = ClipFramesToTake((*reader)->skeleton(), clip, rows.data(), clip.frame_count);
  double worst = 0;
  for (size_t frame_idx = 0; frame_idx < take->frame_count(); frame_idx += 97) {
    const std::vector<Eigen::Vector3d> expected = TakeFramePositions(*take, frame_idx);
    const std::vector<Eigen::Vector3d> actual = TakeFramePositions(back, frame_idx);
    ASSERT_EQ(actual.size(), expected.size());
    // Relative to the root: the integrated root path drifts by the velocity quantisation,
    // which is not what this test is about.
    for (size_t point_idx = 0; point_idx < actual.size(); ++point_idx) {
      const Eigen::Vector3d error =
          (actual[point_idx] - actual[0]) - (expected[point_idx] - expected[0]);
      worst = std::max(worst, error.norm());
    }
    EXPECT_NEAR(actual[0].y(), expected[0].y(), 1e-3);
  }
  EXPECT_LT(worst, 0.05) << "BVH length units";
}

}  // namespace
}  // namespace motif
