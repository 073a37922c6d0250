// The importers on the real CMU takes (../shared/data/mocap, see its README.md): every BVH and
// AMC file imports, with the frame count INDEX.tsv gives (less the converter's T-pose for BVH),
// into the skeleton family it should, and the T-pose detection drops frame 0 of every cgspeed
// BVH file and of no AMC file. Skips when the data is absent.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "formats/import/first_frame.h"
#include "formats/import/take_importer.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

struct IndexRow {
  std::string format;
  int64_t frames = 0;
  double fps = 0;
};

// INDEX.tsv: file format subject trial frames fps description.
std::map<std::string, IndexRow> ReadIndex(const std::string& dir) {
  std::map<std::string, IndexRow> rows;
  std::ifstream in(dir + "/INDEX.tsv");
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    std::string field;
    while (std::getline(stream, field, '\t')) fields.push_back(field);
    if (fields.size() < 6) continue;
    IndexRow row;
    row.format = fields[1];
    row.frames = fields[4].empty() ? 0 : std::stoll(fields[4]);
    row.fps = fields[5].empty() ? 0 : std::stod(fields[5]);
    rows[fields[0]] = row;
  }
  return rows;
}

std::string Relative(const std::string& path, const std::string& dir) {
  return std::filesystem::path(path).lexically_relative(dir).generic_string();
}

TEST(RealData, EveryTakeImportsWithItsIndexedFrameCountAndFamily) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  const std::map<std::string, IndexRow> index = ReadIndex(dir);
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  std::map<std::string, int> counts;
  uintmax_t total_bytes = 0;
  int64_t total_frames = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const TakeSource& source : *sources) {
    const std::string relative = Relative(source.path, dir);
    SCOPED_TRACE(relative);
    auto row = index.find(relative);
    ASSERT_NE(row, index.end());
    Result<Take> take = ImportTake(source, {});
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    total_bytes += std::filesystem::file_size(source.path);
    total_frames += static_cast<int64_t>(take->frame_count());
    const std::string& format = row->second.format;
    ++counts[format];
    const bool is_bvh = format == "bvh" || format == "bvh-daz";
    EXPECT_EQ(static_cast<int64_t>(take->frame_count()), row->second.frames - (is_bvh ? 1 : 0));
    EXPECT_DOUBLE_EQ(take->fps, row->second.fps);
    EXPECT_EQ(take->skeleton.family(), format == "bvh-daz" ? "custom" : "cmu31");
    EXPECT_EQ(take->joint_count(), format == "bvh-daz" ? 43u : 31u);
    EXPECT_NE(take->content_hash, 0u);
    if (format == "amc") {
      EXPECT_NEAR(take->meters_per_unit, 0.0254 / 0.45, 1e-12);
      EXPECT_NE(source.asf_path, "");
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(counts["bvh"], 62);
  EXPECT_EQ(counts["bvh-daz"], 10);
  EXPECT_EQ(counts["amc"], 34);
  EXPECT_EQ(total_frames, 40346 + (5936 - 10) + 61495);
  const double mb_per_second = static_cast<double>(total_bytes) / 1e6 / seconds;
  std::printf("imported %zu takes, %.1f MB, %lld frames in %.3f s: %.0f MB/s\n", sources->size(),
              static_cast<double>(total_bytes) / 1e6, static_cast<long long>(total_frames), seconds,
              mb_per_second);
  ::testing::Test::RecordProperty("import_mb_per_second", static_cast<int>(mb_per_second));
}

TEST(RealData, FirstFrameIsDiscontinuousInEveryBvhAndInNoAmc) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  ImportOptions keep;
  keep.first_frame = FirstFramePolicy::kKeep;
  double min_bvh_ratio = 1e9;
  double max_amc_ratio = 0;
  for (const TakeSource& source : *sources) {
    SCOPED_TRACE(source.path);
    Result<Take> take = ImportTake(source, keep);
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    const FirstFrameCheck check = CheckFirstFrame(*take);
    const double ratio = check.first_jump / check.median_step;
    if (source.format == TakeFormat::kBvh) {
      EXPECT_TRUE(check.discontinuous);
      EXPECT_GT(check.first_jump, 2.0);
      min_bvh_ratio = std::min(min_bvh_ratio, ratio);
    } else {
      EXPECT_FALSE(check.discontinuous);
      EXPECT_EQ(check.body_start, 1u);
      max_amc_ratio = std::max(max_amc_ratio, ratio);
    }
  }
  // Measured: 18.1 (bvh/03_02) and 2.5 (asfamc/60/60_06); the threshold is 10.
  std::printf("first jump / median step: BVH min %.1f, AMC max %.1f\n", min_bvh_ratio,
              max_amc_ratio);
  EXPECT_GT(min_bvh_ratio, 15);
  EXPECT_LT(max_amc_ratio, 5);
}

TEST(RealData, TheDroppedFrameIsTheConverterPose) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = testing::MocapDir();
  for (const char* name :
       {"bvh/05_01.bvh", "bvh/07_12.bvh", "bvh/09_10.bvh", "bvh_daz/02_01.bvh"}) {
    SCOPED_TRACE(name);
    TakeSource source;
    source.path = dir + "/" + name;
    ImportOptions keep;
    keep.first_frame = FirstFramePolicy::kKeep;
    Result<Take> kept = ImportTake(source, keep);
    Result<Take> automatic = ImportTake(source, {});
    ASSERT_TRUE(kept.ok() && automatic.ok());
    ASSERT_EQ(automatic->frame_count() + 1, kept->frame_count());
    for (size_t frame_idx = 0; frame_idx < automatic->frame_count(); frame_idx += 37) {
      EXPECT_EQ(automatic->root_positions[frame_idx], kept->root_positions[frame_idx + 1]);
      for (size_t joint_idx = 0; joint_idx < kept->joint_count(); ++joint_idx) {
        ASSERT_EQ(automatic->rotation(frame_idx, joint_idx).coeffs(),
                  kept->rotation(frame_idx + 1, joint_idx).coeffs());
      }
    }
  }
  // The cgspeed T-pose is not an all-zero frame: bvh/05_01 frame 0 bends the hips and arms.
  TakeSource source;
  source.path = dir + "/bvh/05_01.bvh";
  ImportOptions keep;
  keep.first_frame = FirstFramePolicy::kKeep;
  Result<Take> take = ImportTake(source, keep);
  ASSERT_TRUE(take.ok());
  int bent_joints = 0;
  for (size_t joint_idx = 0; joint_idx < take->joint_count(); ++joint_idx) {
    bent_joints +=
        QuaternionDistance(take->rotation(0, joint_idx), Eigen::Quaterniond::Identity()) > 0.05;
  }
  EXPECT_GE(bent_joints, 5);
}

// The studio rig (../shared/data/bandai2) animates Hips under a static joint_Root: the import
// makes Hips the root, so a walk travels and a turn turns in the root's columns.
Take ImportStudioTake(const std::string& name) {
  Result<std::vector<TakeSource>> sources =
      DiscoverTakes({testing::StudioRigDir() + "/bvh/" + name + ".bvh"}, {});
  EXPECT_TRUE(sources.ok()) << sources.status().ToString();
  if (!sources.ok() || sources->empty()) return Take();
  Result<Take> take = ImportTake(sources->front(), {});
  EXPECT_TRUE(take.ok()) << take.status().ToString();
  return take.ok() ? std::move(take).value() : Take();
}

TEST(RealData, AStudioRigsRootIsItsAnimatedHipsSoAWalkTravelsAndATurnTurns) {
  MOTIF_REQUIRE_STUDIO_RIG_DATA();
  const Take walk = ImportStudioTake("dataset-2_walk_normal_001");
  ASSERT_GT(walk.frame_count(), 10u);
  EXPECT_EQ(walk.skeleton.joint(0).name, "Hips");
  EXPECT_EQ(walk.skeleton.FindJoint("joint_Root"), -1);
  Eigen::Vector3d travel = walk.root_positions.back() - walk.root_positions.front();
  travel.y() = 0;
  EXPECT_GT(travel.norm(), 100.0);  // cm: a walk of over a metre
  const Take turn = ImportStudioTake("dataset-2_walk-turn-left_normal_001");
  ASSERT_GT(turn.frame_count(), 10u);
  const double turned = std::remainder(
      HeadingOf(turn.rotation(turn.frame_count() - 1, 0)) - HeadingOf(turn.rotation(0, 0)),
      2 * kPi);
  EXPECT_GT(turned, kPi / 4) << "the heading turned by " << turned << " rad";
}

}  // namespace
}  // namespace motif
