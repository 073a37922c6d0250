#include "engine/synth/truth_json_reader.h"

#include <gtest/gtest.h>

#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TEST(TruthJsonReaderTest, ReadsWhatWriteTruthJsonWrote) {
  testing::TempDir dir;
  SynthOptions options;
  options.seed = 42;
  options.motifs = 2;
  const std::vector<PlantedInstance> planted = {{"synth_0000", 10, 130, 0, 1.1, false},
                                                {"synth_0003", 500, 580, 1, 0.8, true}};
  ASSERT_TRUE(WriteTruthJson(dir.File("s.truth.json"), "s.mfs", 9000, options, planted).ok());
  auto truth = ReadTruthJson(dir.File("s.truth.json"));
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  EXPECT_EQ(truth->archive, "s.mfs");
  EXPECT_EQ(truth->frames, 9000u);
  EXPECT_EQ(truth->seed, 42u);
  EXPECT_EQ(truth->motifs, 2u);
  ASSERT_EQ(truth->instances.size(), 2u);
  EXPECT_EQ(truth->instances[1].clip, "synth_0003");
  EXPECT_EQ(truth->instances[1].start, 500u);
  EXPECT_EQ(truth->instances[1].end, 580u);
  EXPECT_EQ(truth->instances[1].motif, 1u);
  EXPECT_DOUBLE_EQ(truth->instances[1].warp, 0.8);
  EXPECT_TRUE(truth->instances[1].nonuniform);
}

TEST(TruthJsonReaderTest, RejectsMalformedFiles) {
  EXPECT_TRUE(ReadTruthJson("/nonexistent/x.truth.json").status().IsNotFound());
  EXPECT_TRUE(ParseTruthJson("[]", "t").status().IsInvalidArgument());
  EXPECT_EQ(ParseTruthJson(R"({"version": 2})", "t").status().code(), Status::Code::kNotSupported);
  const Status missing =
      ParseTruthJson(
          R"({"version": 1, "archive": "a", "frames": 10, "instances": [{"clip": "c", "start": 1}]})",
          "t")
          .status();
  EXPECT_TRUE(missing.IsInvalidArgument());
  EXPECT_NE(missing.message().find("instances[0]: missing \"end\""), std::string::npos);
  EXPECT_TRUE(ParseTruthJson(R"({"version": 1, "archive": "a", "frames": 10, "instances":
      [{"clip": "c", "start": 5, "end": 5, "motif": 0}]})",
                             "t")
                  .status()
                  .IsInvalidArgument());
}

}  // namespace
}  // namespace motif
