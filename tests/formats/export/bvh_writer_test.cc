#include "formats/export/bvh_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "formats/import/bvh_parser.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using C = ChannelType;

Eigen::Quaterniond Euler(const std::array<Axis, 3>& axes, double a_deg, double b_deg,
                         double c_deg) {
  const double angles[3] = {DegreesToRadians(a_deg), DegreesToRadians(b_deg),
                            DegreesToRadians(c_deg)};
  return ComposeRotations(axes.data(), angles, 3);
}

// Joints: a root with channel order Y X Z; "spine" X Z Y; "neck" with no stored channels (ZYX
// when written); "arm" with only two rotation channels (written ZYX); "hand" Z X Y with an end
// site. Frame rotations include exact gimbal lock for each joint's order and sweeps through it.
Take SyntheticTake() {
  std::vector<Joint> joints(5);
  joints[0] = {
      "root",
      -1,
      {1, 2, 3},
      false,
      {},
      {C::kXPosition, C::kYPosition, C::kZPosition, C::kYRotation, C::kXRotation, C::kZRotation}};
  joints[1] = {"spine", 0, {0, 1, 0}, false, {}, {C::kXRotation, C::kZRotation, C::kYRotation}};
  joints[2] = {"neck", 1, {0, 1.5, 0}, true, {0, 0.5, 0.25}, {}};
  joints[3] = {"arm", 1, {1, 0, 0}, false, {}, {C::kZRotation, C::kXRotation}};
  joints[4] = {"hand", 3,           {1.25, 0, 0},
               true,   {0.5, 0, 0}, {C::kZRotation, C::kXRotation, C::kYRotation}};
  Take take;
  take.name = "synthetic";
  take.fps = 60;
  take.skeleton = Skeleton("custom", joints);
  const std::array<std::array<Axis, 3>, 5> orders = {
      std::array<Axis, 3>{Axis::kY, Axis::kX, Axis::kZ},
      {Axis::kX, Axis::kZ, Axis::kY},
      {Axis::kZ, Axis::kY, Axis::kX},
      {Axis::kZ, Axis::kY, Axis::kX},
      {Axis::kZ, Axis::kX, Axis::kY}};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-180, 180);
  auto add_frame = [&](const std::function<Eigen::Quaterniond(size_t)>& rotation_of) {
    take.root_positions.emplace_back(angle(rng) / 10, 1 + angle(rng) / 100, angle(rng) / 10);
    for (size_t joint_idx = 0; joint_idx < 5; ++joint_idx) {
      take.rotations.push_back(rotation_of(joint_idx));
    }
  };
  for (int frame_idx = 0; frame_idx < 40; ++frame_idx) {  // random rotations
    add_frame([&](size_t) { return Euler(orders[0], angle(rng), angle(rng), angle(rng)); });
  }
  // Exact and near gimbal lock of each joint's written order (QuaternionToEuler switches to its
  // lock branch within about 1e-4 degrees of it).
  for (double middle : {90.0, -90.0, 90 - 1e-5, 90 - 5e-5, -90 + 1e-4, 90 - 1e-3}) {
    for (int frame_idx = 0; frame_idx < 5; ++frame_idx) {
      add_frame([&](size_t joint_idx) {
        return Euler(orders[joint_idx], angle(rng), middle, angle(rng));
      });
    }
  }
  for (int frame_idx = 0; frame_idx <= 200; ++frame_idx) {  // smooth sweeps through the lock
    const double t = frame_idx / 200.0;
    add_frame([&](size_t joint_idx) {
      return Euler(orders[joint_idx], 30 + 400 * t, -120 + 240 * t, 10 - 50 * t);
    });
  }
  return take;
}

void ExpectSameMotion(const Take& actual, const Take& expected, double tolerance) {
  ASSERT_EQ(actual.frame_count(), expected.frame_count());
  ASSERT_EQ(actual.joint_count(), expected.joint_count());
  for (size_t joint_idx = 0; joint_idx < expected.joint_count(); ++joint_idx) {
    const Joint& want = expected.skeleton.joint(joint_idx);
    const Joint& got = actual.skeleton.joint(joint_idx);
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.parent, want.parent);
    EXPECT_EQ(got.has_end_site, want.has_end_site);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(got.offset[axis], want.offset[axis], 1e-6);
      EXPECT_NEAR(got.end_site[axis], want.end_site[axis], 1e-6);
    }
  }
  double max_distance = 0;
  for (size_t frame_idx = 0; frame_idx < expected.frame_count(); ++frame_idx) {
    EXPECT_LT((actual.root_positions[frame_idx] - expected.root_positions[frame_idx])
                  .cwiseAbs()
                  .maxCoeff(),
              1e-6);
    for (size_t joint_idx = 0; joint_idx < expected.joint_count(); ++joint_idx) {
      max_distance =
          std::max(max_distance, QuaternionDistance(actual.rotation(frame_idx, joint_idx),
                                                    expected.rotation(frame_idx, joint_idx)));
    }
  }
  EXPECT_LT(max_distance, tolerance);
}

TEST(BvhWriter, SyntheticTakeRoundTripsIncludingGimbalLock) {
  const Take take = SyntheticTake();
  Result<Take> parsed = ParseBvh(FormatBvh(take), "synthetic.bvh");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  ExpectSameMotion(*parsed, take, 1e-6);
  EXPECT_DOUBLE_EQ(parsed->fps, 60);
}

TEST(BvhWriter, WritesRootWithSixChannelsAndStoredRotationOrders) {
  const std::string text = FormatBvh(SyntheticTake());
  EXPECT_EQ(text.rfind("HIERARCHY\nROOT root\n{\n\tOFFSET 1.000000 2.000000 3.000000\n"
                       "\tCHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\n",
                       0),
            0u)
      << text.substr(0, 200);
  EXPECT_NE(text.find("JOINT spine\n\t{\n\t\tOFFSET 0.000000 1.000000 0.000000\n"
                      "\t\tCHANNELS 3 Xrotation Zrotation Yrotation\n"),
            std::string::npos);
  EXPECT_NE(text.find("JOINT neck\n\t\t{\n\t\t\tOFFSET 0.000000 1.500000 0.000000\n"
                      "\t\t\tCHANNELS 3 Zrotation Yrotation Xrotation\n\t\t\tEnd Site\n"
                      "\t\t\t{\n\t\t\t\tOFFSET 0.000000 0.500000 0.250000\n\t\t\t}\n\t\t}\n"),
            std::string::npos);
  EXPECT_NE(text.find("JOINT arm\n\t\t{\n\t\t\tOFFSET 1.000000 0.000000 0.000000\n"
                      "\t\t\tCHANNELS 3 Zrotation Yrotation Xrotation\n"),
            std::string::npos);
  EXPECT_NE(text.find("CHANNELS 3 Zrotation Xrotation Yrotation"), std::string::npos);
  EXPECT_NE(text.find("MOTION\nFrames: 271\nFrame Time: 0.0166666667\n"), std::string::npos);
  // 6 + 4 * 3 values per frame line.
  const std::string first_frame = text.substr(text.find("Frame Time:"));
  std::istringstream lines(first_frame);
  std::string line;
  std::getline(lines, line);
  std::getline(lines, line);
  std::istringstream values(line);
  int count = 0;
  std::string value;
  while (values >> value) ++count;
  EXPECT_EQ(count, 18);
  EXPECT_EQ(text.find("-0.000000"), std::string::npos);
}

TEST(BvhWriter, EulerAnglesAreContinuousAcrossFrames) {
  // A joint spinning about Y by 3 degrees a frame for two turns: the written angle keeps growing
  // past 180 instead of wrapping.
  Take take;
  std::vector<Joint> joints(1);
  joints[0] = {"root", -1, {0, 0, 0}, false, {}, {}};
  take.skeleton = Skeleton("custom", joints);
  for (int frame_idx = 0; frame_idx < 240; ++frame_idx) {
    take.root_positions.emplace_back(0, 0, 0);
    take.rotations.push_back(AxisRotation(Axis::kY, DegreesToRadians(3.0 * frame_idx)));
  }
  const std::string text = FormatBvh(take);
  std::istringstream lines(text.substr(text.find("Frame Time:")));
  std::string line;
  std::getline(lines, line);
  double previous_y = -3;
  for (int frame_idx = 0; frame_idx < 240; ++frame_idx) {
    ASSERT_TRUE(std::getline(lines, line));
    std::istringstream values(line);
    double x, y, z, rz, ry, rx;
    values >> x >> y >> z >> rz >> ry >> rx;
    EXPECT_NEAR(ry - previous_y, 3.0, 1e-6) << "frame " << frame_idx;
    EXPECT_NEAR(rz, 0, 1e-6);
    EXPECT_NEAR(rx, 0, 1e-6);
    previous_y = ry;
  }
  EXPECT_NEAR(previous_y, 717, 1e-6);
}

TEST(BvhWriter, WriteBvhWritesTheFileAtomically) {
  testing::TempDir dir;
  const Take take = SyntheticTake();
  const std::string path = dir.File("out.bvh");
  ASSERT_TRUE(WriteBvh(take, path).ok());
  std::ifstream in(path, std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, FormatBvh(take));
  // No temporary file is left beside it.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1);
  // A take read back through the importer.
  TakeSource source;
  source.path = path;
  ImportOptions options;
  options.first_frame = FirstFramePolicy::kKeep;
  Result<Take> imported = ImportTake(source, options);
  ASSERT_TRUE(imported.ok()) << imported.status().ToString();
  ExpectSameMotion(*imported, take, 1e-6);
}

TEST(BvhWriter, WriteBvhRejectsBadTakesAndBadPaths) {
  testing::TempDir dir;
  Take take = SyntheticTake();
  EXPECT_FALSE(WriteBvh(take, dir.File("missing/dir/out.bvh")).ok());
  take.rotations.pop_back();
  Status status = WriteBvh(take, dir.File("out.bvh"));
  EXPECT_TRUE(status.IsInvalidArgument()) << status.ToString();
  Take empty;
  EXPECT_TRUE(WriteBvh(empty, dir.File("empty.bvh")).IsInvalidArgument());
}

TEST(BvhWriter, RealTakesRoundTrip) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  struct Source {
    const char* path;
    const char* asf;
  };
  for (const Source& file : {Source{"bvh/05_01.bvh", ""}, Source{"bvh_daz/13_11.bvh", ""},
                             Source{"asfamc/07/07_05-walk.amc", "asfamc/07/07-walk.asf"}}) {
    SCOPED_TRACE(file.path);
    TakeSource source;
    source.path = dir + "/" + file.path;
    if (*file.asf) {
      source.format = TakeFormat::kAmc;
      source.asf_path = dir + "/" + file.asf;
    }
    Result<Take> take = ImportTake(source, {});
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    Result<Take> parsed = ParseBvh(FormatBvh(*take), "roundtrip.bvh");
    ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
    CanonicalizeSkeleton(&*parsed);
    EXPECT_EQ(parsed->skeleton.family(), take->skeleton.family());
    ExpectSameMotion(*parsed, *take, 1e-6);
    EXPECT_DOUBLE_EQ(parsed->fps, take->fps);
  }
}

}  // namespace
}  // namespace motif
