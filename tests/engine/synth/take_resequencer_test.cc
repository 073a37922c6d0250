// Re-sequencing mode: MotionSynthesizer::CreateFromTakes on small source takes built in the test
// (procedural clips turned back into takes), and on real CMU takes when they are present.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/synth_random.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"
#include "tests/engine/synth/synth_test_util.h"
#include "tests/testing/mocap_data.h"

namespace motif {
namespace {

using testing::CollectedArchive;
using testing::PoseMetric;

// About two minutes of source motion in 20-30 s takes, as real takes would arrive: canonical
// CMU skeleton, 120 fps, absolute root positions.
std::vector<Take> SourceTakes(uint64_t seed = 21) {
  SynthOptions options;
  options.frames = 120 * 125;
  options.motifs = 0;
  options.seed = seed;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 30;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok());
  std::vector<Take> takes;
  Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    Take take = ClipFramesToTake((*synthesizer)->skeleton(), clip.info, clip.rows.data(),
                                 clip.info.frame_count);
    take.name = "source_" + std::to_string(takes.size());
    take.source_path = take.name + ".bvh";
    takes.push_back(std::move(take));
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok());
  return takes;
}

SynthOptions ResequenceOptions(uint64_t seed = 5) {
  SynthOptions options;
  options.frames = 120 * 150;
  options.motifs = 3;
  options.seed = seed;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 40;
  options.motif_seconds_min = 0.5;
  options.motif_seconds_max = 2.0;
  options.instances_min = 3;
  options.instances_max = 4;
  return options;
}

std::unique_ptr<MotionSynthesizer> Resequencer(const SynthOptions& options,
                                               std::vector<Take> sources) {
  auto created = MotionSynthesizer::CreateFromTakes(options, std::move(sources));
  EXPECT_TRUE(created.ok()) << created.status().ToString();
  return created.ok() ? std::move(created.value()) : nullptr;
}

// Same-motif pairs vs instance-vs-background, as in the procedural test; returns medians.
struct RepeatStats {
  std::vector<double> same;
  std::vector<double> background;
};

RepeatStats MeasureRepeats(const CollectedArchive& archive,
                           const std::vector<PlantedInstance>& truth, const Skeleton& skeleton) {
  const PoseMetric metric(skeleton);
  const size_t stride = metric.layout().stride();
  auto rows_of = [&](const PlantedInstance& instance) {
    return &archive.clips[archive.clip_index.at(instance.clip)].rows[instance.start * stride];
  };
  RepeatStats stats;
  SynthRandom random(17);
  for (size_t a = 0; a < truth.size(); ++a) {
    const uint64_t frames = truth[a].end - truth[a].start;
    for (size_t b = a + 1; b < truth.size(); ++b) {
      if (truth[a].motif != truth[b].motif) continue;
      stats.same.push_back(metric.AlignedDistance(rows_of(truth[a]), frames, rows_of(truth[b]),
                                                  truth[b].end - truth[b].start));
    }
    for (int window_idx = 0; window_idx < 3;) {
      const ClipFrames& clip = archive.clips[random.UniformInt(0, archive.clips.size() - 1)];
      if (clip.info.frame_count <= frames) continue;
      const uint64_t start = random.UniformInt(0, clip.info.frame_count - frames);
      bool clear = true;
      for (const PlantedInstance& instance : truth) {
        if (instance.clip == clip.info.name && start < instance.end + 60 &&
            instance.start < start + frames + 60) {
          clear = false;
        }
      }
      if (!clear) continue;
      stats.background.push_back(
          metric.AlignedDistance(rows_of(truth[a]), frames, &clip.rows[start * stride], frames));
      ++window_idx;
    }
  }
  return stats;
}

TEST(TakeResequencer, BuildsAnArchiveOfExactSizeFromSourceTakes) {
  std::vector<Take> sources = SourceTakes();
  ASSERT_GE(sources.size(), 4u);
  const Skeleton source_skeleton = sources[0].skeleton;
  const SynthOptions options = ResequenceOptions();
  auto synthesizer = Resequencer(options, std::move(sources));
  ASSERT_NE(synthesizer, nullptr);
  EXPECT_TRUE(synthesizer->skeleton().SameHierarchy(source_skeleton));
  const std::vector<PlantedInstance> truth_before = synthesizer->truth();
  const CollectedArchive archive = testing::Collect(synthesizer.get());
  EXPECT_EQ(archive.frames, options.frames);
  EXPECT_EQ(archive.clips.size(), synthesizer->clip_count());
  for (size_t clip_idx = 0; clip_idx < archive.clips.size(); ++clip_idx) {
    char name[32];
    std::snprintf(name, sizeof(name), "synth_%06zu", clip_idx);
    EXPECT_EQ(archive.clips[clip_idx].info.name, name);
    EXPECT_EQ(archive.clips[clip_idx].info.source_path, "synthetic");
    EXPECT_EQ(archive.clips[clip_idx].info.joint_offsets.size(), 31u);
  }
  ASSERT_EQ(truth_before.size(), synthesizer->truth().size());
  testing::ExpectValidTruth(synthesizer->truth(), testing::ClipLengths(archive), options);
  // Segment joins and instance blends are smooth: no joint jumps between frames.
  const double worst = testing::MaxJointStepDegrees(archive, 31);
  RecordProperty("max_joint_step_degrees", std::to_string(worst));
  EXPECT_LT(worst, 12.0);
  const FrameLayout layout{31};
  for (const ClipFrames& clip : archive.clips) {
    for (size_t frame_idx = 1; frame_idx < clip.info.frame_count; ++frame_idx) {
      const float* row = &clip.rows[frame_idx * layout.stride()];
      const float* previous = row - layout.stride();
      // (The sources' vertical speed, sped up by at most 1 / source_warp_min.)
      ASSERT_LT(std::abs(row[layout.height_offset()] - previous[layout.height_offset()]), 0.4f)
          << clip.info.name << " frame " << frame_idx;
      ASSERT_LT(std::abs(row[layout.heading_offset()] - previous[layout.heading_offset()]),
                DegreesToRadians(4.0))
          << clip.info.name << " frame " << frame_idx;
    }
  }
}

TEST(TakeResequencer, IsDeterministic) {
  SynthOptions options = ResequenceOptions(8);
  options.frames = 120 * 60;
  options.motifs = 2;
  options.threads = 1;
  const CollectedArchive first = testing::Collect(Resequencer(options, SourceTakes()).get());
  options.threads = 2;
  const CollectedArchive second = testing::Collect(Resequencer(options, SourceTakes()).get());
  ASSERT_EQ(first.clips.size(), second.clips.size());
  for (size_t clip_idx = 0; clip_idx < first.clips.size(); ++clip_idx) {
    ASSERT_EQ(first.clips[clip_idx].rows.size(), second.clips[clip_idx].rows.size());
    EXPECT_EQ(std::memcmp(first.clips[clip_idx].rows.data(), second.clips[clip_idx].rows.data(),
                          first.clips[clip_idx].rows.size() * sizeof(float)),
              0);
  }
  options.seed = 9;
  const CollectedArchive other = testing::Collect(Resequencer(options, SourceTakes()).get());
  EXPECT_NE(
      std::memcmp(first.clips[0].rows.data(), other.clips[0].rows.data(),
                  std::min(first.clips[0].rows.size(), other.clips[0].rows.size()) * sizeof(float)),
      0);
}

TEST(TakeResequencer, PlantedInstancesRepeat) {
  std::vector<Take> sources = SourceTakes();
  const SynthOptions options = ResequenceOptions();
  auto synthesizer = Resequencer(options, std::move(sources));
  ASSERT_NE(synthesizer, nullptr);
  const CollectedArchive archive = testing::Collect(synthesizer.get());
  const RepeatStats stats = MeasureRepeats(archive, synthesizer->truth(), synthesizer->skeleton());
  ASSERT_FALSE(stats.same.empty());
  const double same_max = *std::max_element(stats.same.begin(), stats.same.end());
  std::printf("re-sequenced: same motif median %.3f max %.3f; background median %.3f min %.3f\n",
              testing::Median(stats.same), same_max, testing::Median(stats.background),
              *std::min_element(stats.background.begin(), stats.background.end()));
  EXPECT_LT(testing::Median(stats.same), 0.2 * testing::Median(stats.background));
  EXPECT_LT(same_max, 0.5 * testing::Median(stats.background));
}

TEST(TakeResequencer, RejectsUnusableSources) {
  const SynthOptions options = ResequenceOptions();
  {
    auto created = MotionSynthesizer::CreateFromTakes(options, {});
    ASSERT_FALSE(created.ok());
    EXPECT_TRUE(created.status().IsInvalidArgument());
    EXPECT_NE(created.status().message().find("no source takes"), std::string::npos);
  }
  {  // Mixed skeleton families.
    std::vector<Take> sources = SourceTakes();
    Take custom;
    custom.name = "custom";
    custom.source_path = "custom.bvh";
    std::vector<Joint> joints(2);
    joints[0].name = "hip";
    joints[1].name = "knee";
    joints[1].parent = 0;
    custom.skeleton = Skeleton("custom", joints);
    for (int frame_idx = 0; frame_idx < 500; ++frame_idx) {
      custom.root_positions.emplace_back(0, 10, 0);
      custom.rotations.push_back(Eigen::Quaterniond::Identity());
      custom.rotations.push_back(Eigen::Quaterniond::Identity());
    }
    sources.push_back(custom);
    auto created = MotionSynthesizer::CreateFromTakes(options, std::move(sources));
    ASSERT_FALSE(created.ok());
    EXPECT_TRUE(created.status().IsInvalidArgument());
    EXPECT_NE(created.status().message().find("custom.bvh"), std::string::npos)
        << created.status().message();
  }
  {  // Another frame rate.
    std::vector<Take> sources = SourceTakes();
    sources[1].fps = 60;
    auto created = MotionSynthesizer::CreateFromTakes(options, std::move(sources));
    ASSERT_FALSE(created.ok());
    EXPECT_NE(created.status().message().find("fps"), std::string::npos)
        << created.status().message();
  }
  {  // Too short for a motif.
    std::vector<Take> sources = SourceTakes();
    for (Take& take : sources) {
      take.root_positions.resize(100);
      take.rotations.resize(100 * take.joint_count());
    }
    auto created = MotionSynthesizer::CreateFromTakes(options, std::move(sources));
    ASSERT_FALSE(created.ok());
    EXPECT_TRUE(created.status().IsInvalidArgument());
    EXPECT_NE(created.status().message().find("too short"), std::string::npos)
        << created.status().message();
  }
  {  // Bad options are reported before the sources are looked at.
    SynthOptions bad = options;
    bad.frames = 0;
    auto created = MotionSynthesizer::CreateFromTakes(bad, SourceTakes());
    ASSERT_FALSE(created.ok());
    EXPECT_NE(created.status().message().find("frames"), std::string::npos);
  }
}

// Real CMU takes (the importer's output, resampled to the archive's rate) re-sequenced into an
// archive: exact size, smooth joins, planted motifs that repeat.
TEST(TakeResequencer, ResequencesRealCmuTakes) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string dir = ::motif::testing::MocapDir() + "/bvh";
  std::vector<Take> sources;
  for (const char* name : {"05_02", "05_05", "07_01", "09_01", "02_05"}) {
    const std::string path = dir + "/" + name + ".bvh";
    if (!std::filesystem::exists(path)) continue;
    TakeSource source;
    source.format = TakeFormat::kBvh;
    source.path = path;
    Result<Take> take = ImportTake(source, ImportOptions());
    ASSERT_TRUE(take.ok()) << take.status().ToString();
    if (!sources.empty()) {
      ASSERT_TRUE(ConformToSkeleton(sources[0].skeleton, &*take).ok());
    }
    sources.push_back(ResampleTake(*take, 120.0));
  }
  if (sources.size() < 2) GTEST_SKIP() << "the chosen BVH takes are not in " << dir;
  EXPECT_EQ(sources[0].skeleton.family(), "cmu31");
  const Skeleton skeleton = sources[0].skeleton;
  SynthOptions options = ResequenceOptions(3);
  options.frames = 120 * 240;
  auto synthesizer = Resequencer(options, std::move(sources));
  ASSERT_NE(synthesizer, nullptr);
  EXPECT_TRUE(synthesizer->skeleton().SameHierarchy(skeleton));
  const CollectedArchive archive = testing::Collect(synthesizer.get());
  EXPECT_EQ(archive.frames, options.frames);
  testing::ExpectValidTruth(synthesizer->truth(), testing::ClipLengths(archive), options);
  const double worst = testing::MaxJointStepDegrees(archive, 31);
  RecordProperty("max_joint_step_degrees", std::to_string(worst));
  // Real capture has fast moments (toes flick by 40 degrees in a frame), and 05_05 has a
  // 180-degree flip of the right hip at frame 348, which the re-sequencer must leave out.
  EXPECT_LT(worst, 50.0);
  const RepeatStats stats = MeasureRepeats(archive, synthesizer->truth(), synthesizer->skeleton());
  ASSERT_FALSE(stats.same.empty());
  std::printf(
      "real re-sequenced: same motif median %.3f max %.3f; background median %.3f min "
      "%.3f; max joint step %.1f deg\n",
      testing::Median(stats.same), *std::max_element(stats.same.begin(), stats.same.end()),
      testing::Median(stats.background),
      *std::min_element(stats.background.begin(), stats.background.end()), worst);
  EXPECT_LT(testing::Median(stats.same), 0.3 * testing::Median(stats.background));
}

}  // namespace
}  // namespace motif
