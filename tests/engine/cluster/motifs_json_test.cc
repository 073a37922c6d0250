#include "engine/cluster/motifs_json.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

std::vector<ClipInfo> TwoClips() {
  std::vector<ClipInfo> clips(2);
  clips[0].name = "05_01";
  clips[0].source_path = "/data/05_01.bvh";
  clips[0].first_frame = 0;
  clips[0].frame_count = 1000;
  clips[0].fps = 120;
  clips[1].name = "07_02";
  clips[1].source_path = "/data/07_02.amc";
  clips[1].first_frame = 1000;
  clips[1].frame_count = 500;
  clips[1].fps = 120;
  return clips;
}

// Motif 0: [100, 220) of 05_01 and [50, 170) of 07_02; motif 1: two pieces of 05_01.
ClusterResult SmallResult() {
  ClusterResult result;
  result.instances = {{100, 220}, {400, 460}, {700, 760}, {1050, 1170}};
  result.motifs.push_back({{0, 3}, 240});
  result.motifs.push_back({{1, 2}, 120});
  result.report.covered_frames = 360;
  return result;
}

MotifsJsonParams Params() { return {1.05, 256, 4, 60, 0, 7, "warped", 15.0, 0.2}; }

TEST(MotifsJsonTest, DocumentMapsGlobalFramesToClips) {
  auto document = MakeMotifsDocument(SmallResult(), "a.mfs", 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok()) << document.status().ToString();
  ASSERT_EQ(document->motifs.size(), 2u);
  EXPECT_EQ(document->motifs[0].id, 0u);
  EXPECT_EQ(document->motifs[0].instances[0], (MotifsJsonInstance{"05_01", 100, 220, 100}));
  EXPECT_EQ(document->motifs[0].instances[1], (MotifsJsonInstance{"07_02", 50, 170, 1050}));
  EXPECT_EQ(document->motifs[1].id, 1u);
  ASSERT_EQ(document->clips.size(), 2u);
  EXPECT_EQ(document->clips[1],
            (MotifsJsonClip{"07_02", "/data/07_02.amc", 500, 120, 1000, 0, 120}));

  ClusterResult crossing = SmallResult();
  crossing.instances[3] = {950, 1070};  // spans the two clips
  EXPECT_TRUE(MakeMotifsDocument(crossing, "a.mfs", 1500, TwoClips(), Params())
                  .status()
                  .IsInvalidArgument());
}

TEST(MotifsJsonTest, ExactFieldNamesOfTheContract) {
  auto document = MakeMotifsDocument(SmallResult(), "a.mfs", 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok());
  const nlohmann::json json = nlohmann::json::parse(MotifsJsonText(*document));
  EXPECT_EQ(json["version"], 2);
  EXPECT_EQ(json["archive"], "a.mfs");
  EXPECT_EQ(json["frames"], 1500);
  const nlohmann::json& clip = json["clips"][1];
  EXPECT_EQ(clip["name"], "07_02");
  EXPECT_EQ(clip["source"], "/data/07_02.amc");
  EXPECT_EQ(clip["frames"], 500);
  EXPECT_EQ(clip["fps"], 120.0);
  EXPECT_EQ(clip["first_frame"], 1000);
  const nlohmann::json& params = json["params"];
  EXPECT_DOUBLE_EQ(params["eps"].get<double>(), 1.05);
  EXPECT_EQ(params["kmax"], 256);
  EXPECT_EQ(params["branch"], 4);
  EXPECT_EQ(params["min_length"], 60);
  EXPECT_EQ(params["groups"], "auto");
  EXPECT_EQ(params["seed"], 7);
  EXPECT_EQ(params["similarity"], "warped");
  EXPECT_EQ(params["pause_speed"], 15.0);
  EXPECT_EQ(params["pause_seconds"], 0.2);
  const nlohmann::json& motif = json["motifs"][0];
  EXPECT_EQ(motif["id"], 0);
  EXPECT_EQ(motif["instance_count"], 2);
  EXPECT_DOUBLE_EQ(motif["mean_length"].get<double>(), 120.0);
  EXPECT_DOUBLE_EQ(motif["mean_seconds"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(motif["score"].get<double>(), 120.0);  // (instances - 1) x mean length
  const nlohmann::json& instance = motif["instances"][1];
  EXPECT_EQ(instance["clip"], "07_02");
  EXPECT_EQ(instance["start"], 50);
  EXPECT_EQ(instance["end"], 170);
  EXPECT_EQ(instance["frame"], 1050);
  EXPECT_EQ(instance["length"], 120);
  EXPECT_EQ(json["summary"]["covered_frames"], 360);

  MotifsDocument given = *document;
  given.params.groups = 12;
  EXPECT_EQ(nlohmann::json::parse(MotifsJsonText(given))["params"]["groups"], 12);
}

TEST(MotifsJsonTest, WritesAtomicallyAndReadsBack) {
  testing::TempDir dir;
  auto document = MakeMotifsDocument(SmallResult(), dir.File("a.mfs"), 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok());
  for (uint32_t groups : {0u, 5u}) {
    document->params.groups = groups;
    document->params.similarity = groups == 0 ? "warped" : "shared";
    ASSERT_TRUE(WriteMotifsJson(dir.File("motifs.json"), *document).ok());
    auto read = ReadMotifsJson(dir.File("motifs.json"));
    ASSERT_TRUE(read.ok()) << read.status().ToString();
    EXPECT_EQ(*read, *document);
    EXPECT_EQ(read->covered_frames, 360u);
  }
  // A file written before the clustering fields: read with their defaults.
  nlohmann::json older = nlohmann::json::parse(MotifsJsonText(*document));
  for (const char* field : {"similarity", "pause_speed", "pause_seconds"})
    older["params"].erase(field);
  ASSERT_TRUE(AtomicWriteFile(dir.File("older.json"), older.dump()).ok());
  auto older_read = ReadMotifsJson(dir.File("older.json"));
  ASSERT_TRUE(older_read.ok()) << older_read.status().ToString();
  EXPECT_EQ(older_read->params.similarity, "warped");
  EXPECT_EQ(older_read->params.pause_speed, 0.0);
  // An empty result is a valid file too.
  MotifsDocument empty;
  empty.archive = dir.File("e.mfs");
  ASSERT_TRUE(WriteMotifsJson(dir.File("empty.json"), empty).ok());
  auto read = ReadMotifsJson(dir.File("empty.json"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(*read, empty);
}

// Version 2 stores the archive relative to the file's folder, so the file can be read from any
// directory; a version 1 file's path (relative to where the run was) is read as it is.
TEST(MotifsJsonTest, TheArchivePathIsRelativeToTheFilesFolder) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.File("out/deeper"));
  auto document =
      MakeMotifsDocument(SmallResult(), dir.File("out/a.mfs"), 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok());
  const std::string cwd = std::filesystem::current_path().string();
  std::filesystem::current_path(dir.path());
  document->archive = "out/a.mfs";  // as a run in dir was given it
  Status written = WriteMotifsJson("out/deeper/motifs.json", *document);
  std::filesystem::current_path(cwd);
  ASSERT_TRUE(written.ok()) << written.ToString();
  const std::string text = ReadFileToString(dir.File("out/deeper/motifs.json")).value();
  EXPECT_EQ(nlohmann::json::parse(text)["archive"], "../a.mfs");
  auto read = ReadMotifsJson(dir.File("out/deeper/motifs.json"));  // from another directory
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->archive, dir.File("out/a.mfs"));

  nlohmann::json older = nlohmann::json::parse(text);
  older["version"] = 1;
  older["archive"] = "out/a.mfs";
  ASSERT_TRUE(AtomicWriteFile(dir.File("out/deeper/older.json"), older.dump()).ok());
  EXPECT_EQ(ReadMotifsJson(dir.File("out/deeper/older.json"))->archive, "out/a.mfs");
  older["version"] = 3;
  ASSERT_TRUE(AtomicWriteFile(dir.File("out/deeper/newer.json"), older.dump()).ok());
  EXPECT_TRUE(ReadMotifsJson(dir.File("out/deeper/newer.json")).status().IsNotSupported());
}

TEST(MotifsJsonTest, ReaderNamesWhatIsWrong) {
  auto document = MakeMotifsDocument(SmallResult(), "a.mfs", 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok());
  const nlohmann::json good = nlohmann::json::parse(MotifsJsonText(*document));
  auto parse = [](const nlohmann::json& json) { return ParseMotifsJson(json.dump(), "m.json"); };
  EXPECT_TRUE(parse(good).ok());
  EXPECT_TRUE(ParseMotifsJson("{not json", "m.json").status().IsInvalidArgument());

  nlohmann::json changed = good;
  changed["version"] = 3;
  EXPECT_EQ(parse(changed).status().code(), Status::Code::kNotSupported);
  changed = good;
  changed["motifs"][0]["instances"][0].erase("end");
  Status status = parse(changed).status();
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("motifs[0].instances[0]: missing \"end\""), std::string::npos)
      << status.message();
  changed = good;
  changed["motifs"][1]["instances"][0]["clip"] = "nope";
  EXPECT_TRUE(parse(changed).status().IsInvalidArgument());
  changed = good;
  changed["params"]["kmax"] = "many";
  EXPECT_TRUE(parse(changed).status().IsInvalidArgument());
  changed = good;
  changed["motifs"][0]["instances"][0]["end"] = 100;  // = start
  EXPECT_TRUE(parse(changed).status().IsInvalidArgument());
  // Unknown fields are ignored; the extra fields are optional.
  changed = good;
  changed["future"] = {1, 2};
  changed["motifs"][0]["instances"][0].erase("frame");
  auto lenient = parse(changed);
  ASSERT_TRUE(lenient.ok());
  EXPECT_EQ(lenient->motifs[0].instances[0].frame, 100u);  // from the clip table
}

// 05_01 starts at its file's frame 1 (a dropped T-pose); 07_02 at frame 2 of a 100 fps file
// resampled to 120 fps.
std::vector<ClipInfo> ShiftedAndResampledClips() {
  std::vector<ClipInfo> clips = TwoClips();
  clips[0].source_first_frame = 1;
  clips[1].source_first_frame = 2;
  clips[1].source_fps = 100;
  return clips;
}

TEST(MotifsJsonTest, FileFrameOfAClipFrame) {
  MotifsJsonClip clip{"c", "c.bvh", 500, 120, 0, 2, 100};
  EXPECT_EQ(FileFrameOf(clip, 0), 2u);
  EXPECT_EQ(FileFrameOf(clip, 3), 5u);   // 3 x 100 / 120 = 2.5: halves up
  EXPECT_EQ(FileFrameOf(clip, 8), 9u);   // 6.67
  EXPECT_EQ(FileFrameOf(clip, 9), 10u);  // 7.5
  clip.source_fps = 240;                 // two file frames a clip frame
  EXPECT_EQ(FileFrameOf(clip, 5), 12u);
  clip.source_fps = 0;  // not known (an older file): not resampled
  EXPECT_EQ(FileFrameOf(clip, 5), 7u);
  clip.source_fps = 120;
  EXPECT_EQ(FileFrameOf(clip, 5), 7u);
}

TEST(MotifsJsonTest, InstancesGiveTheirSourceFileFrames) {
  auto document =
      MakeMotifsDocument(SmallResult(), "a.mfs", 1500, ShiftedAndResampledClips(), Params());
  ASSERT_TRUE(document.ok()) << document.status().ToString();
  const nlohmann::json json = nlohmann::json::parse(MotifsJsonText(*document));
  EXPECT_EQ(json["clips"][0]["source_fps"], 120.0);
  EXPECT_EQ(json["clips"][1]["source_fps"], 100.0);
  EXPECT_EQ(json["clips"][1]["source_first_frame"], 2);
  // 05_01 [100, 220): file frames 101 to 220, the last inclusive.
  const nlohmann::json& shifted = json["motifs"][0]["instances"][0];
  EXPECT_EQ(shifted["start"], 100);
  EXPECT_EQ(shifted["file_first_frame"], 101);
  EXPECT_EQ(shifted["file_last_frame"], 220);
  // 07_02 [50, 170): 2 + round(50 x 100 / 120 = 41.7) = 44 to 2 + round(169 x 100 / 120 = 140.8).
  const nlohmann::json& resampled = json["motifs"][0]["instances"][1];
  EXPECT_EQ(resampled["start"], 50);
  EXPECT_EQ(resampled["end"], 170);
  EXPECT_EQ(resampled["file_first_frame"], 44);
  EXPECT_EQ(resampled["file_last_frame"], 143);
  // Without distances measured (no archive) a motif has no representative.
  EXPECT_FALSE(json["motifs"][0].contains("representative"));
  EXPECT_FALSE(shifted.contains("distance"));
}

// SmallResult with motif 0 measured: its second instance the medoid.
ClusterResult MeasuredResult() {
  ClusterResult result = SmallResult();
  result.motifs[0].representative = 1;
  result.motifs[0].distances = {0.8125, 0.0};
  return result;
}

TEST(MotifsJsonTest, RepresentativeAndDistancesRoundTrip) {
  testing::TempDir dir;
  auto document = MakeMotifsDocument(MeasuredResult(), dir.File("a.mfs"), 1500,
                                     ShiftedAndResampledClips(), Params());
  ASSERT_TRUE(document.ok()) << document.status().ToString();
  ASSERT_EQ(document->motifs[0].representative, std::optional<uint32_t>(1));
  EXPECT_EQ(document->motifs[0].instances[0].distance, std::optional<double>(0.8125));
  EXPECT_EQ(document->motifs[0].instances[1].distance, std::optional<double>(0.0));
  EXPECT_FALSE(document->motifs[1].representative.has_value());
  const std::string path = dir.File("motifs.json");
  ASSERT_TRUE(WriteMotifsJson(path, *document).ok());
  const nlohmann::json json = nlohmann::json::parse(ReadFileToString(path).value());
  EXPECT_EQ(json["version"], 2);  // added fields only: the version stays
  EXPECT_EQ(json["motifs"][0]["representative"], 1);
  EXPECT_EQ(json["motifs"][0]["instances"][0]["distance"], 0.8125);
  EXPECT_EQ(json["motifs"][0]["instances"][1]["distance"], 0.0);
  EXPECT_FALSE(json["motifs"][1].contains("representative"));
  auto read = ReadMotifsJson(path);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(*read, *document);
  EXPECT_EQ(read->clips[1].source_fps, 100.0);

  // A file written before these fields: read, with none of them.
  nlohmann::json older = json;
  for (nlohmann::json& clip : older["clips"]) clip.erase("source_fps");
  for (nlohmann::json& motif : older["motifs"]) {
    motif.erase("representative");
    for (nlohmann::json& instance : motif["instances"]) {
      for (const char* field : {"distance", "file_first_frame", "file_last_frame"}) {
        instance.erase(field);
      }
    }
  }
  ASSERT_TRUE(AtomicWriteFile(dir.File("older.json"), older.dump()).ok());
  auto older_read = ReadMotifsJson(dir.File("older.json"));
  ASSERT_TRUE(older_read.ok()) << older_read.status().ToString();
  EXPECT_FALSE(older_read->motifs[0].representative.has_value());
  EXPECT_FALSE(older_read->motifs[0].instances[0].distance.has_value());
  EXPECT_EQ(older_read->clips[1].source_fps, 0.0);
  EXPECT_EQ(older_read->motifs[0].instances[1].start, 50u);
  EXPECT_EQ(older_read->motifs.size(), document->motifs.size());
  // Written again, such a document still has no representative, and its file frames assume
  // the clip was not resampled (the older file does not say).
  const nlohmann::json rewritten = nlohmann::json::parse(MotifsJsonText(*older_read));
  EXPECT_FALSE(rewritten["motifs"][0].contains("representative"));
  EXPECT_EQ(rewritten["motifs"][0]["instances"][1]["file_first_frame"], 52);
}

TEST(MotifsJsonTest, ReaderChecksTheRepresentative) {
  auto document = MakeMotifsDocument(MeasuredResult(), "a.mfs", 1500, TwoClips(), Params());
  ASSERT_TRUE(document.ok());
  const nlohmann::json good = nlohmann::json::parse(MotifsJsonText(*document));
  auto parse = [](const nlohmann::json& json) { return ParseMotifsJson(json.dump(), "m.json"); };
  ASSERT_TRUE(parse(good).ok());
  nlohmann::json changed = good;
  changed["motifs"][0]["representative"] = 2;  // two instances
  Status status = parse(changed).status();
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("motifs[0]: \"representative\" is not an index"),
            std::string::npos)
      << status.message();
  changed = good;
  changed["motifs"][0]["instances"][0].erase("distance");
  status = parse(changed).status();
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("motifs[0].instances[0]: missing \"distance\""),
            std::string::npos)
      << status.message();
  changed = good;
  changed["motifs"][0]["instances"][0]["distance"] = -0.5;
  EXPECT_TRUE(parse(changed).status().IsInvalidArgument());
  changed = good;
  changed["motifs"][0]["instances"][0]["distance"] = "near";
  EXPECT_TRUE(parse(changed).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
