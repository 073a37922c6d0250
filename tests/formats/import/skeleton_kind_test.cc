// ReadSkeletonKind: a take's skeleton read without its motion, as the archive import reads it to
// learn whether a folder mixes skeleton families.
#include "formats/import/skeleton_kind.h"

#include <fstream>

#include <gtest/gtest.h>

#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TakeSource Bvh(const std::string& path) {
  TakeSource source;
  source.path = path;
  return source;
}

void Write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(ReadSkeletonKind, NamesTheJointsOfACustomRigAndReadsNoMotion) {
  testing::TempDir dir;
  const std::string path = dir.File("rig.bvh");
  // The motion is not read: a broken MOTION section does not matter.
  Write(path,
        "HIERARCHY\nROOT pelvis\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition "
        "Zrotation Xrotation Yrotation\n JOINT spine\n {\n  OFFSET 0 1 0\n  CHANNELS 3 Zrotation "
        "Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 1 0\n  }\n }\n}\nMOTION\nFrames: x\n");
  Result<std::string> kind = ReadSkeletonKind(Bvh(path), ImportOptions());
  ASSERT_TRUE(kind.ok()) << kind.status().ToString();
  EXPECT_EQ(*kind, "custom:pelvis<-1;spine<0;");
}

TEST(ReadSkeletonKind, RefusesAMissingFileAndABrokenHierarchyNamingTheFile) {
  testing::TempDir dir;
  Result<std::string> kind = ReadSkeletonKind(Bvh(dir.File("none.bvh")), ImportOptions());
  ASSERT_FALSE(kind.ok());
  EXPECT_NE(kind.status().message().find("none.bvh"), std::string::npos);
  Write(dir.File("broken.bvh"), "HIERARCHY\nROOT pelvis\n{\n OFFSET 0 0\n");
  kind = ReadSkeletonKind(Bvh(dir.File("broken.bvh")), ImportOptions());
  ASSERT_FALSE(kind.ok());
  EXPECT_NE(kind.status().message().find("broken.bvh:"), std::string::npos)
      << kind.status().message();
}

TEST(ReadSkeletonKind, TellsTheRealFamiliesApart) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string mocap = testing::MocapDir();
  EXPECT_EQ(ReadSkeletonKind(Bvh(mocap + "/bvh/02_01.bvh"), ImportOptions()).value(), "cmu31");
  TakeSource amc;
  amc.format = TakeFormat::kAmc;
  amc.path = mocap + "/asfamc/60/60_01.amc";
  amc.asf_path = mocap + "/asfamc/60/60.asf";
  EXPECT_EQ(ReadSkeletonKind(amc, ImportOptions()).value(), "cmu31");
  const std::string daz =
      ReadSkeletonKind(Bvh(mocap + "/bvh_daz/02_01.bvh"), ImportOptions()).value();
  EXPECT_EQ(daz.rfind("custom:hip<-1;abdomen<0;", 0), 0u) << daz;
  EXPECT_EQ(ReadSkeletonKind(Bvh(mocap + "/bvh_daz/13_11.bvh"), ImportOptions()).value(), daz);
}

}  // namespace
}  // namespace motif
