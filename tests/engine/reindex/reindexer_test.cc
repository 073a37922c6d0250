// Reindex (engine/reindex/reindexer.h) against failing writes: a disk that fills up at any write
// of a run (an injected failure at every step in turn, and a real full tmpfs when the test may
// mount one) gives a clear error, leaves the current version exactly as it was (verified whole),
// and the next run, with room again, makes the version an uninterrupted run makes.
#include "engine/reindex/reindexer.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/cli/clip_range_take.h"
#include "engine/cluster/motifs_json.h"
#include "engine/pipeline/option_table.h"
#include "engine/pipeline/stage_options.h"
#include "engine/reindex/mined_version.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/export/bvh_writer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/tmpfs.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

// Takes with two planted motifs as BVH files: batch1/ (the first two thirds) and batch2/.
void MakeTakes(const std::string& dir) {
  SynthOptions options;
  options.frames = 3600;
  options.motifs = 2;
  options.instances_min = 2;
  options.instances_max = 3;
  options.motif_seconds_max = 1.5;
  options.clip_seconds_min = 6;
  options.clip_seconds_max = 10;
  options.seed = 6;
  auto synthesizer = MotionSynthesizer::Create(options);
  ASSERT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  const std::string archive = dir + "/synth.mfs";
  auto writer = FrameFileWriter::Create(archive, (*synthesizer)->skeleton(), options.fps);
  ASSERT_TRUE(writer.ok());
  ASSERT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) { return (*writer)->AppendClip(clip); })
                  .ok());
  ASSERT_TRUE((*writer)->Commit().ok());
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok());
  const std::vector<ClipInfo>& clips = (*reader)->clips();
  ASSERT_GE(clips.size(), 3u);
  fs::create_directories(dir + "/batch1");
  fs::create_directories(dir + "/batch2");
  for (size_t idx = 0; idx < clips.size(); ++idx) {
    auto take = ReadClipRangeAsTake(**reader, clips[idx], 0, clips[idx].frame_count);
    ASSERT_TRUE(take.ok());
    const std::string batch = idx < clips.size() * 2 / 3 ? "/batch1/" : "/batch2/";
    ASSERT_TRUE(WriteBvh(*take, dir + batch + clips[idx].name + ".bvh").ok());
  }
}

class ReindexFailureTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    takes_ = new testing::TempDir();
    MakeTakes(takes_->path());
  }
  static void TearDownTestSuite() {
    delete takes_;
    takes_ = nullptr;
  }

  // The options of a run in `root` (archive, incoming/ and out/ in it).
  ReindexOptions Options(const std::string& root, FileSystem* file_system = PosixFileSystem()) {
    ReindexOptions options;
    options.archive_path = root + "/archive.mfs";
    options.watch_dir = root + "/incoming";
    options.out_dir = root + "/out";
    options.min_age_seconds = 0;
    options.import.first_frame = FirstFramePolicy::kKeep;
    options.mine.write_report = false;
    options.mine.threads = 2;
    options.file_system = file_system;
    return options;
  }

  static void Arrive(const std::string& root, const std::string& batch) {
    fs::create_directories(root + "/incoming");
    for (const auto& entry : fs::directory_iterator(takes_->File(batch))) {
      fs::copy_file(entry.path(), fs::path(root) / "incoming" / entry.path().filename(),
                    fs::copy_options::overwrite_existing);
    }
  }

  // The current version is whole, and it is `version`.
  static void ExpectIntact(const std::string& root, uint64_t version) {
    std::vector<std::string> notes;
    const Status verified = VerifyMinedVersion(root + "/out", &notes);
    EXPECT_TRUE(verified.ok()) << verified.ToString();
    auto manifest = ReadManifest(root + "/out");
    ASSERT_TRUE(manifest.ok());
    EXPECT_EQ(manifest->version, version);
    auto archive = FrameFileReader::Open(root + "/archive.mfs");
    ASSERT_TRUE(archive.ok()) << archive.status().ToString();
    // A failure in the write of the archive's commit slot leaves the new version whole, read
    // from its footer, and Verify names the slot (tests/formats/frame_file/); nothing else.
    const Status archive_verified = (*archive)->Verify();
    EXPECT_TRUE(archive_verified.ok() || !(*archive)->summary().damaged_slot_reason.empty())
        << archive_verified.ToString();
  }

  static testing::TempDir* takes_;
};

testing::TempDir* ReindexFailureTest::takes_ = nullptr;

TEST_F(ReindexFailureTest, AWriteFailingAtAnyStepLeavesTheCurrentVersionAndTheNextRunFinishes) {
  testing::TempDir dir;
  const std::string start = dir.File("start");
  Arrive(start, "batch1");
  ASSERT_TRUE(Reindex(Options(start)).ok());
  Arrive(start, "batch2");
  // An uninterrupted second run: its steps through the file-system seam, and its result.
  const std::string reference = dir.File("reference");
  fs::copy(start, reference, fs::copy_options::recursive);
  testing::FaultInjectingFileSystem counting;
  auto uninterrupted = Reindex(Options(reference, &counting));
  ASSERT_TRUE(uninterrupted.ok()) << uninterrupted.status().ToString();
  ASSERT_EQ(uninterrupted->manifest.build.kind, "incremental");
  // The motifs found (clips' sources name each copy's own folder, so only the motifs compare).
  auto motifs_of = [](const std::string& root) {
    auto document = ReadMotifsJson(root + "/out/motifs.json");
    EXPECT_TRUE(document.ok()) << document.status().ToString();
    return document.ok() ? document->motifs : std::vector<MotifsJsonMotif>{};
  };
  const std::vector<MotifsJsonMotif> expected_motifs = motifs_of(reference);
  ASSERT_FALSE(expected_motifs.empty());
  const int64_t steps = counting.steps();
  ASSERT_GT(steps, 10);
  std::printf("%lld steps through the file-system seam\n", static_cast<long long>(steps));
  // Every step fails in turn, and stays failing (a full disk): the archive append, the trellis
  // update's blocks, index and rename, the manifest, the publication of motifs.json.
  for (int64_t step = 0; step < steps; ++step) {
    SCOPED_TRACE("failing step " + std::to_string(step) + " of " + std::to_string(steps));
    const std::string root = dir.File("step" + std::to_string(step));
    fs::copy(start, root, fs::copy_options::recursive);
    testing::FaultInjectingFileSystem full_disk;
    full_disk.FailAt(step, /*sticky=*/true);
    auto failed = Reindex(Options(root, &full_disk));
    if (failed.ok()) {
      // A failure after the switch (the manifest's rename): the new version is current, and
      // the run says what is left (a folder not synced, motifs.json not yet replaced).
      EXPECT_GE(step, steps - 3);
      EXPECT_FALSE(failed->warnings.empty());
      EXPECT_EQ(failed->manifest.version, 2u);
    } else {
      EXPECT_EQ(failed.status().code(), Status::Code::kResourceExhausted)
          << failed.status().ToString();
      EXPECT_NE(failed.status().message().find("No space left"), std::string::npos);
      ExpectIntact(root, 1);
    }
    auto next = Reindex(Options(root));
    ASSERT_TRUE(next.ok()) << next.status().ToString();
    ExpectIntact(root, 2);
    EXPECT_EQ(motifs_of(root), expected_motifs);
    fs::remove_all(root);
  }
}

TEST_F(ReindexFailureTest, AFullFileSystemGivesAClearErrorAndLeavesTheVersionIntact) {
  testing::TempDir dir;
  testing::Tmpfs tmpfs(dir.File("small"));
  if (!tmpfs.mounted()) {
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?); "
                    "AWriteFailingAtAnyStep... covers a full disk by injected failures";
  }
  const std::string root = dir.File("small");
  Arrive(root, "batch1");
  ASSERT_TRUE(Reindex(Options(root)).ok());
  Arrive(root, "batch2");
  // Little room: the archive append fails. Some room: the append fits, the trellis does not.
  const std::pair<uint64_t, const char*> cases[] = {{uint64_t{16} << 10, "archive.mfs"},
                                                    {uint64_t{256} << 10, "trellis.mtr"}};
  for (const auto& [room, failing_file] : cases) {
    SCOPED_TRACE("room " + std::to_string(room));
    ASSERT_TRUE(tmpfs.LeaveRoom(room));
    auto failed = Reindex(Options(root));
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(failed.status().code(), Status::Code::kResourceExhausted)
        << failed.status().ToString();
    EXPECT_NE(failed.status().message().find("No space left"), std::string::npos)
        << failed.status().ToString();
    std::printf("room %llu bytes: %s\n", (unsigned long long)room,
                failed.status().ToString().c_str());
    EXPECT_NE(failed.status().message().find(failing_file), std::string::npos)
        << "expected the write of " << failing_file << " to fail";
    ExpectIntact(root, 1);
  }
  ASSERT_TRUE(tmpfs.LeaveRoom(uint64_t{64} << 20));
  auto next = Reindex(Options(root));
  ASSERT_TRUE(next.ok()) << next.status().ToString();
  ExpectIntact(root, 2);
}

}  // namespace
}  // namespace motif

namespace motif {
namespace {

// The reindex manifest's parameters are the option table's (engine/pipeline/option_table.h): each
// field is an option's name ('_' for '-') or one of the few the run records beside them, of the
// option's kind, and a first run with no option given records the table's defaults (resolved:
// λ in frames, eps as the joint-angle rule made it).
TEST_F(ReindexFailureTest, TheManifestsParametersAreTheOptionTablesWithItsDefaults) {
  testing::TempDir dir;
  const std::string root = dir.File("root");
  Arrive(root, "batch1");
  ASSERT_TRUE(Reindex(Options(root)).ok());
  const nlohmann::json manifest =
      nlohmann::json::parse(ReadFileToString(root + "/out/manifest.json").value());
  const nlohmann::json& params = manifest["params"];
  const std::set<std::string> recorded_only = {"eps_estimated", "mu",           "sigma",
                                               "weights_hash",  "block_columns", "lsh"};
  const motifmine::MineOptions defaults;
  for (const auto& [key, value] : params.items()) {
    if (recorded_only.count(key)) continue;
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', '-');
    const OptionSpec* spec = FindMineOption(name);
    ASSERT_NE(spec, nullptr) << "params." << key << " is not an option";
    ASSERT_EQ(spec->info.name, name) << "params." << key;
    if (spec->type == OptionType::kChoice || spec->type == OptionType::kText) {
      EXPECT_TRUE(value.is_string()) << key;
    } else {
      EXPECT_TRUE(value.is_number()) << key;
    }
    if (key == "eps" || key == "exclusion" || key == "search") continue;  // resolved by the build
    if (key == "min_length") {  // in frames at the archive's rate
      auto archive = FrameFileReader::Open(root + "/archive.mfs");
      ASSERT_TRUE(archive.ok());
      EXPECT_EQ(value.get<uint64_t>(), ResolvedMinLengthFrames(defaults, (*archive)->fps()));
      continue;
    }
    const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
    motifmine::MineOptions read;
    ASSERT_TRUE(SetOptionFromText(&read, name, key == "groups" && text == "0" ? "auto" : text).ok())
        << key << " " << text;
    EXPECT_EQ(OptionAsText(read, name), spec->info.default_value) << key;
  }
  for (const char* key : {"kmax", "branch", "groups", "similarity", "pause_speed", "eps_rule",
                          "eps_angle", "seed", "max_length_ratio"}) {
    EXPECT_TRUE(params.contains(key)) << key;
  }
  const nlohmann::json& lsh = params["lsh"];
  for (const char* key : {"tables", "probes", "max_candidates", "chain", "chain_sweeps"}) {
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', '-');
    ASSERT_NE(FindMineOption(name), nullptr) << "params.lsh." << key;
    EXPECT_EQ(lsh[key].dump(), FindMineOption(name)->info.default_value) << key;
  }
}

}  // namespace
}  // namespace motif
