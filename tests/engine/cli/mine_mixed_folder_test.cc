// `motifmine mine` on a folder that mixes skeleton families (CMU ASF/AMC, cgspeed BVH, Daz BVH,
// the studio rig): one run, exit 0, one archive on the CMU body and one report, the notes naming
// each mapped skeleton once.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/cluster/motifs_json.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

void CopyInto(const std::string& file, const std::string& folder) {
  fs::create_directories(folder);
  fs::copy_file(file, folder + "/" + fs::path(file).filename().string());
}

TEST(MineMixedFolder, FourFamiliesMineInOneRunWithOneReport) {
  MOTIF_REQUIRE_MOCAP_DATA();
  MOTIF_REQUIRE_STUDIO_RIG_DATA();
  const std::string mocap = testing::MocapDir();
  const std::string rig = testing::StudioRigDir() + "/bvh/";
  testing::TempDir dir;
  const std::string takes = dir.File("takes");
  CopyInto(mocap + "/asfamc/07/07-walk.asf", takes + "/asfamc");
  CopyInto(mocap + "/asfamc/07/07_05-walk.amc", takes + "/asfamc");
  CopyInto(mocap + "/bvh/02_01.bvh", takes + "/bvh");
  CopyInto(mocap + "/bvh/08_01.bvh", takes + "/bvh");
  CopyInto(mocap + "/bvh_daz/02_01.bvh", takes + "/daz");
  CopyInto(mocap + "/bvh_daz/12_01.bvh", takes + "/daz");
  CopyInto(rig + "dataset-2_walk_normal_001.bvh", takes + "/studio");
  CopyInto(rig + "dataset-2_walk_normal_002.bvh", takes + "/studio");
  const std::string out = dir.File("out");
  testing::RunResult run = testing::RunTool("mine " + takes + " --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("a 43-joint skeleton (root 'hip'), mapped onto the CMU body"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("a 21-joint skeleton (root 'Hips'), mapped onto the CMU body"),
            std::string::npos)
      << run.output;
  auto archive = FrameFileReader::Open(out + "/archive.mfs");
  ASSERT_TRUE(archive.ok()) << archive.status().ToString();
  EXPECT_EQ((*archive)->skeleton().family(), "cmu31");
  EXPECT_EQ((*archive)->clips().size(), 7u);  // the Daz 02_01 is stored as "02_01~2"
  EXPECT_TRUE(fs::exists(out + "/report.html"));
  Result<MotifsDocument> motifs = ReadMotifsJson(out + "/motifs.json");
  ASSERT_TRUE(motifs.ok()) << motifs.status().ToString();
  EXPECT_FALSE(motifs->motifs.empty());
}

}  // namespace
}  // namespace motif
