#include "engine/synth/motion_synthesizer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "common/file_util.h"
#include "engine/synth/cmu_body_model.h"
#include "engine/synth/synth_random.h"
#include "formats/motion/canonical_skeleton.h"
#include "tests/engine/synth/synth_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::CollectedArchive;
using testing::PoseMetric;

// A small archive: 5 minutes at 120 fps in 20-40 s clips, 6 motifs of 0.5-2.5 s.
SynthOptions SmallOptions(uint64_t seed = 7) {
  SynthOptions options;
  options.frames = 120 * 300;
  options.motifs = 6;
  options.seed = seed;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 40;
  options.motif_seconds_min = 0.5;
  options.motif_seconds_max = 2.5;
  options.instances_min = 3;
  options.instances_max = 4;
  return options;
}

std::unique_ptr<MotionSynthesizer> MakeSynthesizer(const SynthOptions& options) {
  auto created = MotionSynthesizer::Create(options);
  EXPECT_TRUE(created.ok()) << created.status().ToString();
  return created.ok() ? std::move(created.value()) : nullptr;
}

// One archive shared by the (read-only) quality tests: generated once.
const CollectedArchive& SharedArchive() {
  static const CollectedArchive* archive = [] {
    auto synthesizer = MakeSynthesizer(SmallOptions());
    return new CollectedArchive(testing::Collect(synthesizer.get()));
  }();
  return *archive;
}

const std::vector<PlantedInstance>& SharedTruth() {
  static const auto* truth = [] {
    auto synthesizer = MakeSynthesizer(SmallOptions());
    return new std::vector<PlantedInstance>(synthesizer->truth());
  }();
  return *truth;
}

TEST(MotionSynthesizer, ProducesExactFrameAndClipCounts) {
  SynthOptions options;
  options.frames = 5003;
  options.motifs = 2;
  options.seed = 3;
  options.clip_seconds_min = 2;
  options.clip_seconds_max = 4;
  options.motif_seconds_min = 0.5;
  options.motif_seconds_max = 0.8;
  options.instances_min = 2;
  options.instances_max = 3;
  auto synthesizer = MakeSynthesizer(options);
  ASSERT_NE(synthesizer, nullptr);
  const CollectedArchive archive = testing::Collect(synthesizer.get());
  EXPECT_EQ(archive.frames, 5003u);
  ASSERT_EQ(archive.clips.size(), synthesizer->clip_count());
  const FrameLayout layout{31};
  for (size_t clip_idx = 0; clip_idx < archive.clips.size(); ++clip_idx) {
    const ClipFrames& clip = archive.clips[clip_idx];
    char name[32];
    std::snprintf(name, sizeof(name), "synth_%06zu", clip_idx);
    EXPECT_EQ(clip.info.name, name);
    EXPECT_EQ(clip.info.source_path, "synthetic");
    EXPECT_EQ(clip.info.fps, 120.0);
    EXPECT_EQ(clip.info.source_fps, 120.0);
    EXPECT_EQ(clip.info.joint_offsets.size(), 31u);
    EXPECT_EQ(clip.info.end_sites.size(), 31u);
    EXPECT_EQ(clip.rows.size(), clip.info.frame_count * layout.stride());
    if (clip_idx + 1 < archive.clips.size()) {
      EXPECT_GE(clip.info.frame_count, 240u);
      EXPECT_LE(clip.info.frame_count, 480u);
    } else {
      EXPECT_GE(clip.info.frame_count, 1u);
      EXPECT_LE(clip.info.frame_count, 480u);
    }
    // The start position is where the root is at frame 0: at standing height above the floor.
    EXPECT_GT(clip.info.start_position[1], 12.0);
    EXPECT_LT(clip.info.start_position[1], 20.0);
  }
}

TEST(MotionSynthesizer, OneFrameArchive) {
  SynthOptions options;
  options.frames = 1;
  options.motifs = 0;
  auto synthesizer = MakeSynthesizer(options);
  ASSERT_NE(synthesizer, nullptr);
  const CollectedArchive archive = testing::Collect(synthesizer.get());
  ASSERT_EQ(archive.clips.size(), 1u);
  EXPECT_EQ(archive.clips[0].info.frame_count, 1u);
  EXPECT_TRUE(synthesizer->truth().empty());
}

TEST(MotionSynthesizer, SkeletonIsCanonicalCmu) {
  auto synthesizer = MakeSynthesizer(SmallOptions());
  ASSERT_NE(synthesizer, nullptr);
  const Skeleton& skeleton = synthesizer->skeleton();
  EXPECT_EQ(skeleton.family(), "cmu31");
  ASSERT_EQ(skeleton.joint_count(), 31u);
  for (size_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
    EXPECT_EQ(skeleton.joint(joint_idx).name, CmuCanonicalJointNames()[joint_idx]);
    EXPECT_EQ(skeleton.joint(joint_idx).parent, CmuCanonicalParents()[joint_idx]);
  }
}

TEST(MotionSynthesizer, SameSeedGivesIdenticalRowsDifferentSeedDiffers) {
  SynthOptions options = SmallOptions(11);
  options.frames = 120 * 60;
  options.clip_seconds_min = 10;
  options.clip_seconds_max = 20;
  options.motifs = 2;
  options.threads = 1;
  const CollectedArchive first = testing::Collect(MakeSynthesizer(options).get());
  options.threads = 2;  // the thread count must not matter
  const CollectedArchive second = testing::Collect(MakeSynthesizer(options).get());
  ASSERT_EQ(first.clips.size(), second.clips.size());
  for (size_t clip_idx = 0; clip_idx < first.clips.size(); ++clip_idx) {
    const ClipFrames& a = first.clips[clip_idx];
    const ClipFrames& b = second.clips[clip_idx];
    EXPECT_EQ(a.info.name, b.info.name);
    EXPECT_EQ(a.info.start_position, b.info.start_position);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    EXPECT_EQ(std::memcmp(a.rows.data(), b.rows.data(), a.rows.size() * sizeof(float)), 0)
        << "clip " << clip_idx << " differs between runs with the same seed";
  }
  options.seed = 12;
  const CollectedArchive other = testing::Collect(MakeSynthesizer(options).get());
  ASSERT_FALSE(other.clips.empty());
  const ClipFrames& a = first.clips[0];
  const ClipFrames& b = other.clips[0];
  const size_t common = std::min(a.rows.size(), b.rows.size());
  EXPECT_NE(std::memcmp(a.rows.data(), b.rows.data(), common * sizeof(float)), 0);
}

TEST(MotionSynthesizer, TruthIsKnownBeforeRunAndValid) {
  SynthOptions options = SmallOptions();
  options.frames = 120 * 60 * 30;  // 30 minutes, planned only
  options.motifs = 40;
  options.instances_min = 3;
  options.instances_max = 6;
  options.motif_seconds_max = 5;
  auto synthesizer = MakeSynthesizer(options);
  ASSERT_NE(synthesizer, nullptr);
  const std::vector<PlantedInstance>& truth = synthesizer->truth();
  ASSERT_FALSE(truth.empty());
  // Clip lengths from a counting run are the same as the plan's.
  std::map<std::string, uint64_t> lengths;
  ASSERT_TRUE(synthesizer
                  ->Run([&](const ClipFrames& clip) {
                    lengths[clip.info.name] = clip.info.frame_count;
                    return Status::Ok();
                  })
                  .ok());
  testing::ExpectValidTruth(truth, lengths, options);
  size_t nonuniform = 0;
  for (const PlantedInstance& instance : truth) nonuniform += instance.nonuniform;
  EXPECT_GT(nonuniform, truth.size() / 4);
  EXPECT_LT(nonuniform, 3 * truth.size() / 4);
}

TEST(MotionSynthesizer, SinkErrorStopsTheRun) {
  auto synthesizer = MakeSynthesizer(SmallOptions());
  ASSERT_NE(synthesizer, nullptr);
  int calls = 0;
  Status status = synthesizer->Run([&](const ClipFrames&) {
    ++calls;
    return calls == 2 ? Status::IOError("disk on fire") : Status::Ok();
  });
  EXPECT_TRUE(status.IsIOError());
  EXPECT_EQ(calls, 2);
}

TEST(MotionSynthesizer, MotionIsSmoothFiniteAndUnit) {
  const CollectedArchive& archive = SharedArchive();
  const double worst = testing::MaxJointStepDegrees(archive, 31);
  RecordProperty("max_joint_step_degrees", std::to_string(worst));
  // At 120 fps: 12 degrees a frame is 1440 degrees per second, beyond the fastest real limbs.
  EXPECT_LT(worst, 12.0);
  const FrameLayout layout{31};
  for (const ClipFrames& clip : archive.clips) {
    for (size_t frame_idx = 1; frame_idx < clip.info.frame_count; ++frame_idx) {
      const float* row = &clip.rows[frame_idx * layout.stride()];
      const float* previous = row - layout.stride();
      ASSERT_LT(std::abs(row[layout.height_offset()] - previous[layout.height_offset()]), 0.3f)
          << clip.info.name << " frame " << frame_idx;
      ASSERT_LT(std::abs(row[layout.heading_offset()] - previous[layout.heading_offset()]),
                DegreesToRadians(4.0))
          << clip.info.name << " frame " << frame_idx;
      const float speed =
          std::hypot(row[layout.velocity_offset()], row[layout.velocity_offset() + 1]);
      ASSERT_LT(speed, 100.0f) << clip.info.name << " frame " << frame_idx;  // 5.6 m/s
      const float previous_speed =
          std::hypot(previous[layout.velocity_offset()], previous[layout.velocity_offset() + 1]);
      ASSERT_LT(std::abs(speed - previous_speed), 3.0f) << clip.info.name << " frame " << frame_idx;
      ASSERT_GT(row[layout.height_offset()], 8.0f);
      ASSERT_LT(row[layout.height_offset()], 24.0f);
    }
  }
}

TEST(MotionSynthesizer, JointsStayWithinTheirLimits) {
  const CollectedArchive& archive = SharedArchive();
  const CmuBodyModel& body = CmuBodyModel::Get();
  const FrameLayout layout{31};
  const int knee = body.skeleton().FindJoint("ltibia");
  double knee_max = -1e9;
  double knee_min = 1e9;
  for (const ClipFrames& clip : archive.clips) {
    for (size_t frame_idx = 0; frame_idx < clip.info.frame_count; ++frame_idx) {
      const float* row = &clip.rows[frame_idx * layout.stride()];
      for (size_t joint_idx = 1; joint_idx < 31; ++joint_idx) {
        const float* q = row + layout.quaternion_offset(joint_idx);
        const std::array<double, 3> angles =
            body.DofAngles(joint_idx, Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
        const Axis axes[3] = {Axis::kX, Axis::kY, Axis::kZ};
        for (int axis = 0; axis < 3; ++axis) {
          const int dof_idx = body.FindDof(body.skeleton().joint(joint_idx).name, axes[axis]);
          if (dof_idx < 0) {
            ASSERT_NEAR(angles[axis], 0.0, 0.5)
                << body.skeleton().joint(joint_idx).name << " has no DOF about axis " << axis;
          } else {
            ASSERT_GE(angles[axis], body.dof(dof_idx).lo_deg - 0.5)
                << body.skeleton().joint(joint_idx).name << " axis " << axis;
            ASSERT_LE(angles[axis], body.dof(dof_idx).hi_deg + 0.5)
                << body.skeleton().joint(joint_idx).name << " axis " << axis;
          }
        }
        if (static_cast<int>(joint_idx) == knee) {
          knee_max = std::max(knee_max, angles[0]);
          knee_min = std::min(knee_min, angles[0]);
        }
      }
    }
  }
  // The knee bends one way only (ASF: -10 to 170), and it does bend.
  EXPECT_GE(knee_min, -10.5);
  EXPECT_GT(knee_max, 60.0);
}

TEST(MotionSynthesizer, IsNotWhiteNoise) {
  const CollectedArchive& archive = SharedArchive();
  const PoseMetric metric(CmuBodyModel::Get().skeleton());
  const size_t stride = metric.layout().stride();
  double consecutive = 0;
  size_t consecutive_count = 0;
  for (const ClipFrames& clip : archive.clips) {
    for (size_t frame_idx = 1; frame_idx < clip.info.frame_count; frame_idx += 7) {
      consecutive +=
          metric.Distance(&clip.rows[frame_idx * stride], &clip.rows[(frame_idx - 1) * stride]);
      ++consecutive_count;
    }
  }
  SynthRandom random(5);
  double random_pairs = 0;
  const size_t pairs = 5000;
  for (size_t pair_idx = 0; pair_idx < pairs; ++pair_idx) {
    const ClipFrames& a = archive.clips[random.UniformInt(0, archive.clips.size() - 1)];
    const ClipFrames& b = archive.clips[random.UniformInt(0, archive.clips.size() - 1)];
    random_pairs += metric.Distance(&a.rows[random.UniformInt(0, a.info.frame_count - 1) * stride],
                                    &b.rows[random.UniformInt(0, b.info.frame_count - 1) * stride]);
  }
  consecutive /= static_cast<double>(consecutive_count);
  random_pairs /= static_cast<double>(pairs);
  RecordProperty("mean_consecutive_distance", std::to_string(consecutive));
  RecordProperty("mean_random_pair_distance", std::to_string(random_pairs));
  EXPECT_LT(consecutive, 0.05 * random_pairs);
  // Poses vary: random pairs are far apart on average (real CMU takes: mean 3.1).
  EXPECT_GT(random_pairs, 1.0);
}

// The ground truth the miner is judged on: two instances of one motif, aligned through their
// time warps (DTW), are much closer than an instance and background of the same length, and
// closer than instances of different motifs.
TEST(MotionSynthesizer, PlantedInstancesReallyRepeat) {
  const CollectedArchive& archive = SharedArchive();
  const std::vector<PlantedInstance>& truth = SharedTruth();
  const PoseMetric metric(CmuBodyModel::Get().skeleton());
  const size_t stride = metric.layout().stride();
  auto rows_of = [&](const PlantedInstance& instance) {
    return &archive.clips[archive.clip_index.at(instance.clip)].rows[instance.start * stride];
  };
  auto frames_of = [](const PlantedInstance& instance) { return instance.end - instance.start; };
  std::vector<double> same;
  std::vector<double> different;
  std::vector<double> background;
  SynthRandom random(9);
  for (size_t a = 0; a < truth.size(); ++a) {
    for (size_t b = a + 1; b < truth.size(); ++b) {
      const double d = metric.AlignedDistance(rows_of(truth[a]), frames_of(truth[a]),
                                              rows_of(truth[b]), frames_of(truth[b]));
      if (truth[a].motif == truth[b].motif) {
        same.push_back(d);
      } else if (random.Bernoulli(0.3)) {
        different.push_back(d);
      }
    }
    // Background windows of the same length, away from every instance and its blends.
    for (int window_idx = 0; window_idx < 3;) {
      const ClipFrames& clip = archive.clips[random.UniformInt(0, archive.clips.size() - 1)];
      const uint64_t frames = frames_of(truth[a]);
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
      background.push_back(
          metric.AlignedDistance(rows_of(truth[a]), frames, &clip.rows[start * stride], frames));
      ++window_idx;
    }
  }
  ASSERT_FALSE(same.empty());
  const double same_max = *std::max_element(same.begin(), same.end());
  const double different_min = *std::min_element(different.begin(), different.end());
  const double background_min = *std::min_element(background.begin(), background.end());
  RecordProperty("same_motif_median", std::to_string(testing::Median(same)));
  RecordProperty("same_motif_max", std::to_string(same_max));
  RecordProperty("different_motif_median", std::to_string(testing::Median(different)));
  RecordProperty("different_motif_min", std::to_string(different_min));
  RecordProperty("background_median", std::to_string(testing::Median(background)));
  RecordProperty("background_min", std::to_string(background_min));
  std::printf(
      "aligned D: same motif median %.3f max %.3f; different motifs median %.3f min %.3f; "
      "background median %.3f min %.3f\n",
      testing::Median(same), same_max, testing::Median(different), different_min,
      testing::Median(background), background_min);
  EXPECT_LT(testing::Median(same), 0.2 * testing::Median(background));
  EXPECT_LT(same_max, background_min);
  EXPECT_LT(same_max, different_min);
}

TEST(MotionSynthesizer, WritesTruthJson) {
  testing::TempDir dir;
  auto synthesizer = MakeSynthesizer(SmallOptions());
  ASSERT_NE(synthesizer, nullptr);
  const std::string path = dir.File("out.truth.json");
  ASSERT_TRUE(WriteTruthJson(path, "out.mfs", 36000, SmallOptions(), synthesizer->truth()).ok());
  Result<std::string> text = ReadFileToString(path);
  ASSERT_TRUE(text.ok());
  const nlohmann::json doc = nlohmann::json::parse(text.value());
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["archive"], "out.mfs");
  EXPECT_EQ(doc["frames"], 36000);
  EXPECT_EQ(doc["seed"], 7);
  EXPECT_EQ(doc["motifs"], 6);
  const auto& instances = doc["instances"];
  ASSERT_EQ(instances.size(), synthesizer->truth().size());
  for (size_t idx = 0; idx < instances.size(); ++idx) {
    const PlantedInstance& expected = synthesizer->truth()[idx];
    EXPECT_EQ(instances[idx]["clip"], expected.clip);
    EXPECT_EQ(instances[idx]["start"], expected.start);
    EXPECT_EQ(instances[idx]["end"], expected.end);
    EXPECT_EQ(instances[idx]["motif"], expected.motif);
    EXPECT_EQ(instances[idx]["warp"].get<double>(), expected.warp);
    EXPECT_EQ(instances[idx]["nonuniform"], expected.nonuniform);
  }
  // Empty truth is still valid JSON; a path in a missing folder is an IO error.
  ASSERT_TRUE(WriteTruthJson(path, "x", 1, SynthOptions(), {}).ok());
  EXPECT_TRUE(nlohmann::json::parse(ReadFileToString(path).value())["instances"].empty());
  EXPECT_FALSE(WriteTruthJson(dir.File("missing/t.json"), "x", 1, SynthOptions(), {}).ok());
}

TEST(MotionSynthesizer, RejectsImpossibleOptionsNamingTheOption) {
  struct Case {
    const char* option;
    std::function<void(SynthOptions*)> change;
  };
  const std::vector<Case> cases = {
      {"frames", [](SynthOptions* o) { o->frames = 0; }},
      {"fps", [](SynthOptions* o) { o->fps = 0; }},
      {"fps", [](SynthOptions* o) { o->fps = -120; }},
      {"clip_seconds_min", [](SynthOptions* o) { o->clip_seconds_min = 70; }},
      {"clip_seconds_min", [](SynthOptions* o) { o->clip_seconds_min = 0; }},
      {"motif_seconds_min", [](SynthOptions* o) { o->motif_seconds_min = 6; }},
      {"motif_seconds_min", [](SynthOptions* o) { o->motif_seconds_min = 0; }},
      {"instances_min", [](SynthOptions* o) { o->instances_min = 7; }},
      {"instances_min", [](SynthOptions* o) { o->instances_min = 1; }},
      {"warp_min", [](SynthOptions* o) { o->warp_min = 0; }},
      {"warp_min", [](SynthOptions* o) { o->warp_min = 1.5; }},
      {"noise_degrees", [](SynthOptions* o) { o->noise_degrees = -1; }},
      {"motifs", [](SynthOptions* o) { o->motifs = 200; }},
      {"motifs",
       [](SynthOptions* o) {  // instances longer than any clip
         o->frames = 120 * 3600;
         o->motifs = 2;
         o->clip_seconds_min = o->clip_seconds_max = 3;
         o->motif_seconds_min = 4;
       }},
      {"segment_seconds_min", [](SynthOptions* o) { o->segment_seconds_min = 0; }},
  };
  for (const Case& test_case : cases) {
    SynthOptions options;
    test_case.change(&options);
    auto created = MotionSynthesizer::Create(options);
    ASSERT_FALSE(created.ok()) << test_case.option;
    EXPECT_TRUE(created.status().IsInvalidArgument()) << created.status().ToString();
    EXPECT_NE(created.status().message().find(test_case.option), std::string::npos)
        << created.status().message();
  }
  SynthOptions no_motifs;
  no_motifs.motifs = 0;
  no_motifs.frames = 10;
  EXPECT_TRUE(MotionSynthesizer::Create(no_motifs).ok());
}

}  // namespace
}  // namespace motif
