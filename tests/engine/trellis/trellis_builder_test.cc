#include "engine/trellis/trellis_builder.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/trellis/trellis_audit.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// A synthetic archive of `frames` frames with planted motifs, written once per test.
std::string MakeArchive(const testing::TempDir& dir, uint64_t frames) {
  const std::string path = dir.File("synth.mfs");
  SynthOptions options;
  options.frames = frames;
  options.motifs = 2;
  options.instances_min = 2;
  options.instances_max = 3;
  options.motif_seconds_max = 1.5;
  options.seed = 3;
  options.clip_seconds_min = 15;
  options.clip_seconds_max = 30;
  auto synthesizer = MotionSynthesizer::Create(options);
  if (!synthesizer.ok()) {
    ADD_FAILURE() << synthesizer.status().ToString();
    return path;
  }
  auto writer = FrameFileWriter::Create(path, (*synthesizer)->skeleton(), options.fps);
  EXPECT_TRUE(writer.ok());
  EXPECT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& clip) { return (*writer)->AppendClip(clip); })
                  .ok());
  EXPECT_TRUE((*writer)->Commit().ok());
  return path;
}

TrellisOptions SmallOptions(bool exact, int threads) {
  TrellisOptions options;
  // Explicit: on archives this small the default (auto) would choose the exact search.
  options.search = exact ? TrellisSearchMode::kExact : TrellisSearchMode::kLsh;
  options.threads = threads;
  options.k_max = 64;
  options.block_columns = 2048;
  return options;
}

TEST(BuildTrellis, SameBytesForAnyThreadCount) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 4300);  // 3 blocks of 2048 columns
  for (bool exact : {true, false}) {
    std::string bytes[2];
    for (int threads = 1; threads <= 2; ++threads) {
      const std::string path = dir.File(std::to_string(threads) + "t.mtr");
      auto report = BuildTrellis(archive, path, SmallOptions(exact, threads));
      ASSERT_TRUE(report.ok()) << report.status().ToString();
      EXPECT_FALSE(report->reused);
      EXPECT_EQ(report->columns, 4300u);
      EXPECT_GT(report->mean_k, 1.0);
      bytes[threads - 1] = ReadFileToString(path).value();
    }
    EXPECT_EQ(bytes[0], bytes[1]) << (exact ? "exact" : "lsh");
  }
}

TEST(BuildTrellis, ExactTrellisHoldsTheExactColumns) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 6000);
  const std::string path = dir.File("e.mtr");
  auto report = BuildTrellis(archive, path, SmallOptions(true, 2));
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok());
  auto weights = LoadDistanceWeights((*reader)->skeleton(), "");
  auto features = PoseFeatures::FromArchive(**reader, *weights);
  ASSERT_TRUE(features.ok());
  NeighbourRules rules;
  rules.eps = report->params.eps;
  rules.k_max = 64;
  rules.exclusion_frames = report->params.exclusion_frames;
  EXPECT_EQ(rules.exclusion_frames, 30u);  // half of 0.5 s at 120 fps
  rules.clip_first_frames = features->clip_first_frames();
  ExactSearch exact(*features, rules);
  std::vector<std::vector<Neighbour>> expected;
  SearchStats stats;
  ASSERT_TRUE(exact.SearchColumns(0, 6000, &expected, &stats).ok());
  auto trellis = TrellisFileReader::Open(path);
  ASSERT_TRUE(trellis.ok());
  std::vector<std::vector<Neighbour>> stored;
  ASSERT_TRUE((*trellis)->ReadColumns(0, 6000, &stored).ok());
  const float bound = rules.eps / 65535.0f;
  for (uint64_t column = 0; column < 6000; ++column) {
    ASSERT_EQ(stored[column].size(), expected[column].size()) << "column " << column;
    for (size_t idx = 0; idx < stored[column].size(); ++idx) {
      EXPECT_EQ(stored[column][idx].frame, expected[column][idx].frame);
      EXPECT_NEAR(stored[column][idx].distance, expected[column][idx].distance, bound);
    }
  }
}

TEST(BuildTrellis, ReusesAFinishedTrellisAndRebuildsWhenAParameterChanges) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 6000);
  const std::string path = dir.File("r.mtr");
  ASSERT_TRUE(BuildTrellis(archive, path, SmallOptions(false, 2)).ok());
  auto again = BuildTrellis(archive, path, SmallOptions(false, 1));
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(again->reused);
  TrellisOptions changed = SmallOptions(false, 2);
  changed.k_max = 32;
  auto rebuilt = BuildTrellis(archive, path, changed);
  ASSERT_TRUE(rebuilt.ok());
  EXPECT_FALSE(rebuilt->reused);
  auto trellis = TrellisFileReader::Open(path);
  ASSERT_TRUE(trellis.ok());
  EXPECT_EQ((*trellis)->params().k_max, 32u);
}

TEST(BuildTrellis, ResumesAnInterruptedBuildToTheSameFile) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 9000);
  const std::string reference = dir.File("reference.mtr");
  ASSERT_TRUE(BuildTrellis(archive, reference, SmallOptions(false, 2)).ok());
  const std::string path = dir.File("resumed.mtr");
  TrellisOptions interrupted = SmallOptions(false, 2);
  interrupted.stop_after_blocks = 2;
  auto stopped = BuildTrellis(archive, path, interrupted);
  ASSERT_FALSE(stopped.ok());
  EXPECT_FALSE(std::filesystem::exists(path));
  auto resumed = BuildTrellis(archive, path, SmallOptions(false, 1));
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_EQ(resumed->resumed_from_column, 4096u);
  EXPECT_EQ(ReadFileToString(path).value(), ReadFileToString(reference).value());
}

// LSH columns depend on their whole chain (256 columns, swept both ways), never on how the
// trellis is cut into blocks: blocks of 1000 columns (which cut chains) give the columns of
// blocks of 2048, also when the build is interrupted and resumed in the middle of a chain.
TEST(BuildTrellis, LshColumnsDoNotDependOnTheBlockSplit) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 9000);
  const std::string reference = dir.File("reference.mtr");
  ASSERT_TRUE(BuildTrellis(archive, reference, SmallOptions(false, 2)).ok());
  TrellisOptions cut = SmallOptions(false, 2);
  cut.block_columns = 1000;
  ASSERT_NE(cut.lsh.chain_columns, 0u);
  ASSERT_NE(cut.block_columns % cut.lsh.chain_columns, 0u);
  ASSERT_GT(cut.lsh.chain_sweeps, 0u);
  const std::string path = dir.File("cut.mtr");
  TrellisOptions interrupted = cut;
  interrupted.stop_after_blocks = 3;
  ASSERT_FALSE(BuildTrellis(archive, path, interrupted).ok());
  cut.threads = 1;
  auto resumed = BuildTrellis(archive, path, cut);
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_EQ(resumed->resumed_from_column, 3000u);
  auto expected = TrellisFileReader::Open(reference);
  auto actual = TrellisFileReader::Open(path);
  ASSERT_TRUE(expected.ok());
  ASSERT_TRUE(actual.ok());
  std::vector<std::vector<Neighbour>> expected_columns;
  std::vector<std::vector<Neighbour>> actual_columns;
  ASSERT_TRUE((*expected)->ReadColumns(0, 9000, &expected_columns).ok());
  ASSERT_TRUE((*actual)->ReadColumns(0, 9000, &actual_columns).ok());
  EXPECT_EQ((*actual)->block_columns(), 1000u);
  for (uint64_t column = 0; column < 9000; ++column) {
    ASSERT_EQ(actual_columns[column], expected_columns[column]) << "column " << column;
  }
}

TEST(AuditTrellis, LshRecallOnAPlantedSyntheticArchive) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 12000);
  const std::string lsh_path = dir.File("l.mtr");
  TrellisOptions options = SmallOptions(false, 2);
  ASSERT_TRUE(BuildTrellis(archive, lsh_path, options).ok());
  AuditOptions audit;
  audit.sample_columns = 300;
  audit.lsh = options.lsh;
  auto report = AuditTrellis(archive, lsh_path, audit);
  ASSERT_TRUE(report.ok()) << report.status().ToString();
  EXPECT_EQ(report->sampled_columns, 300u);
  EXPECT_GE(report->recall, 0.95);
  EXPECT_GT(report->lsh_evaluations_per_query, 0.0);
  EXPECT_LT(report->lsh_evaluations_per_query, report->exact_evaluations_per_query);
  // The split by kind of column adds up to the totals.
  EXPECT_EQ(report->capped_exact_entries + report->uncapped_exact_entries, report->exact_entries);
  EXPECT_EQ(report->capped_found_entries + report->uncapped_found_entries, report->found_entries);
  EXPECT_LE(report->capped_columns_full, report->capped_exact_columns);
  // An exact trellis audits at recall 1.
  const std::string exact_path = dir.File("x.mtr");
  ASSERT_TRUE(BuildTrellis(archive, exact_path, SmallOptions(true, 2)).ok());
  auto exact_report = AuditTrellis(archive, exact_path, audit);
  ASSERT_TRUE(exact_report.ok());
  EXPECT_EQ(exact_report->recall, 1.0);
  EXPECT_EQ(exact_report->capped_found_entries, exact_report->capped_exact_entries);
  EXPECT_EQ(exact_report->capped_columns_full, exact_report->capped_exact_columns);
}

TEST(BuildTrellis, AutoChoosesExactBelowTheThresholdAndLshFromIt) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 6000);
  TrellisOptions options = SmallOptions(false, 2);
  options.search = TrellisSearchMode::kAuto;
  EXPECT_EQ(options.auto_exact_max_frames, kAutoExactMaxFrames);
  EXPECT_GT(kAutoExactMaxFrames, 6000u);
  auto small = BuildTrellis(archive, dir.File("auto.mtr"), options);
  ASSERT_TRUE(small.ok()) << small.status().ToString();
  EXPECT_EQ(small->search, TrellisSearchMode::kExact);
  EXPECT_EQ(small->params.search_mode, 0u);
  EXPECT_EQ(small->params.search_params, "exact");
  // The same file as asking for the exact search: reused, not rebuilt.
  auto exact = BuildTrellis(archive, dir.File("auto.mtr"), SmallOptions(true, 1));
  ASSERT_TRUE(exact.ok());
  EXPECT_TRUE(exact->reused);
  // At or above the threshold: LSH, recorded as such.
  options.auto_exact_max_frames = 6000;
  auto large = BuildTrellis(archive, dir.File("auto.mtr"), options);
  ASSERT_TRUE(large.ok()) << large.status().ToString();
  EXPECT_FALSE(large->reused);
  EXPECT_EQ(large->search, TrellisSearchMode::kLsh);
  EXPECT_EQ(large->params.search_mode, 1u);
  EXPECT_EQ(large->params.search_params.rfind("lsh ", 0), 0u) << large->params.search_params;
  // The legacy flag still forces the exact search; it contradicts an explicit LSH request.
  TrellisOptions legacy = SmallOptions(false, 2);
  legacy.search = TrellisSearchMode::kAuto;
  legacy.exact = true;
  legacy.auto_exact_max_frames = 1;
  auto forced = BuildTrellis(archive, dir.File("auto.mtr"), legacy);
  ASSERT_TRUE(forced.ok());
  EXPECT_EQ(forced->search, TrellisSearchMode::kExact);
  legacy.search = TrellisSearchMode::kLsh;
  EXPECT_TRUE(BuildTrellis(archive, dir.File("b.mtr"), legacy).status().IsInvalidArgument());
}

TEST(TrellisSearchMode, NamesRoundTrip) {
  for (TrellisSearchMode mode :
       {TrellisSearchMode::kAuto, TrellisSearchMode::kLsh, TrellisSearchMode::kExact}) {
    auto parsed = ParseTrellisSearchMode(TrellisSearchModeName(mode));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, mode);
  }
  EXPECT_TRUE(ParseTrellisSearchMode("fast").status().IsInvalidArgument());
}

TEST(BuildTrellis, RejectsImpossibleParameters) {
  testing::TempDir dir;
  const std::string archive = MakeArchive(dir, 6000);
  TrellisOptions options = SmallOptions(false, 1);
  options.k_max = 0;
  EXPECT_TRUE(BuildTrellis(archive, dir.File("a.mtr"), options).status().IsInvalidArgument());
  options = SmallOptions(false, 1);
  options.eps = -1;
  EXPECT_TRUE(BuildTrellis(archive, dir.File("a.mtr"), options).status().IsInvalidArgument());
  options = SmallOptions(false, 1);
  options.weights_path = dir.File("missing.txt");
  EXPECT_TRUE(BuildTrellis(archive, dir.File("a.mtr"), options).status().IsNotFound());
  EXPECT_TRUE(BuildTrellis(dir.File("nope.mfs"), dir.File("a.mtr"), SmallOptions(false, 1))
                  .status()
                  .IsNotFound());
}

}  // namespace
}  // namespace motif
