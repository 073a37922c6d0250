// The option table (engine/pipeline/option_table.h): every option reads back its own text, its
// range and choices are enforced with a message naming it, the older Python names reach their
// option, and a default MineOptions resolves to the stage options' own defaults, so the defaults
// are one definition (include/motifmine/defaults.h).
#include "engine/pipeline/option_table.h"

#include <algorithm>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "engine/pipeline/stage_options.h"

namespace motif {
namespace {

using motifmine::MineOptions;

TEST(OptionTable, EveryOptionReadsBackItsOwnTextAndItsDefault) {
  const MineOptions defaults;
  ASSERT_GE(MineOptionSpecs().size(), 37u);
  for (const OptionSpec& spec : MineOptionSpecs()) {
    EXPECT_EQ(spec.info.default_value, spec.get(defaults)) << spec.info.name;
    MineOptions options;
    ASSERT_TRUE(spec.set(&options, spec.info.default_value).ok()) << spec.info.name;
    EXPECT_EQ(spec.get(options), spec.info.default_value) << spec.info.name;
    EXPECT_EQ(spec.info.type, OptionTypeName(spec.type)) << spec.info.name;
    EXPECT_EQ(FindMineOption(spec.info.name), &spec);
  }
  EXPECT_TRUE(CheckMineOptions(defaults).ok());
}

TEST(OptionTable, NamesAreUniqueFlagsAndPythonKeywordsAlike) {
  std::set<std::string> names;
  for (const OptionSpec& spec : MineOptionSpecs()) {
    EXPECT_TRUE(names.insert(spec.info.name).second) << spec.info.name;
    for (const std::string& alias : spec.info.aliases) EXPECT_TRUE(names.insert(alias).second);
    EXPECT_EQ(spec.info.name.find('_'), std::string::npos) << "a flag is dashed";
    std::string keyword = spec.info.name;
    std::replace(keyword.begin(), keyword.end(), '-', '_');
    EXPECT_EQ(FindMineOption(keyword), &spec) << keyword;
  }
}

// The least and greatest values of each numeric option pass, one step beyond each fails with a
// message naming the option; a choice outside its list and text that is not a number fail too.
TEST(OptionTable, RangesAndChoicesAreEnforcedNamingTheOption) {
  for (const OptionSpec& spec : MineOptionSpecs()) {
    MineOptions options;
    const std::string& name = spec.info.name;
    auto refused = [&](const std::string& text) {
      const Status status = spec.set(&options, text);
      EXPECT_TRUE(status.IsInvalidArgument()) << name << " accepted '" << text << "'";
      EXPECT_EQ(status.option(), name);
      EXPECT_EQ(status.message().rfind(name + " ", 0), 0u) << status.message();
    };
    switch (spec.type) {
      case OptionType::kCount:
      case OptionType::kInteger:
        if (spec.info.max < 1e15) {
          EXPECT_TRUE(spec.set(&options, FormatOptionNumber(spec.info.max)).ok()) << name;
          refused(FormatOptionNumber(spec.info.max + 1));
        }
        EXPECT_TRUE(spec.set(&options, FormatOptionNumber(spec.info.min)).ok()) << name;
        refused(FormatOptionNumber(spec.info.min - 1));
        refused("1.5");
        refused("x");
        refused("");
        break;
      case OptionType::kNumber:
        EXPECT_TRUE(spec.set(&options, FormatOptionNumber(spec.info.max)).ok()) << name;
        refused(FormatOptionNumber(spec.info.max * 2 + 1));
        if (spec.info.min_exclusive) {
          refused(FormatOptionNumber(spec.info.min));
        } else {
          EXPECT_TRUE(spec.set(&options, FormatOptionNumber(spec.info.min)).ok()) << name;
        }
        refused(FormatOptionNumber(spec.info.min - 1));
        refused("nan");
        refused("inf");
        refused("x");
        break;
      case OptionType::kChoice:
        for (const std::string& choice : spec.info.choices) {
          EXPECT_TRUE(spec.set(&options, choice).ok()) << name << " " << choice;
        }
        refused("nonsense");
        break;
      case OptionType::kSwitch:
        EXPECT_TRUE(spec.set(&options, "true").ok());
        EXPECT_TRUE(spec.set(&options, "false").ok());
        refused("maybe");
        break;
      case OptionType::kLength:
        EXPECT_TRUE(spec.set(&options, "60").ok());
        EXPECT_TRUE(spec.set(&options, "0.3s").ok());
        refused("0.5");
        refused("0s");
        refused("0");
        refused("-1s");
        break;
      case OptionType::kGroups:
      case OptionType::kRadius:
        EXPECT_TRUE(spec.set(&options, "auto").ok());
        refused("-1");
        refused("nan");
        refused("many");
        break;
      case OptionType::kText:
        EXPECT_TRUE(spec.set(&options, "some/path").ok());
        break;
    }
  }
}

TEST(OptionTable, ValuesLandInTheirFields) {
  MineOptions options;
  ASSERT_TRUE(SetOptionFromText(&options, "kmax", "64").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "min-length", "0.3s").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "eps", "auto").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "groups", "7").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "no-report", "true").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "pause_seconds", "0.25").ok());  // a keyword
  EXPECT_EQ(options.k_max, 64u);
  EXPECT_EQ(options.min_length_frames, 0u);
  EXPECT_EQ(options.min_length_seconds, 0.3);
  EXPECT_EQ(options.eps, 0);
  EXPECT_EQ(options.groups, 7u);
  EXPECT_FALSE(options.write_report);
  EXPECT_EQ(options.pause_seconds, 0.25);
  ASSERT_TRUE(SetOptionFromText(&options, "min-length", "90").ok());
  EXPECT_EQ(options.min_length_frames, 90u);
  EXPECT_EQ(OptionAsText(options, "min-length"), "90");
  EXPECT_EQ(OptionAsText(options, "groups"), "7");
  EXPECT_EQ(OptionAsText(MineOptions{}, "pause-seconds"), "0.2");  // not 0.20000000000000001
  const Status unknown = SetOptionFromText(&options, "no-such", "1");
  EXPECT_TRUE(unknown.IsInvalidArgument());
  EXPECT_EQ(unknown.option(), "no-such");
}

// The keywords Python had before the table: k_max, eps_angle_degrees, min_length_seconds,
// min_length_frames and write_report (the inverse of no-report).
TEST(OptionTable, TheOlderPythonNamesReachTheirOption) {
  MineOptions options;
  ASSERT_TRUE(SetOptionFromText(&options, "k_max", "32").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "eps_angle_degrees", "14").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "min_length_seconds", "0.4").ok());
  ASSERT_TRUE(SetOptionFromText(&options, "write_report", "false").ok());
  EXPECT_EQ(options.k_max, 32u);
  EXPECT_EQ(options.eps_angle_degrees, 14);
  EXPECT_EQ(options.min_length_seconds, 0.4);
  EXPECT_FALSE(options.write_report);
  ASSERT_TRUE(SetOptionFromText(&options, "min_length_frames", "48").ok());
  EXPECT_EQ(options.min_length_frames, 48u);
  const Status bad = SetOptionFromText(&options, "min_length_seconds", "-1");
  EXPECT_EQ(bad.option(), "min_length_seconds");
}

// One definition of every default: a default MineOptions resolves to the stages' own defaults.
TEST(StageOptions, ADefaultRunResolvesToEveryStagesOwnDefaults) {
  const MineOptions defaults;
  const double fps = 120;
  Result<TrellisOptions> trellis = TrellisOptionsFor(defaults, fps);
  ASSERT_TRUE(trellis.ok());
  const TrellisOptions stage_trellis;
  EXPECT_EQ(trellis->eps, stage_trellis.eps);
  EXPECT_EQ(trellis->eps_rule, stage_trellis.eps_rule);
  EXPECT_EQ(trellis->eps_joint_angle_degrees, stage_trellis.eps_joint_angle_degrees);
  EXPECT_EQ(trellis->k_max, stage_trellis.k_max);
  EXPECT_EQ(trellis->search, stage_trellis.search);
  EXPECT_EQ(trellis->seed, stage_trellis.seed);
  EXPECT_EQ(trellis->threads, stage_trellis.threads);
  EXPECT_EQ(trellis->exclusion_frames, 30u);  // half of 0.5 s at 120 fps, resolved once
  LshOptions lsh = trellis->lsh;
  lsh.seed = LshOptions{}.seed;
  EXPECT_EQ(DescribeLshOptions(lsh), DescribeLshOptions(LshOptions{}));
  const PathsOptions paths = PathsOptionsFor(defaults, fps);
  EXPECT_EQ(paths.branch, PathsOptions{}.branch);
  EXPECT_EQ(paths.min_length_frames, MinLengthFrames(PathsOptions{}.min_length_seconds, fps));
  EXPECT_EQ(paths.all_branches, PathsOptions{}.all_branches);
  Result<ClusterOptions> cluster = ClusterOptionsFor(defaults);
  ASSERT_TRUE(cluster.ok());
  const ClusterOptions stage_cluster;
  EXPECT_EQ(cluster->cut.groups, stage_cluster.cut.groups);
  EXPECT_EQ(cluster->cut.max_ncut, stage_cluster.cut.max_ncut);
  EXPECT_EQ(cluster->similarity.min_similarity, stage_cluster.similarity.min_similarity);
  EXPECT_EQ(cluster->max_length_ratio, stage_cluster.max_length_ratio);
  EXPECT_EQ(cluster->warped.enabled, stage_cluster.warped.enabled);
  EXPECT_EQ(cluster->pauses.max_speed, stage_cluster.pauses.max_speed);
  EXPECT_EQ(cluster->pauses.min_seconds, stage_cluster.pauses.min_seconds);
  EXPECT_EQ(cluster->seed, stage_cluster.seed);
  EXPECT_EQ(ReportOptionsFor(defaults).playback_bytes, ReportOptions{}.playback_bytes);
}

// λ and the exclusion radius are resolved once, in frames: seconds at the archive's rate, or
// frames as given (the exclusion half of them, rounded).
TEST(StageOptions, LambdaAndTheExclusionAreResolvedInFrames) {
  MineOptions options;
  EXPECT_EQ(ResolvedMinLengthFrames(options, 30), 15u);
  EXPECT_EQ(ResolvedExclusionFrames(options, 30), 8u);  // 7.5 rounded
  options.min_length_frames = 61;
  EXPECT_EQ(ResolvedMinLengthFrames(options, 120), 61u);
  EXPECT_EQ(ResolvedExclusionFrames(options, 120), 31u);
  options.exclusion_frames = 5;
  EXPECT_EQ(ResolvedExclusionFrames(options, 120), 5u);
}

}  // namespace
}  // namespace motif
