// UpdateTrellis: the trellis of an archive that grew, from the trellis of its earlier version.
// With the exact search it must be the full build's file byte for byte (after one update and
// after two in a row, when the new frames reach many old columns and when they reach none, and
// after an interrupted update is resumed); with LSH the new columns are the full build's and
// the old columns share almost all entries with it.
#include "engine/trellis/trellis_update.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/distance/exact_search.h"
#include "engine/lsh/lsh_search.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"
#include "tests/engine/distance/distance_test_util.h"
#include "tests/testing/fault_injection.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/trellis_entries.h"

namespace motif {
namespace {

using testing::ArchiveRows;

constexpr uint32_t kKMax = 24;  // small: most columns are full, so new frames displace entries
constexpr uint32_t kBlockColumns = 512;
constexpr uint32_t kExclusion = 30;

// The first `clip_count` clips of `full`: the archive before the later clips were appended.
ArchiveRows Prefix(const ArchiveRows& full, size_t clip_count) {
  ArchiveRows prefix;
  prefix.skeleton = full.skeleton;
  const size_t stride = full.rows.size() / full.frame_count;
  prefix.frame_count = clip_count < full.clip_first_frames.size()
                           ? full.clip_first_frames[clip_count]
                           : full.frame_count;
  prefix.clip_first_frames.assign(full.clip_first_frames.begin(),
                                  full.clip_first_frames.begin() + clip_count);
  prefix.rows.assign(full.rows.begin(), full.rows.begin() + prefix.frame_count * stride);
  return prefix;
}

// `archive` with a clip of random poses appended: far from every natural pose.
ArchiveRows WithNoiseClip(ArchiveRows archive, uint64_t frames) {
  const std::vector<float> noise = testing::RandomRows(
      frames, static_cast<uint32_t>(archive.skeleton.joint_count()), /*seed=*/99);
  archive.clip_first_frames.push_back(archive.frame_count);
  archive.rows.insert(archive.rows.end(), noise.begin(), noise.end());
  archive.frame_count += frames;
  return archive;
}

// `archive` with its first `clip_count` clips appended again: every new frame has an old twin
// at exactly the same distances, so new and old entries tie in many columns.
ArchiveRows WithRepeatedClips(ArchiveRows archive, size_t clip_count) {
  const ArchiveRows repeated = Prefix(archive, clip_count);
  archive.clip_first_frames.push_back(archive.frame_count);
  for (size_t clip = 1; clip < repeated.clip_first_frames.size(); ++clip) {
    archive.clip_first_frames.push_back(archive.frame_count + repeated.clip_first_frames[clip]);
  }
  archive.rows.insert(archive.rows.end(), repeated.rows.begin(), repeated.rows.end());
  archive.frame_count += repeated.frame_count;
  return archive;
}

NeighbourRules RulesFor(const PoseFeatures& features, float eps) {
  NeighbourRules rules;
  rules.eps = eps;
  rules.k_max = kKMax;
  rules.exclusion_frames = kExclusion;
  rules.clip_first_frames = features.clip_first_frames();
  return rules;
}

TrellisParams ParamsFor(const PoseFeatures& features, float eps, uint64_t identity, bool exact) {
  TrellisParams params;
  params.frame_count = features.frame_count();
  params.archive_identity = identity;
  params.eps = eps;
  params.k_max = kKMax;
  params.exclusion_frames = kExclusion;
  params.search_mode = exact ? 0 : 1;
  params.seed = 1;
  params.weights_hash = 7;
  params.search_params = exact ? "exact" : "lsh";
  return params;
}

// The trellis a full build writes: every column searched, block by block.
void WriteFullTrellis(const NeighbourSearch& search, const TrellisParams& params,
                      const std::string& path) {
  auto writer = TrellisFileWriter::OpenOrResume(path, params, {kBlockColumns});
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  SearchStats stats;
  for (uint64_t first = 0; first < params.frame_count; first += kBlockColumns) {
    std::vector<std::vector<Neighbour>> columns;
    const uint64_t count = std::min<uint64_t>(kBlockColumns, params.frame_count - first);
    ASSERT_TRUE(search.SearchColumns(first, count, &columns, &stats).ok());
    ASSERT_TRUE((*writer)->AppendBlock(columns).ok());
  }
  ASSERT_TRUE((*writer)->Finish().ok());
}

float EstimateEps(const PoseFeatures& features) {
  NeighbourRules rules = RulesFor(features, 1.0f);
  EpsilonOptions options;
  options.sample_pairs = 20000;
  auto estimate = EpsilonEstimator(features, rules, options).Estimate();
  EXPECT_TRUE(estimate.ok()) << estimate.status().ToString();
  return estimate.ok() ? estimate->eps : 1.0f;
}

class TrellisUpdateTest : public ::testing::Test {
 protected:
  void SetUp() override { full_ = testing::SynthArchive(7000, /*seed=*/5); }

  // Builds the exact trellis of `old_rows` at old.mtr, updates it to `new_rows` and compares
  // the result with the full build over `new_rows`.
  TrellisUpdateReport ExpectExactUpdateIsFullBuild(const ArchiveRows& old_rows,
                                                   const ArchiveRows& new_rows, float eps,
                                                   const std::string& name) {
    const PoseFeatures old_features = old_rows.Features();
    const PoseFeatures new_features = new_rows.Features();
    const ExactSearch old_search(old_features, RulesFor(old_features, eps));
    const ExactSearch new_search(new_features, RulesFor(new_features, eps));
    const std::string old_path = dir_.File(name + "-old.mtr");
    const std::string full_path = dir_.File(name + "-full.mtr");
    const std::string updated_path = dir_.File(name + "-updated.mtr");
    if (!std::filesystem::exists(old_path)) {
      WriteFullTrellis(old_search, ParamsFor(old_features, eps, 1, true), old_path);
    }
    const TrellisParams new_params = ParamsFor(new_features, eps, 2, true);
    WriteFullTrellis(new_search, new_params, full_path);
    auto previous = TrellisFileReader::Open(old_path);
    EXPECT_TRUE(previous.ok()) << previous.status().ToString();
    auto report = UpdateTrellis(**previous, new_features, RulesFor(new_features, eps), new_search,
                                new_params, updated_path);
    EXPECT_TRUE(report.ok()) << report.status().ToString();
    EXPECT_EQ(ReadFileToString(updated_path).value(), ReadFileToString(full_path).value()) << name;
    return report.ok() ? *report : TrellisUpdateReport{};
  }

  // An exact update of the first `old_clips` clips to the whole archive: old.mtr and full.mtr
  // written; Update() runs it into updated.mtr.
  struct ExactCase {
    float eps = 0;
    PoseFeatures new_features;
    std::unique_ptr<ExactSearch> search;
    std::unique_ptr<TrellisFileReader> previous;
  };
  void PrepareExact(size_t old_clips, ExactCase* update) {
    const ArchiveRows old_rows = Prefix(full_, old_clips);
    const PoseFeatures old_features = old_rows.Features();
    update->eps = EstimateEps(old_features);
    update->new_features = full_.Features();
    update->search = std::make_unique<ExactSearch>(update->new_features,
                                                   RulesFor(update->new_features, update->eps));
    WriteFullTrellis(ExactSearch(old_features, RulesFor(old_features, update->eps)),
                     ParamsFor(old_features, update->eps, 1, true), dir_.File("old.mtr"));
    WriteFullTrellis(*update->search, ParamsFor(update->new_features, update->eps, 2, true),
                     dir_.File("full.mtr"));
    auto previous = TrellisFileReader::Open(dir_.File("old.mtr"));
    ASSERT_TRUE(previous.ok());
    update->previous = std::move(previous.value());
  }
  Result<TrellisUpdateReport> Update(const ExactCase& update, const std::string& out,
                                     const TrellisUpdateOptions& options = {}) {
    return UpdateTrellis(*update.previous, update.new_features,
                         RulesFor(update.new_features, update.eps), *update.search,
                         ParamsFor(update.new_features, update.eps, 2, true), out, options);
  }

  // An LSH update of the first three quarters of the clips to the whole archive: old.mtr
  // written by a full LSH build (2 threads), and opened as `previous`.
  struct LshCase {
    uint64_t old_frames = 0;
    PoseFeatures new_features;
    float eps = 0;
    LshOptions lsh;  // the first build's hash family: explicit sizes, as reindex records them
    std::unique_ptr<TrellisFileReader> previous;
  };
  void PrepareLsh(LshCase* update) {
    const ArchiveRows old_rows = Prefix(full_, full_.clip_first_frames.size() * 3 / 4);
    const PoseFeatures old_features = old_rows.Features();
    update->old_frames = old_rows.frame_count;
    update->new_features = full_.Features();
    update->eps = EstimateEps(old_features);
    update->lsh.hashes_per_table = 12;
    update->lsh.bucket_width = 0.3f;
    update->lsh.threads = 2;
    auto old_search =
        LshSearch::Create(old_features, RulesFor(old_features, update->eps), update->lsh);
    ASSERT_TRUE(old_search.ok());
    WriteFullTrellis(**old_search, ParamsFor(old_features, update->eps, 1, false),
                     dir_.File("old.mtr"));
    auto previous = TrellisFileReader::Open(dir_.File("old.mtr"));
    ASSERT_TRUE(previous.ok());
    update->previous = std::move(previous.value());
  }

  testing::TempDir dir_;
  ArchiveRows full_;
};

TEST_F(TrellisUpdateTest, ExactUpdateIsTheFullBuildByteForByte) {
  ASSERT_GE(full_.clip_first_frames.size(), 4u);
  const size_t old_clips = full_.clip_first_frames.size() * 3 / 4;
  const ArchiveRows old_rows = Prefix(full_, old_clips);
  const float eps = EstimateEps(old_rows.Features());
  const TrellisUpdateReport report = ExpectExactUpdateIsFullBuild(old_rows, full_, eps, "one");
  EXPECT_EQ(report.old_columns, old_rows.frame_count);
  EXPECT_EQ(report.new_columns, full_.frame_count - old_rows.frame_count);
  // The new clips are the same kind of motion: they displace entries of many old columns.
  EXPECT_GT(report.changed_columns, report.old_columns / 50);
  std::printf("changed %llu of %llu old columns, %llu reverse candidates, %llu exact ties\n",
              (unsigned long long)report.changed_columns, (unsigned long long)report.old_columns,
              (unsigned long long)report.reverse_candidates,
              (unsigned long long)report.exact_recomputations);
  EXPECT_GT(report.rewritten_blocks, 0u);
  EXPECT_GE(report.reverse_candidates, report.changed_columns);
  EXPECT_GT(report.new_blocks, 0u);
}

TEST_F(TrellisUpdateTest, TwoUpdatesInARowAreTheFullBuild) {
  const size_t clips = full_.clip_first_frames.size();
  ASSERT_GE(clips, 4u);
  const ArchiveRows first = Prefix(full_, clips / 2);
  const ArchiveRows second = Prefix(full_, clips * 3 / 4);
  const float eps = EstimateEps(first.Features());
  ExpectExactUpdateIsFullBuild(first, second, eps, "a");
  // The updated file of the first step is the old trellis of the second.
  std::filesystem::copy_file(dir_.File("a-updated.mtr"), dir_.File("b-old.mtr"));
  ExpectExactUpdateIsFullBuild(second, full_, eps, "b");
}

TEST_F(TrellisUpdateTest, BlocksNoNewFrameReachesAreCopied) {
  // A clip of random poses is within eps of nothing natural: no old column changes, every old
  // block is copied as it was, and the result is still the full build.
  const ArchiveRows noisy = WithNoiseClip(full_, 700);
  const float eps = EstimateEps(full_.Features());
  const TrellisUpdateReport report = ExpectExactUpdateIsFullBuild(full_, noisy, eps, "noise");
  EXPECT_EQ(report.changed_columns, 0u);
  EXPECT_EQ(report.rewritten_blocks, 0u);
  EXPECT_EQ(report.copied_blocks, full_.frame_count / kBlockColumns);
}

TEST_F(TrellisUpdateTest, ExactTiesBetweenOldAndNewFramesAreBrokenAsAFullBuildDoes) {
  // New frames at exactly the distances of old ones: the cut of a full column falls inside a
  // group of equal codes, the exact distances are recomputed, and the lower (old) frame wins.
  const ArchiveRows twice = WithRepeatedClips(full_, 2);
  const float eps = EstimateEps(full_.Features());
  const TrellisUpdateReport report = ExpectExactUpdateIsFullBuild(full_, twice, eps, "ties");
  EXPECT_GT(report.exact_recomputations, 0u);
  EXPECT_GT(report.changed_columns, 0u);
}

TEST_F(TrellisUpdateTest, AnInterruptedUpdateResumesAndEndsTheSame) {
  ExactCase update;
  PrepareExact(full_.clip_first_frames.size() * 2 / 3, &update);
  // A disk that fills up after a few blocks: the update fails with a clear error, nothing is
  // renamed into place, and the blocks already written stay for the next run.
  testing::FaultInjectingFileSystem full_disk;
  full_disk.FailAt(12, /*sticky=*/true);
  TrellisUpdateOptions options;
  options.file_system = &full_disk;
  const std::string out = dir_.File("updated.mtr");
  auto failed = Update(update, out, options);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.status().code(), Status::Code::kResourceExhausted) << failed.status().ToString();
  EXPECT_FALSE(std::filesystem::exists(out));
  auto resumed = Update(update, out);
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_GT(resumed->resumed_from_column, 0u);
  EXPECT_EQ(ReadFileToString(out).value(), ReadFileToString(dir_.File("full.mtr")).value());
}

TEST_F(TrellisUpdateTest, AnUpdateInterruptedWhileFinishingResumesWithNothingLeftToWrite) {
  // Every block written, then the index, footer or rename failed: the resumed update has no
  // block left to write and only finishes the file.
  ExactCase update;
  PrepareExact(full_.clip_first_frames.size() / 2, &update);
  // Count the steps of a whole update, then fail its last write (the index and footer).
  testing::FaultInjectingFileSystem counting;
  TrellisUpdateOptions options;
  options.file_system = &counting;
  ASSERT_TRUE(Update(update, dir_.File("counted.mtr"), options).ok());
  testing::FaultInjectingFileSystem failing;
  failing.FailAt(counting.steps() - 4);  // the tail's write, before its sync, rename, dir sync
  options.file_system = &failing;
  const std::string out = dir_.File("updated.mtr");
  ASSERT_FALSE(Update(update, out, options).ok());
  auto resumed = Update(update, out);
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_EQ(resumed->resumed_from_column, full_.frame_count);
  EXPECT_EQ(ReadFileToString(out).value(), ReadFileToString(dir_.File("full.mtr")).value());
}

TEST_F(TrellisUpdateTest, RefusesAnOldTrellisOfOtherParameters) {
  const ArchiveRows old_rows = Prefix(full_, 2);
  const PoseFeatures old_features = old_rows.Features();
  const PoseFeatures new_features = full_.Features();
  WriteFullTrellis(ExactSearch(old_features, RulesFor(old_features, 1.0f)),
                   ParamsFor(old_features, 1.0f, 1, true), dir_.File("old.mtr"));
  auto previous = TrellisFileReader::Open(dir_.File("old.mtr"));
  ASSERT_TRUE(previous.ok());
  const ExactSearch search(new_features, RulesFor(new_features, 1.5f));
  auto report = UpdateTrellis(**previous, new_features, RulesFor(new_features, 1.5f), search,
                              ParamsFor(new_features, 1.5f, 2, true), dir_.File("u.mtr"));
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.status().code(), Status::Code::kInvalidArgument);
}

TEST_F(TrellisUpdateTest, LshNewColumnsAreTheFullBuildsAndAlmostAllEntriesAgree) {
  LshCase update;
  ASSERT_NO_FATAL_FAILURE(PrepareLsh(&update));
  const PoseFeatures& new_features = update.new_features;
  const float eps = update.eps;
  auto new_search = LshSearch::Create(new_features, RulesFor(new_features, eps), update.lsh);
  ASSERT_TRUE(new_search.ok());
  WriteFullTrellis(**new_search, ParamsFor(new_features, eps, 2, false), dir_.File("full.mtr"));
  auto report =
      UpdateTrellis(*update.previous, new_features, RulesFor(new_features, eps), **new_search,
                    ParamsFor(new_features, eps, 2, false), dir_.File("updated.mtr"));
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  EXPECT_GT(report->changed_columns, 0u);

  auto updated = TrellisFileReader::Open(dir_.File("updated.mtr"));
  auto full = TrellisFileReader::Open(dir_.File("full.mtr"));
  ASSERT_TRUE(updated.ok() && full.ok());
  const uint64_t old_count = update.old_frames;
  std::vector<std::vector<Neighbour>> updated_new, full_new;
  ASSERT_TRUE((*updated)->ReadColumns(old_count, full_.frame_count - old_count, &updated_new).ok());
  ASSERT_TRUE((*full)->ReadColumns(old_count, full_.frame_count - old_count, &full_new).ok());
  EXPECT_EQ(updated_new, full_new);

  const double share =
      testing::SharedTrellisEntries(dir_.File("updated.mtr"), dir_.File("full.mtr"));
  RecordProperty("shared_entries", std::to_string(share));
  std::printf("LSH: %.5f of the entries shared with the full build\n", share);
  EXPECT_GE(share, 0.99);
}

// The update's parallel parts (the LSH index, the new columns' and reverse searches, the blocks
// decoded, merged and encoded) give the same file for any thread count.
TEST_F(TrellisUpdateTest, LshUpdateIsTheSameFileForOneAndTwoThreads) {
  LshCase update;
  ASSERT_NO_FATAL_FAILURE(PrepareLsh(&update));
  const PoseFeatures& new_features = update.new_features;
  const float eps = update.eps;
  LshOptions lsh = update.lsh;
  std::vector<std::string> files;
  for (int threads : {1, 2}) {
    lsh.threads = threads;
    auto search = LshSearch::Create(new_features, RulesFor(new_features, eps), lsh);
    ASSERT_TRUE(search.ok());
    TrellisUpdateOptions options;
    options.threads = threads;
    const std::string path = dir_.File("updated-" + std::to_string(threads) + ".mtr");
    auto report = UpdateTrellis(*update.previous, new_features, RulesFor(new_features, eps),
                                **search, ParamsFor(new_features, eps, 2, false), path, options);
    ASSERT_TRUE(report.ok()) << report.status().ToString();
    EXPECT_GT(report->changed_columns, 0u);
    files.push_back(ReadFileToString(path).value());
  }
  EXPECT_EQ(files[0], files[1]);
}

}  // namespace
}  // namespace motif
