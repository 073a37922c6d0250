#include "formats/import/take_importer.h"

#include <gtest/gtest.h>
#include <xxhash.h>

#include <filesystem>

#include "tests/formats/import/import_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using import_test::FixturePath;
using import_test::ReadText;
using import_test::Rot;
using import_test::SameRotation;
using import_test::WriteText;
using testing::TempDir;

void Touch(const std::string& path, const std::string& text = "x") {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteText(path, text);
}

std::vector<std::string> Paths(const std::vector<TakeSource>& sources) {
  std::vector<std::string> paths;
  for (const TakeSource& source : sources) paths.push_back(source.path);
  return paths;
}

TEST(DiscoverTakes, ExpandsFoldersRecursivelyInPathOrder) {
  TempDir dir;
  Touch(dir.File("b.bvh"));
  Touch(dir.File("sub/a.BVH"));
  Touch(dir.File("sub/c_01.amc"));
  Touch(dir.File("sub/c.asf"));
  Touch(dir.File("notes.txt"));
  Touch(dir.File("a.bvh"));
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.path()}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  EXPECT_EQ(Paths(*sources),
            (std::vector<std::string>{dir.File("a.bvh"), dir.File("b.bvh"), dir.File("sub/a.BVH"),
                                      dir.File("sub/c_01.amc")}));
  EXPECT_EQ((*sources)[0].format, TakeFormat::kBvh);
  EXPECT_EQ((*sources)[3].format, TakeFormat::kAmc);
  EXPECT_EQ((*sources)[3].asf_path, dir.File("sub/c.asf"));
}

TEST(DiscoverTakes, KeepsArgumentOrderAndSkipsDuplicates) {
  TempDir dir;
  Touch(dir.File("z.bvh"));
  Touch(dir.File("y/a.bvh"));
  Result<std::vector<TakeSource>> sources =
      DiscoverTakes({dir.File("z.bvh"), dir.File("y"), dir.File("y/a.bvh")}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  EXPECT_EQ(Paths(*sources), (std::vector<std::string>{dir.File("z.bvh"), dir.File("y/a.bvh")}));
}

// Linked folders are searched (a user's folder of links to capture sessions); a link back up
// the tree or a second link to one folder is not followed again.
TEST(DiscoverTakes, FollowsLinkedFoldersOnce) {
  TempDir dir;
  Touch(dir.File("sessions/monday/a.bvh"));
  Touch(dir.File("mine/b.bvh"));
  std::filesystem::create_directory_symlink(dir.File("sessions/monday"), dir.File("mine/monday"));
  std::filesystem::create_directory_symlink(dir.File("sessions/monday"), dir.File("mine/again"));
  std::filesystem::create_directory_symlink(dir.File("mine"), dir.File("mine/monday_loop"));
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.File("mine")}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  const std::vector<std::string> paths = Paths(*sources);
  ASSERT_EQ(paths.size(), 2u) << ::testing::PrintToString(paths);
  EXPECT_EQ(paths[1], dir.File("mine/b.bvh"));
  EXPECT_EQ(std::filesystem::path(paths[0]).filename(), "a.bvh");
}

TEST(DiscoverTakes, RejectsMissingPathsAndOtherFiles) {
  TempDir dir;
  Result<std::vector<TakeSource>> missing = DiscoverTakes({dir.File("nope.bvh")}, {});
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(missing.status().IsNotFound());
  EXPECT_NE(missing.status().message().find("nope.bvh"), std::string::npos);
  Touch(dir.File("skeleton.asf"));
  Result<std::vector<TakeSource>> asf = DiscoverTakes({dir.File("skeleton.asf")}, {});
  ASSERT_FALSE(asf.ok());
  EXPECT_TRUE(asf.status().IsInvalidArgument());
  EXPECT_NE(asf.status().message().find("not a .bvh or .amc file"), std::string::npos);
}

TEST(DiscoverTakes, PairsAnAmcWithTheOnlyAsfOfItsFolder) {
  TempDir dir;
  Touch(dir.File("walk_05.amc"));
  Touch(dir.File("Subject.ASF"));
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.File("walk_05.amc")}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  EXPECT_EQ((*sources)[0].asf_path, dir.File("Subject.ASF"));
}

TEST(DiscoverTakes, PairsBySubjectPrefixAndDashSuffix) {
  TempDir dir;
  for (const char* name :
       {"13.asf", "14.asf", "07.asf", "07-walk.asf", "07-run.asf", "09-run.asf"}) {
    Touch(dir.File(name));
  }
  for (const char* name : {"13_17.amc", "14_02.amc", "07_05-walk.amc", "07_12-run.amc", "07_01.amc",
                           "09_06-run.amc"}) {
    Touch(dir.File(name));
  }
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.path()}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  std::map<std::string, std::string> paired;
  for (const TakeSource& source : *sources) {
    paired[std::filesystem::path(source.path).filename().string()] =
        std::filesystem::path(source.asf_path).filename().string();
  }
  EXPECT_EQ(paired["13_17.amc"], "13.asf");
  EXPECT_EQ(paired["14_02.amc"], "14.asf");
  EXPECT_EQ(paired["07_05-walk.amc"], "07-walk.asf");
  EXPECT_EQ(paired["07_12-run.amc"], "07-run.asf");
  EXPECT_EQ(paired["07_01.amc"], "07.asf");
  EXPECT_EQ(paired["09_06-run.amc"], "09-run.asf");
}

TEST(DiscoverTakes, FallsBackToTheOnlyAsfOfTheSameSubject) {
  TempDir dir;
  Touch(dir.File("07-walk.asf"));
  Touch(dir.File("09-run.asf"));
  Touch(dir.File("07_06-jump.amc"));
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.File("07_06-jump.amc")}, {});
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  EXPECT_EQ((*sources)[0].asf_path, dir.File("07-walk.asf"));
}

// An AMC take with no ASF to pair is listed with the reason, and fails alone when imported (so
// --skip-bad passes over it and keeps the others).
TEST(DiscoverTakes, ExplainsWhenNoAsfMatches) {
  TempDir dir;
  Touch(dir.File("lonely_01.amc"));
  Result<std::vector<TakeSource>> none = DiscoverTakes({dir.File("lonely_01.amc")}, {});
  ASSERT_TRUE(none.ok()) << none.status().ToString();
  ASSERT_EQ(none->size(), 1u);
  EXPECT_EQ((*none)[0].asf_path, "");
  EXPECT_NE((*none)[0].unpaired_reason.find("no .asf skeleton in its folder"), std::string::npos);
  // The option that helps, as the library names it ("(asf)"; the tool prints "(--asf)").
  EXPECT_NE((*none)[0].unpaired_reason.find("(asf)"), std::string::npos);
  Result<Take> imported = ImportTake((*none)[0], {});
  EXPECT_TRUE(imported.status().IsInvalidArgument());
  EXPECT_EQ(imported.status().message(), (*none)[0].unpaired_reason);
  Touch(dir.File("13.asf"));
  Touch(dir.File("14.asf"));
  Result<std::vector<TakeSource>> ambiguous = DiscoverTakes({dir.File("lonely_01.amc")}, {});
  ASSERT_TRUE(ambiguous.ok());
  EXPECT_NE((*ambiguous)[0].unpaired_reason.find("13.asf, 14.asf"), std::string::npos)
      << (*ambiguous)[0].unpaired_reason;
  EXPECT_NE((*ambiguous)[0].unpaired_reason.find("none named lonely.asf"), std::string::npos);
}

TEST(DiscoverTakes, AsfPathOverridesPairing) {
  TempDir dir;
  Touch(dir.File("13_17.amc"));
  Touch(dir.File("13.asf"));
  Touch(dir.File("other/skeleton.asf"));
  ImportOptions options;
  options.asf_path = dir.File("other/skeleton.asf");
  Result<std::vector<TakeSource>> sources = DiscoverTakes({dir.path()}, options);
  ASSERT_TRUE(sources.ok()) << sources.status().ToString();
  ASSERT_EQ(sources->size(), 1u);
  EXPECT_EQ((*sources)[0].asf_path, options.asf_path);
  options.asf_path = dir.File("missing.asf");
  Result<std::vector<TakeSource>> missing = DiscoverTakes({dir.path()}, options);
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(missing.status().IsNotFound());
}

TEST(ImportTake, BvhTakeCarriesNameHashRateAndWeights) {
  TempDir dir;  // the take's name is its file stem: give the fixture its real name
  TakeSource source;
  source.path = dir.File("custom_zxy.bvh");
  std::filesystem::copy_file(FixturePath("custom_zxy.bvh"), source.path);
  Result<Take> take = ImportTake(source, {});
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  EXPECT_EQ(take->name, "custom_zxy");
  EXPECT_EQ(take->source_path, source.path);
  const std::string bytes = ReadText(source.path);
  EXPECT_EQ(take->content_hash, XXH3_64bits(bytes.data(), bytes.size()));
  EXPECT_DOUBLE_EQ(take->fps, 30.0);
  EXPECT_DOUBLE_EQ(take->source_fps, 30.0);
  EXPECT_EQ(take->meters_per_unit, 0);
  EXPECT_EQ(take->skeleton.family(), "custom");
  EXPECT_EQ(take->skeleton.joint(0).weight, 1.0f);  // the root
  EXPECT_EQ(take->skeleton.joint(1).weight, 1.0f);  // "spine"
  EXPECT_EQ(take->frame_count(), 3u);               // frame 0 continues into frame 1: kept
}

// Names that reach JSON outputs must be UTF-8: a file name or a joint name that is not is
// refused, naming the file.
TEST(ImportTake, NamesThatAreNotUtf8AreRefused) {
  TempDir dir;
  TakeSource source;
  source.path = dir.File("take\xff.bvh");
  std::filesystem::copy_file(FixturePath("custom_zxy.bvh"), source.path);
  Result<Take> take = ImportTake(source, {});
  EXPECT_TRUE(take.status().IsInvalidArgument());
  EXPECT_NE(take.status().message().find("path is not valid UTF-8"), std::string::npos);

  source.path = dir.File("joint.bvh");
  std::string text = ReadText(FixturePath("custom_zxy.bvh"));
  const size_t name = text.find("spine");
  ASSERT_NE(name, std::string::npos);
  text.replace(name, 5, "sp\xc3ne");  // a lead byte without its continuation
  Touch(source.path, text);
  take = ImportTake(source, {});
  EXPECT_TRUE(take.status().IsInvalidArgument()) << take.status().ToString();
  EXPECT_EQ(take.status().message(), source.path + ": a joint name is not valid UTF-8");
}

TEST(ImportTake, AmcTakeUsesTheAmcRateAndHashesTheAmcBytes) {
  TempDir dir;  // the take's name is its file stem: give the fixture its real name
  TakeSource source;
  source.format = TakeFormat::kAmc;
  source.path = dir.File("tiny_01.amc");
  std::filesystem::copy_file(FixturePath("tiny_01.amc"), source.path);
  source.asf_path = FixturePath("tiny.asf");
  ImportOptions options;
  options.amc_fps = 60;
  Result<Take> take = ImportTake(source, options);
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  EXPECT_EQ(take->name, "tiny_01");
  const std::string bytes = ReadText(source.path);
  EXPECT_EQ(take->content_hash, XXH3_64bits(bytes.data(), bytes.size()));
  EXPECT_DOUBLE_EQ(take->fps, 60);
  EXPECT_DOUBLE_EQ(take->meters_per_unit, 0.0254 / 0.5);
  EXPECT_EQ(take->frame_count(), 2u);
  EXPECT_EQ(take->skeleton.joint(0).name, "root");
}

TEST(ImportTake, AmcWithoutSkeletonIsAnError) {
  TakeSource source;
  source.format = TakeFormat::kAmc;
  source.path = FixturePath("tiny_01.amc");
  Result<Take> take = ImportTake(source, {});
  ASSERT_FALSE(take.ok());
  EXPECT_TRUE(take.status().IsInvalidArgument());
  ImportOptions options;
  options.asf_path = FixturePath("tiny.asf");
  EXPECT_TRUE(ImportTake(source, options).ok());
}

TEST(ImportTake, MissingFileIsNotFound) {
  TakeSource source;
  source.path = "/nonexistent/x.bvh";
  Result<Take> take = ImportTake(source, {});
  ASSERT_FALSE(take.ok());
  EXPECT_TRUE(take.status().IsNotFound());
}

// A one-joint BVH: frame 0 a pose far from the rest, then a slow smooth swing.
std::string TPoseBvh() {
  std::string text =
      "HIERARCHY\nROOT hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Yrotation Xrotation\nJOINT chest\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation "
      "Yrotation Xrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\n}\nMOTION\nFrames: 60\n"
      "Frame Time: 0.0083333\n0 0 0 0 0 0 0 0 0\n";
  for (int frame_idx = 1; frame_idx < 60; ++frame_idx) {
    const double angle = 40 + 0.5 * frame_idx;
    text += "0 1 0 " + std::to_string(angle) + " 10 20 " + std::to_string(-angle) + " 30 5\n";
  }
  return text;
}

TEST(ImportTake, FirstFramePolicy) {
  TempDir dir;
  WriteText(dir.File("t.bvh"), TPoseBvh());
  TakeSource source;
  source.path = dir.File("t.bvh");
  ImportOptions options;
  Result<Take> automatic = ImportTake(source, options);
  ASSERT_TRUE(automatic.ok()) << automatic.status().ToString();
  EXPECT_EQ(automatic->frame_count(), 59u);
  EXPECT_TRUE(
      SameRotation(automatic->rotation(0, 0), Rot('z', 40.5) * Rot('y', 10) * Rot('x', 20)));
  options.first_frame = FirstFramePolicy::kKeep;
  Result<Take> kept = ImportTake(source, options);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(kept->frame_count(), 60u);
  options.first_frame = FirstFramePolicy::kDrop;
  TakeSource fixture;
  fixture.path = FixturePath("custom_zxy.bvh");
  Result<Take> dropped = ImportTake(fixture, options);
  ASSERT_TRUE(dropped.ok());
  EXPECT_EQ(dropped->frame_count(), 2u);
  EXPECT_EQ(dropped->root_positions[0], Eigen::Vector3d(10.5, 20.25, -30));
}

}  // namespace
}  // namespace motif
