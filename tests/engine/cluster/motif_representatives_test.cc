// Motif representatives: the medoid of a distance matrix (least row sum, ties to the lowest
// index), and FindRepresentatives on an archive of held poses whose warped distances are known
// in closed form: every weighted joint turned about x by a constant angle over an instance, so
// d(a, b) = W · 2 sin(|angle_a - angle_b| / 4) (W the sum of the joint weights) along any warp.
#include "engine/cluster/motif_representatives.h"

#include <algorithm>

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cluster/instance_samples.h"
#include "engine/distance/pose_features.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

TEST(MedoidIndexTest, LeastTotalDistanceTiesToTheLowestIndex) {
  // Row sums 5, 3, 6: item 1.
  EXPECT_EQ(MedoidIndex({0, 1, 4,  //
                         1, 0, 2,  //
                         4, 2, 0},
                        3),
            1u);
  // Row sums 3, 3, 4: a tie between 0 and 1 goes to 0; the same with the roles swapped.
  EXPECT_EQ(MedoidIndex({0, 1, 2,  //
                         1, 0, 2,  //
                         2, 2, 0},
                        3),
            0u);
  EXPECT_EQ(MedoidIndex({0, 2, 2,  //
                         2, 0, 1,  //
                         2, 1, 0},
                        3),
            1u);
  EXPECT_EQ(MedoidIndex({0}, 1), 0u);
}

// Held angles (degrees) for frames [40 i, 40 i + 40) of one clip.
constexpr double kAngles[] = {0, 10, 30, 0, 0, 20};
constexpr uint64_t kSpan = 40;

struct HeldArchive {
  std::unique_ptr<FrameFileReader> reader;
  double weight_sum = 0;
};

HeldArchive MakeHeldArchive(const testing::TempDir& dir) {
  SynthOptions options;
  options.frames = 6000;
  options.motifs = 1;
  options.threads = 1;
  auto synthesizer = MotionSynthesizer::Create(options);
  EXPECT_TRUE(synthesizer.ok());
  ClipFrames clip;
  EXPECT_TRUE((*synthesizer)
                  ->Run([&](const ClipFrames& made) {
                    if (clip.rows.empty()) clip = made;
                    return Status::Ok();
                  })
                  .ok());
  const std::string path = dir.File("held.mfs");
  auto writer = FrameFileWriter::Create(path, (*synthesizer)->skeleton(), 120.0);
  EXPECT_TRUE(writer.ok());
  const FrameLayout layout = (*writer)->layout();
  clip.info.name = "held";
  clip.info.frame_count = std::size(kAngles) * kSpan;
  clip.rows.assign(clip.info.frame_count * layout.stride(), 0.0f);
  for (uint64_t frame = 0; frame < clip.info.frame_count; ++frame) {
    const double half = kAngles[frame / kSpan] * std::numbers::pi / 360.0;
    for (uint32_t joint = 0; joint < layout.joint_count; ++joint) {
      float* q = &clip.rows[frame * layout.stride() + layout.quaternion_offset(joint)];
      q[0] = static_cast<float>(std::cos(half));
      q[1] = static_cast<float>(std::sin(half));
    }
  }
  EXPECT_TRUE((*writer)->AppendClip(clip).ok());
  EXPECT_TRUE((*writer)->Commit().ok());
  HeldArchive archive;
  archive.reader = std::move(FrameFileReader::Open(path).value());
  const std::vector<float> weights = LoadDistanceWeights(archive.reader->skeleton(), "").value();
  archive.weight_sum = std::accumulate(weights.begin(), weights.end(), 0.0);
  return archive;
}

TEST(FindRepresentativesTest, TheMedoidByWarpedDistanceAndEachInstancesDistanceToIt) {
  testing::TempDir dir;
  const HeldArchive archive = MakeHeldArchive(dir);
  ASSERT_GT(archive.weight_sum, 0.0);
  auto d = [&](double degrees) {
    return archive.weight_sum * 2 * std::sin(degrees * std::numbers::pi / 180.0 / 4);
  };
  std::vector<MotifInstance> instances;
  for (uint64_t idx = 0; idx < std::size(kAngles); ++idx) {
    instances.push_back({idx * kSpan + 5, idx * kSpan + 35});
  }
  // Motif 0: angles 0, 10, 30 (the middle one is the medoid); motif 1: 0, 0, 20 (two equal
  // medoids: the first listed).
  std::vector<Motif> motifs = {{{0, 1, 2}, 90}, {{3, 4, 5}, 90}};
  ASSERT_TRUE(FindRepresentatives(*archive.reader, instances, 32, 2, &motifs).ok());
  constexpr double kQuantisation = 1e-3;  // int16 features
  EXPECT_EQ(motifs[0].representative, 1u);
  ASSERT_EQ(motifs[0].distances.size(), 3u);
  EXPECT_NEAR(motifs[0].distances[0], d(10), kQuantisation);
  EXPECT_EQ(motifs[0].distances[1], 0.0);
  EXPECT_NEAR(motifs[0].distances[2], d(20), kQuantisation);
  EXPECT_EQ(motifs[1].representative, 0u);
  ASSERT_EQ(motifs[1].distances.size(), 3u);
  EXPECT_EQ(motifs[1].distances[0], 0.0);
  EXPECT_EQ(motifs[1].distances[1], 0.0);  // the same poses
  EXPECT_NEAR(motifs[1].distances[2], d(20), kQuantisation);

  // An instance outside the archive is named as such.
  instances[5] = {230, 400};
  EXPECT_TRUE(FindRepresentatives(*archive.reader, instances, 32, 1, &motifs).IsInvalidArgument());
}


// The samples the cluster stage reads once: each instance's frames sampled as WarpedDistances
// samples them, its held-pose flag, and the representatives measured on them, bit for bit
// those read alone, for one and two threads.
TEST(InstanceSamplesTest, HeldPosesAndRepresentativesAreThoseOfTheInstancesReadAlone) {
  testing::TempDir dir;
  const HeldArchive archive = MakeHeldArchive(dir);
  std::vector<MotifInstance> instances;
  for (uint64_t idx = 0; idx < std::size(kAngles); ++idx) {
    instances.push_back({idx * kSpan + 5, idx * kSpan + 35});
  }
  instances.push_back({kSpan - 10, kSpan + 10});  // 0 then 10 degrees: no held pose
  const float eps = 0.01f;                          // within it: the same pose to quantisation
  Result<InstanceSamples> one = ReadInstanceSamples(*archive.reader, instances, 32, eps, 1);
  Result<InstanceSamples> two = ReadInstanceSamples(*archive.reader, instances, 32, eps, 2);
  ASSERT_TRUE(one.ok()) << one.status().ToString();
  ASSERT_TRUE(two.ok()) << two.status().ToString();
  EXPECT_EQ(one->held, (std::vector<uint8_t>{1, 1, 1, 1, 1, 1, 0}));
  EXPECT_EQ(two->held, one->held);
  // 30 and 20 frames, fewer than 32: every frame is a sample.
  EXPECT_EQ(one->first, (std::vector<uint64_t>{0, 30, 60, 90, 120, 150, 180, 200}));
  EXPECT_EQ(two->first, one->first);
  ASSERT_EQ(one->features.frame_count(), 200u);
  const size_t per_frame = 4 * one->features.weighted_joint_count();
  EXPECT_TRUE(std::equal(one->features.frame(0), one->features.frame(0) + 200 * per_frame,
                         two->features.frame(0)));
  // Sample 0 of instance 6 is frame 30 (angle 0), its last frame 49 (angle 10).
  EXPECT_EQ(PoseDistance(one->features, 180, 0), 0.0f);
  EXPECT_EQ(PoseDistance(one->features, 199, 30), 0.0f);

  std::vector<Motif> alone = {{{0, 1, 2}, 90}, {{3, 4, 5, 6}, 110}};
  std::vector<Motif> shared = alone;
  ASSERT_TRUE(FindRepresentatives(*archive.reader, instances, 32, 2, &alone).ok());
  ASSERT_TRUE(FindRepresentatives(*two, 2, &shared).ok());
  for (size_t motif = 0; motif < alone.size(); ++motif) {
    EXPECT_EQ(shared[motif].representative, alone[motif].representative);
    EXPECT_EQ(shared[motif].distances, alone[motif].distances);
  }
  std::vector<Motif> beyond = {{{0, 7}, 60}};  // no instance 7
  EXPECT_TRUE(FindRepresentatives(*one, 1, &beyond).IsInvalidArgument());
  EXPECT_TRUE(ReadInstanceSamples(*archive.reader, instances, 1, eps, 1).status().IsInvalidArgument());
  instances.push_back({230, 400});  // outside the archive
  EXPECT_TRUE(ReadInstanceSamples(*archive.reader, instances, 32, eps, 2).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
