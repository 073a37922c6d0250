// `motifmine reindex` with the built binary, as cron runs it: takes arrive in a watched folder in
// two batches. The second run updates the trellis incrementally; its result must agree with a
// from-scratch `mine` over the same archive with the same eps and seed: the same trellis file
// and motifs.json byte for byte with the exact search; with LSH at least 99 % of the trellis
// entries shared and the same planted motifs recovered. Also: a re-run imports nothing, a
// changed file is reported (exit 3) and not imported, a second run while one holds the output
// folder exits at once with 17, and verify accepts the output.
//
// The takes are a synthetic archive with planted motifs (`motifmine synth`), each clip exported
// as a BVH file (`motifmine export`), so the truth file names the imported clips.
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/file_lock.h"
#include "common/file_util.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/reindex/mined_version.h"
#include "engine/reindex/reindex_manifest.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/shared_inputs.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/trellis_entries.h"

namespace motif {
namespace {

namespace fs = std::filesystem;
using testing::RunResult;
using testing::RunTool;

// Two batches of BVH takes with 3 planted motifs, made once for all tests.
class ReindexCliTest : public ::testing::Test {
 protected:
  // How the takes are made; part of the shared inputs' key, so that new options make new takes.
  static constexpr const char* kSynthOptions =
      "--frames 12000 --motifs 3 --seed 4 --motif-seconds-max 2.5 --clip-seconds-min 5 "
      "--clip-seconds-max 12";

  static void SetUpTestSuite() {
    const size_t options_hash = std::hash<std::string>{}(kSynthOptions);
    takes_ = testing::SharedInputs("reindex-cli-takes-" + std::to_string(options_hash) + "-" +
                                       testing::ExecutableStamp(MOTIF_TOOL),
                                   MakeTakes);
  }

  // The takes of both nights, as BVH files in batch1/ and batch2/, and the archive they came from.
  static bool MakeTakes(const std::string& dir) {
    const std::string synth = dir + "/synth.mfs";
    RunResult made = RunTool("synth " + synth + " " + kSynthOptions + " --quiet");
    EXPECT_EQ(made.exit_code, 0) << made.output;
    auto reader = FrameFileReader::Open(synth);
    EXPECT_TRUE(reader.ok());
    if (made.exit_code != 0 || !reader.ok()) return false;
    const std::vector<ClipInfo>& clips = (*reader)->clips();
    EXPECT_GE(clips.size(), 6u);
    fs::create_directories(dir + "/batch1");
    fs::create_directories(dir + "/batch2");
    for (size_t clip = 0; clip < clips.size(); ++clip) {
      // The last quarter of the clips arrives the second night: about a quarter of the frames.
      const std::string batch = clip < clips.size() * 3 / 4 ? "batch1" : "batch2";
      RunResult exported = RunTool("export " + synth + " --clip " + clips[clip].name + " --out " +
                                   dir + "/" + batch + "/" + clips[clip].name + ".bvh");
      EXPECT_EQ(exported.exit_code, 0) << exported.output;
      if (exported.exit_code != 0) return false;
    }
    return clips.size() >= 6;
  }

  static std::string Take(const std::string& name) { return takes_ + "/" + name; }

  void SetUp() override {
    ASSERT_FALSE(takes_.empty()) << "the takes could not be made";
    archive_ = dir_.File("archive.mfs");
    watch_ = dir_.File("incoming");
    out_ = dir_.File("out");
    fs::create_directories(watch_);
  }

  // The takes of `batch` in name order, from the first..last one (last exclusive, -1: all).
  void Arrive(const std::string& batch, int first = 0, int last = -1) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(Take(batch))) {
      files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    if (last < 0) last = static_cast<int>(files.size());
    for (int idx = first; idx < last; ++idx) {
      fs::copy_file(files[idx], fs::path(watch_) / files[idx].filename());
    }
  }

  RunResult Reindex(const std::string& extra = "") {
    return RunTool("reindex " + archive_ + " --watch " + watch_ + " --out " + out_ +
                   " --min-age 0 --first-frame keep --no-report --quiet " + extra);
  }

  ReindexManifest Manifest() {
    auto manifest = ReadManifest(out_);
    EXPECT_TRUE(manifest.ok()) << manifest.status().ToString();
    return manifest.ok() ? *manifest : ReindexManifest{};
  }

  static std::string Bytes(const std::string& path) {
    Result<std::string> bytes = ReadFileToString(path);
    EXPECT_TRUE(bytes.ok()) << path;
    return bytes.ok() ? *bytes : "";
  }

  PlantedMotifScore Score(const std::string& motifs_path) {
    auto truth = ReadTruthJson(Take("synth.truth.json"));
    EXPECT_TRUE(truth.ok());
    auto document = ReadMotifsJson(motifs_path);
    EXPECT_TRUE(document.ok()) << document.status().ToString();
    return ScoreMotifsDocument(*document, truth->instances);
  }

  static std::string takes_;  // the shared inputs' folder
  testing::TempDir dir_;
  std::string archive_, watch_, out_;
};

std::string ReindexCliTest::takes_;

TEST_F(ReindexCliTest, ExactIncrementalResultIsTheFromScratchMineByteForByte) {
  Arrive("batch1", 0, 4);
  RunResult first = Reindex();
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const ReindexManifest v1 = Manifest();
  EXPECT_EQ(v1.version, 1u);
  EXPECT_EQ(v1.build.kind, "full");
  EXPECT_TRUE(v1.params.exact) << "auto picks the exact search on a small archive";
  EXPECT_TRUE(v1.params.eps_estimated);
  EXPECT_EQ(Bytes(out_ + "/motifs.json"), Bytes(out_ + "/v000001/motifs.json"));

  // Two more nights: the first update decodes the trellis for its thresholds, the second uses
  // the ones the first saved (search.msc); both extend the saved features.
  Arrive("batch1", 4);
  RunResult second = Reindex();
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(Manifest().build.kind, "incremental");
  Arrive("batch2");
  RunResult third = Reindex();
  ASSERT_EQ(third.exit_code, 0) << third.output;
  const ReindexManifest v3 = Manifest();
  EXPECT_EQ(v3.version, 3u);
  EXPECT_EQ(v3.build.kind, "incremental");
  EXPECT_GT(v3.build.new_frames, 0u);
  EXPECT_GT(v3.build.changed_columns, 0u);
  EXPECT_EQ(v3.params.eps, v1.params.eps) << "eps is recorded at the first build";
  EXPECT_TRUE(fs::exists(out_ + "/v000003/search.msc"));

  // From scratch over the same archive, the same eps and seed.
  char eps[32];
  std::snprintf(eps, sizeof eps, "%.9g", v3.params.eps);
  const std::string scratch = dir_.File("scratch");
  RunResult mined = RunTool("mine " + archive_ + " --out " + scratch + " --eps " + eps +
                            " --seed 1 --search exact --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  EXPECT_EQ(Bytes(scratch + "/trellis.mtr"), Bytes(out_ + "/v000003/trellis.mtr"));
  EXPECT_EQ(Bytes(scratch + "/paths.mpa"), Bytes(out_ + "/v000003/paths.mpa"));
  EXPECT_EQ(Bytes(scratch + "/motifs.json"), Bytes(out_ + "/motifs.json"));
  const PlantedMotifScore score = Score(out_ + "/motifs.json");
  EXPECT_EQ(score.recall, 1.0);

  // Nothing new: no new version, exit 0.
  RunResult again = Reindex();
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(Manifest().version, 3u);
  RunResult verified = RunTool("verify " + out_);
  EXPECT_EQ(verified.exit_code, 0) << verified.output;
  EXPECT_NE(verified.output.find("version 3"), std::string::npos) << verified.output;
}

// A night's takes are a small share of a grown archive: here every take but one is mined
// first, then the first 240 frames of the remaining one (2 % of the frames) arrive. The LSH
// columns are approximate either way; what differs is which new frames each old column gets:
// the from-scratch build finds them with the old column's own query, the update with the new
// frames' queries (docs/reliability.md, "Agreement").
TEST_F(ReindexCliTest, LshIncrementalResultSharesAlmostAllEntriesAndFindsTheSameMotifs) {
  std::vector<fs::path> takes;
  for (const char* batch : {"batch1", "batch2"}) {
    for (const auto& entry : fs::directory_iterator(Take(batch))) {
      takes.push_back(entry.path());
    }
  }
  std::sort(takes.begin(), takes.end(), [](const fs::path& a, const fs::path& b) {
    return fs::file_size(a) != fs::file_size(b) ? fs::file_size(a) > fs::file_size(b) : a < b;
  });
  for (size_t idx = 0; idx + 1 < takes.size(); ++idx) {
    fs::copy_file(takes[idx], fs::path(watch_) / takes[idx].filename());
  }
  RunResult first = Reindex("--search lsh");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const ReindexManifest v1 = Manifest();
  EXPECT_FALSE(v1.params.exact);
  EXPECT_GT(v1.params.lsh.hashes_per_table, 0u) << "the family is recorded resolved";
  EXPECT_GT(v1.params.lsh.bucket_width, 0.0f);
  RunResult late =
      RunTool("export " + Take("synth.mfs") + " --clip " + takes.back().stem().string() +
              " --start 0 --end 240 --out " + watch_ + "/late_take.bvh");
  ASSERT_EQ(late.exit_code, 0) << late.output;
  RunResult second = Reindex();
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const ReindexManifest v2 = Manifest();
  EXPECT_EQ(v2.build.kind, "incremental");
  EXPECT_FALSE(v2.params.exact) << "the search is recorded";
  std::printf("LSH reindex: %llu new frames of %llu\n", (unsigned long long)v2.build.new_frames,
              (unsigned long long)v2.archive.frames);

  char flags[160];
  std::snprintf(flags, sizeof flags, "--eps %.9g --hashes %u --width %.9g", v2.params.eps,
                v2.params.lsh.hashes_per_table, v2.params.lsh.bucket_width);
  const std::string scratch = dir_.File("scratch");
  RunResult mined = RunTool("mine " + archive_ + " --out " + scratch + " " + flags +
                            " --seed 1 --search lsh --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;

  const std::string incremental_path = out_ + "/v000002/trellis.mtr";
  const std::string full_path = scratch + "/trellis.mtr";
  const double share = testing::SharedTrellisEntries(incremental_path, full_path);
  std::printf("LSH reindex: %.5f of the entries shared with the from-scratch build\n", share);
  EXPECT_GE(share, 0.99);
  {
    // Where they differ: old or new columns, old or new frames.
    const auto incremental = testing::TrellisEntries(incremental_path);
    const auto full = testing::TrellisEntries(full_path);
    const uint64_t old_frames = v1.archive.frames;
    uint64_t counts[2][2][2] = {};  // [only in incremental?][new column?][new frame?]
    for (const auto& entry : incremental) {
      if (!full.count(entry)) ++counts[1][entry.first >= old_frames][entry.second >= old_frames];
    }
    for (const auto& entry : full) {
      if (!incremental.count(entry))
        ++counts[0][entry.first >= old_frames][entry.second >= old_frames];
    }
    for (int only_incremental = 0; only_incremental < 2; ++only_incremental) {
      std::printf(
          "  only in %s: old col/old frame %llu, old col/new frame %llu, new col/old "
          "frame %llu, new col/new frame %llu\n",
          only_incremental ? "incremental" : "from scratch",
          (unsigned long long)counts[only_incremental][0][0],
          (unsigned long long)counts[only_incremental][0][1],
          (unsigned long long)counts[only_incremental][1][0],
          (unsigned long long)counts[only_incremental][1][1]);
    }
    // The new frames' columns are a full build's.
    EXPECT_EQ(counts[0][1][0] + counts[0][1][1] + counts[1][1][0] + counts[1][1][1], 0u);
  }

  // The same planted motifs recovered, with the same quality.
  const PlantedMotifScore ours = Score(out_ + "/motifs.json");
  const PlantedMotifScore theirs = Score(scratch + "/motifs.json");
  std::printf("planted recall %.3f incremental, %.3f from scratch\n", ours.recall, theirs.recall);
  EXPECT_EQ(ours.planted_hit, theirs.planted_hit);
  EXPECT_GE(ours.recall, theirs.recall - 0.05);
  EXPECT_GE(ours.recall, 0.8);
  EXPECT_GE(ours.adjusted_rand_index, theirs.adjusted_rand_index - 0.05);
}

TEST_F(ReindexCliTest, AChangedParameterRegrowsOrRebuildsAsAFromScratchMineWould) {
  Arrive("batch1");
  ASSERT_EQ(Reindex().exit_code, 0);
  const ReindexManifest v1 = Manifest();
  char eps[32];
  std::snprintf(eps, sizeof eps, "%.9g", v1.params.eps);
  // A grow parameter: the same trellis (linked, with its search cache), paths grown again.
  RunResult regrow = Reindex("--branch 3");
  ASSERT_EQ(regrow.exit_code, 0) << regrow.output;
  const ReindexManifest v2 = Manifest();
  EXPECT_EQ(v2.build.kind, "regrow");
  EXPECT_EQ(v2.params.branch, 3u);
  EXPECT_EQ(v2.trellis.checksum, v1.trellis.checksum);
  EXPECT_TRUE(fs::exists(out_ + "/v000002/search.msc"));
  RunResult mined = RunTool("mine " + archive_ + " --out " + dir_.File("b3") + " --eps " + eps +
                            " --branch 3 --search exact --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  EXPECT_EQ(Bytes(dir_.File("b3") + "/motifs.json"), Bytes(out_ + "/motifs.json"));
  // Recorded: the next run keeps B = 3 without being told.
  EXPECT_EQ(Reindex().exit_code, 0);
  EXPECT_EQ(Manifest().version, 2u);
  // A trellis parameter: everything from the archive again, with the recorded eps.
  RunResult rebuild = Reindex("--kmax 128");
  ASSERT_EQ(rebuild.exit_code, 0) << rebuild.output;
  const ReindexManifest v3 = Manifest();
  EXPECT_EQ(v3.build.kind, "full");
  EXPECT_EQ(v3.params.k_max, 128u);
  EXPECT_EQ(v3.params.eps, v1.params.eps);
  mined = RunTool("mine " + archive_ + " --out " + dir_.File("k128") + " --eps " + eps +
                  " --branch 3 --kmax 128 --search exact --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  EXPECT_EQ(Bytes(dir_.File("k128") + "/trellis.mtr"), Bytes(out_ + "/v000003/trellis.mtr"));
  EXPECT_EQ(Bytes(dir_.File("k128") + "/motifs.json"), Bytes(out_ + "/motifs.json"));
}

// The rule that estimates eps: recorded at the first run, and another rule or angle estimates it
// again, as `mine` with that rule would, while a run without them keeps the recorded eps.
TEST_F(ReindexCliTest, AnotherEpsRuleEstimatesEpsAgainAsMineWithThatRuleWould) {
  Arrive("batch1", 0, 3);
  ASSERT_EQ(Reindex().exit_code, 0);
  const ReindexManifest v1 = Manifest();
  EXPECT_TRUE(v1.params.eps_estimated);
  EXPECT_EQ(v1.params.eps_rule, "joint-angle");
  EXPECT_EQ(v1.params.eps_angle_degrees, 12.0);

  RunResult angle = Reindex("--eps-angle 14");
  ASSERT_EQ(angle.exit_code, 0) << angle.output;
  const ReindexManifest v2 = Manifest();
  EXPECT_EQ(v2.build.kind, "full");
  EXPECT_EQ(v2.params.eps_angle_degrees, 14.0);
  EXPECT_GT(v2.params.eps, v1.params.eps);
  RunResult mined = RunTool("mine " + archive_ + " --out " + dir_.File("a14") +
                            " --eps-angle 14 --search exact --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  EXPECT_EQ(Bytes(dir_.File("a14") + "/motifs.json"), Bytes(out_ + "/motifs.json"));
  // The same angle again, or none: up to date.
  EXPECT_EQ(Reindex("--eps-angle 14").exit_code, 0);
  EXPECT_EQ(Reindex().exit_code, 0);
  EXPECT_EQ(Manifest().version, 2u);

  RunResult paper = Reindex("--eps-rule paper");
  ASSERT_EQ(paper.exit_code, 0) << paper.output;
  const ReindexManifest v3 = Manifest();
  EXPECT_EQ(v3.version, 3u);
  EXPECT_EQ(v3.params.eps_rule, "paper");
  EXPECT_EQ(v3.params.eps_angle_degrees, 0.0);
  EXPECT_GT(v3.params.mu, 0.0f);
  EXPECT_FLOAT_EQ(v3.params.eps, v3.params.mu - 2 * v3.params.sigma);
  mined = RunTool("mine " + archive_ + " --out " + dir_.File("paper") +
                  " --eps-rule paper --search exact --no-report --quiet");
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  EXPECT_EQ(Bytes(dir_.File("paper") + "/motifs.json"), Bytes(out_ + "/motifs.json"));

  // An explicit eps overrides the rule; a bad rule or angle is a usage error naming the flag (exit
  // 2, the option table's values), as in mine.
  char eps[32];
  std::snprintf(eps, sizeof eps, "%.9g", v1.params.eps);
  RunResult given = Reindex(std::string("--eps ") + eps + " --eps-rule paper");
  ASSERT_EQ(given.exit_code, 0) << given.output;
  EXPECT_FALSE(Manifest().params.eps_estimated);
  EXPECT_EQ(Manifest().params.eps_rule, "");
  for (const std::string bad : {"--eps-rule median", "--eps-angle 0", "--eps-angle 200"}) {
    RunResult refused = Reindex(bad);
    EXPECT_EQ(refused.exit_code, 2) << bad << ": " << refused.output;
    EXPECT_NE(refused.output.find(bad.substr(0, bad.find(' '))), std::string::npos)
        << refused.output;
  }
  EXPECT_EQ(Manifest().version, 4u);
}

TEST_F(ReindexCliTest, ARerunImportsNothingAndAChangedFileIsReportedNotImported) {
  Arrive("batch1");
  ASSERT_EQ(Reindex().exit_code, 0);
  const ReindexManifest v1 = Manifest();
  // The same content under a new name is the same take: skipped.
  const fs::path some_take = fs::directory_iterator(watch_)->path();
  fs::copy_file(some_take, fs::path(watch_) / "copy_of_a_take.bvh");
  RunResult again = Reindex();
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("up to date"), std::string::npos) << again.output;
  EXPECT_EQ(Manifest().version, v1.version);

  // An imported file whose content changed: reported (exit 3), not imported.
  {
    std::ofstream append(some_take, std::ios::app);
    append << "\n";
  }
  RunResult changed = Reindex();
  EXPECT_EQ(changed.exit_code, 3) << changed.output;
  EXPECT_NE(changed.output.find("changed since it was imported"), std::string::npos)
      << changed.output;
  EXPECT_EQ(Manifest().archive.frames, v1.archive.frames);
  EXPECT_EQ(Manifest().version, v1.version);
}

TEST_F(ReindexCliTest, AFirstNightWithEveryTakeStillBeingCopiedWaitsAndExitsZero) {
  Arrive("batch1");
  // Every take is younger than --min-age: not a failure (cron would mail one), a wait.
  RunResult waiting = RunTool("reindex " + archive_ + " --watch " + watch_ + " --out " + out_ +
                              " --min-age 3600 --no-report");
  EXPECT_EQ(waiting.exit_code, 0) << waiting.output;
  EXPECT_NE(waiting.output.find("waiting: no archive yet"), std::string::npos) << waiting.output;
  EXPECT_FALSE(fs::exists(archive_));
  EXPECT_FALSE(fs::exists(out_ + "/manifest.json"));
  RunResult later = Reindex();  // the next night: old enough
  ASSERT_EQ(later.exit_code, 0) << later.output;
  EXPECT_EQ(Manifest().version, 1u);
}

TEST_F(ReindexCliTest, ASecondRunWhileOneHoldsTheOutputFolderExitsAtOnceWith17) {
  Arrive("batch1");
  fs::create_directories(out_);
  ExclusiveFileLock held;  // what a running reindex holds
  ASSERT_TRUE(held.Acquire(out_ + "/.motifmine.lock", "test", /*create=*/true).ok());
  RunResult busy = Reindex();
  EXPECT_EQ(busy.exit_code, 17) << busy.output;
  EXPECT_NE(busy.output.find("another motifmine run"), std::string::npos) << busy.output;
  EXPECT_FALSE(fs::exists(archive_)) << "nothing was imported";
  EXPECT_FALSE(fs::exists(out_ + "/manifest.json"));
}

TEST_F(ReindexCliTest, ProgressJsonGivesLogLinesAndASummaryLine) {
  Arrive("batch1");
  RunResult run = RunTool("reindex " + archive_ + " --watch " + watch_ + " --out " + out_ +
                          " --min-age 0 --no-report --progress=json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* stage : {"import", "trellis", "grow", "cluster"}) {
    EXPECT_NE(run.output.find(std::string("\"stage\":\"") + stage), std::string::npos)
        << stage << "\n"
        << run.output;
  }
  EXPECT_NE(run.output.find("\"event\":\"reindex\""), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\"exit_code\":0"), std::string::npos) << run.output;
}

TEST_F(ReindexCliTest, TheCronWrapperIsSilentWhenAllIsWellAndSaysWhatWasNotImported) {
  Arrive("batch1");
  const std::string wrapper = std::string("MOTIFMINE=") + MOTIF_TOOL + " " + MOTIF_CRON_SCRIPT +
                              " " + archive_ + " " + watch_ + " " + out_ + " --min-age 0 " +
                              "--first-frame keep --no-report";
  RunResult night = testing::RunShell(wrapper + " 2>&1");
  EXPECT_EQ(night.exit_code, 0) << night.output;
  EXPECT_EQ(night.output, "") << "cron mails whatever a job prints";
  EXPECT_EQ(Manifest().version, 1u);
  // The day's log: JSON lines, the summary last.
  std::vector<fs::path> logs;
  for (const auto& entry : fs::directory_iterator(out_ + "/logs")) logs.push_back(entry.path());
  ASSERT_EQ(logs.size(), 1u);
  const std::string log = Bytes(logs[0].string());
  EXPECT_NE(log.find("\"event\":\"reindex\""), std::string::npos) << log;
  EXPECT_NE(log.find("\"exit_code\":0"), std::string::npos) << log;
  EXPECT_NE(log.find("\"stage\":\"trellis\""), std::string::npos);

  // A run still going (the lock held): silent, exit 0; tomorrow does it.
  {
    ExclusiveFileLock held;
    ASSERT_TRUE(held.Acquire(out_ + "/.motifmine.lock", "test").ok());
    RunResult busy = testing::RunShell(wrapper + " 2>&1");
    EXPECT_EQ(busy.exit_code, 0) << busy.output;
    EXPECT_EQ(busy.output, "");
  }
  // A changed take: exit 3, and the file is named.
  const fs::path some_take = fs::directory_iterator(watch_)->path();
  {
    std::ofstream append(some_take, std::ios::app);
    append << "\n";
  }
  RunResult changed = testing::RunShell(wrapper + " 2>&1");
  EXPECT_EQ(changed.exit_code, 3) << changed.output;
  EXPECT_NE(changed.output.find(some_take.filename().string()), std::string::npos)
      << changed.output;
}

// What a reader holds of a version: everything it can read, decoded.
struct VersionContent {
  std::vector<std::vector<Neighbour>> columns;
  std::vector<PathCandidate> candidates;
  MotifsDocument motifs;
  std::vector<float> last_frames;  // the archive's last 100 frames
  uint64_t archive_frames = 0;
};

VersionContent ReadAll(const MinedVersion& version) {
  VersionContent content;
  EXPECT_TRUE(
      version.trellis->ReadColumns(0, version.trellis->column_count(), &content.columns).ok());
  content.candidates = version.paths->candidates();
  content.motifs = version.motifs;
  content.archive_frames = version.archive->frame_count();
  EXPECT_TRUE(
      version.archive->ReadFrames(content.archive_frames - 100, 100, &content.last_frames).ok());
  return content;
}

TEST_F(ReindexCliTest, AReaderOfTheOldVersionKeepsReadingItWhileNewVersionsAreSwitchedIn) {
  Arrive("batch1", 0, 3);
  ASSERT_EQ(Reindex().exit_code, 0);
  auto opened = OpenMinedVersion(out_);
  ASSERT_TRUE(opened.ok()) << opened.status().ToString();
  const MinedVersion& v1 = *opened;
  EXPECT_EQ(v1.manifest.version, 1u);
  const VersionContent before = ReadAll(v1);

  // Two more nights: version 3 is current, version 2 kept, version 1 removed.
  Arrive("batch1", 3);
  ASSERT_EQ(Reindex().exit_code, 0);
  Arrive("batch2");
  ASSERT_EQ(Reindex().exit_code, 0);
  EXPECT_EQ(Manifest().version, 3u);
  EXPECT_FALSE(fs::exists(out_ + "/v000001")) << "older than the previous: removed";
  EXPECT_TRUE(fs::exists(out_ + "/v000002"));
  auto archive_now = FrameFileReader::Open(archive_);
  ASSERT_TRUE(archive_now.ok());
  EXPECT_GT((*archive_now)->frame_count(), before.archive_frames);

  // The reader of version 1 still reads exactly what it read: its files are mapped or held,
  // and its archive reader is at version 1's commit.
  const VersionContent after = ReadAll(v1);
  EXPECT_EQ(after.columns, before.columns);
  EXPECT_EQ(after.candidates, before.candidates);
  EXPECT_EQ(after.motifs, before.motifs);
  EXPECT_EQ(after.archive_frames, before.archive_frames);
  EXPECT_EQ(after.last_frames, before.last_frames);
  // A new reader gets version 3, consistent with the archive as it is now.
  auto current = OpenMinedVersion(out_);
  ASSERT_TRUE(current.ok()) << current.status().ToString();
  EXPECT_EQ(current->manifest.version, 3u);
  EXPECT_EQ(current->archive->frame_count(), (*archive_now)->frame_count());
  EXPECT_EQ(current->motifs.frames, (*archive_now)->frame_count());
  // motifs.json at its documented path is version 3's, and still opens against the archive
  // version it names (report and export-motif read it so).
  EXPECT_EQ(Bytes(out_ + "/motifs.json"), Bytes(out_ + "/v000003/motifs.json"));
  RunResult report = RunTool("report " + out_ + " --out " + dir_.File("r.html"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
}

TEST_F(ReindexCliTest, ReadersOpeningWhileARunSwitchesAlwaysSeeOneWholeVersion) {
  Arrive("batch1");
  ASSERT_EQ(Reindex().exit_code, 0);
  Arrive("batch2");
  RunResult run;
  std::atomic<bool> finished{false};
  std::thread writer([&] {
    run = Reindex();
    finished = true;
  });
  uint64_t opens = 0;
  std::set<uint64_t> versions;
  // Open, check, close, again, until the run has switched to version 2 (and a little more).
  for (int after_switch = 0; after_switch < 20;) {
    if (finished && versions.count(2) == 0 && ReadManifest(out_)->version != 2) break;
    auto version = OpenMinedVersion(out_);
    ASSERT_TRUE(version.ok()) << version.status().ToString();
    ++opens;
    versions.insert(version->manifest.version);
    const ReindexManifest& manifest = version->manifest;
    EXPECT_EQ(version->trellis->params().archive_identity, manifest.archive.identity);
    EXPECT_EQ(version->trellis->column_count(), version->archive->frame_count());
    EXPECT_EQ(version->paths->params().trellis_identity, version->trellis->identity());
    EXPECT_EQ(version->motifs.frames, version->archive->frame_count());
    if (manifest.version == 2) ++after_switch;
  }
  writer.join();
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(versions, (std::set<uint64_t>{1, 2}));
  std::printf("%llu consistent opens while the run switched\n", (unsigned long long)opens);
}

}  // namespace
}  // namespace motif
