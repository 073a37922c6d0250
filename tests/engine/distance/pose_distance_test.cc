#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "engine/distance/pose_features.h"
#include "formats/motion/pose_frames.h"
#include "tests/engine/distance/distance_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::CmuSkeleton;
using testing::WeightsOf;

PoseFeatures FeaturesOfTakes(const std::vector<Take>& takes) {
  testing::ArchiveRows archive;
  archive.skeleton = takes.front().skeleton;
  for (const Take& take : takes) archive.Append(TakeToClipFrames(take));
  return archive.Features();
}

// sum_k w_k min(|q - p|, |q + p|) in double on the dequantised components: the definition.
double DefinitionDistance(const PoseFeatures& features, uint64_t a, uint64_t b) {
  double total = 0;
  for (uint32_t joint_idx = 0; joint_idx < features.weighted_joint_count(); ++joint_idx) {
    double minus = 0;
    double plus = 0;
    for (int component = 0; component < 4; ++component) {
      const double qa = features.frame(a)[4 * joint_idx + component] / 32767.0;
      const double qb = features.frame(b)[4 * joint_idx + component] / 32767.0;
      minus += (qa - qb) * (qa - qb);
      plus += (qa + qb) * (qa + qb);
    }
    total += features.weights()[joint_idx] * std::sqrt(std::min(minus, plus));
  }
  return total;
}

TEST(PoseDistance, KeepsTheTwelveDefaultWeightedJointsOfTheCmuSkeleton) {
  const Skeleton skeleton = CmuSkeleton();
  const std::vector<float> rows = testing::RandomRows(4, 31, 1);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 4, 31, WeightsOf(skeleton), {0});
  EXPECT_EQ(features.weighted_joint_count(), 12u);
  EXPECT_EQ(features.memory_bytes(), 4u * 12 * 4 * sizeof(int16_t));
  for (uint32_t joint : features.joints()) {
    EXPECT_GT(skeleton.joint(joint).weight, 0) << skeleton.joint(joint).name;
  }
}

TEST(PoseDistance, IsZeroBetweenAFrameAndItself) {
  const std::vector<float> rows = testing::RandomRows(200, 31, 2);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 200, 31, WeightsOf(CmuSkeleton()), {0});
  for (uint64_t frame_idx = 0; frame_idx < 200; ++frame_idx) {
    EXPECT_EQ(PoseDistance(features, frame_idx, frame_idx), 0.0f) << frame_idx;
  }
}

TEST(PoseDistance, IsSymmetric) {
  const std::vector<float> rows = testing::RandomRows(100, 31, 3);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 100, 31, WeightsOf(CmuSkeleton()), {0});
  for (uint64_t a = 0; a < 100; ++a) {
    for (uint64_t b = 0; b < 100; ++b) {
      ASSERT_EQ(PoseDistance(features, a, b), PoseDistance(features, b, a)) << a << " " << b;
    }
  }
}

TEST(PoseDistance, MatchesTheDefinitionWithTheSmallerOfTheTwoChords) {
  const std::vector<float> rows = testing::RandomRows(100, 31, 4);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 100, 31, WeightsOf(CmuSkeleton()), {0});
  double largest = 0;
  for (uint64_t a = 0; a < 100; ++a) {
    for (uint64_t b = 0; b < 100; ++b) {
      const double error =
          std::abs(PoseDistance(features, a, b) - DefinitionDistance(features, a, b));
      largest = std::max(largest, error);
    }
  }
  EXPECT_LT(largest, 1e-5);
}

TEST(PoseDistance, IgnoresTheSignOfAnyJointsQuaternion) {
  const Skeleton skeleton = CmuSkeleton();
  const FrameLayout layout{31};
  std::vector<float> rows = testing::RandomRows(40, 31, 5);
  // Frames 20..39 are frames 0..19 with one (weighted or not) joint's quaternion negated each,
  // frame 39 with every joint negated.
  for (uint64_t frame_idx = 0; frame_idx < 20; ++frame_idx) {
    float* copy = &rows[(20 + frame_idx) * layout.stride()];
    std::copy_n(&rows[frame_idx * layout.stride()], layout.stride(), copy);
    for (uint32_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
      if (joint_idx == frame_idx % 31 || frame_idx == 19) {
        for (int component = 0; component < 4; ++component) {
          copy[layout.quaternion_offset(joint_idx) + component] *= -1.0f;
        }
      }
    }
  }
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 40, 31, WeightsOf(skeleton), {0});
  for (uint64_t frame_idx = 0; frame_idx < 20; ++frame_idx) {
    EXPECT_EQ(PoseDistance(features, frame_idx, 20 + frame_idx), 0.0f) << frame_idx;
    for (uint64_t other = 0; other < 20; ++other) {
      EXPECT_EQ(PoseDistance(features, frame_idx, other),
                PoseDistance(features, 20 + frame_idx, other))
          << frame_idx << " " << other;
      EXPECT_EQ(PoseDistance(features, frame_idx, other),
                PoseDistance(features, 20 + frame_idx, 20 + other))
          << frame_idx << " " << other;
    }
  }
}

TEST(PoseDistance, IgnoresTheDirectionThePerformanceFaces) {
  // Two takes, and the same two turned about the vertical by various angles: the distances
  // between any frames are unchanged (the root's heading is not part of the stored pose).
  const Take first = testing::SmoothTake(240, 11, "first");
  const Take second = testing::SmoothTake(240, 12, "second");
  const PoseFeatures original = FeaturesOfTakes({first, second});
  for (double yaw_degrees : {37.0, 90.0, 180.0, -135.0}) {
    SCOPED_TRACE(yaw_degrees);
    const double yaw = DegreesToRadians(yaw_degrees);
    // The second take turned alone, and both turned (by different angles).
    const PoseFeatures one_turned = FeaturesOfTakes({first, testing::Yawed(second, yaw)});
    const PoseFeatures both_turned =
        FeaturesOfTakes({testing::Yawed(first, -yaw / 3), testing::Yawed(second, yaw)});
    ASSERT_EQ(one_turned.frame_count(), original.frame_count());
    double largest = 0;
    double smallest_distance = 1e9;
    for (uint64_t a = 0; a < original.frame_count(); a += 7) {
      for (uint64_t b = 0; b < original.frame_count(); b += 5) {
        const float expected = PoseDistance(original, a, b);
        largest = std::max<double>(largest, std::abs(PoseDistance(one_turned, a, b) - expected));
        largest = std::max<double>(largest, std::abs(PoseDistance(both_turned, a, b) - expected));
        if (a != b) smallest_distance = std::min<double>(smallest_distance, expected);
      }
    }
    // Only the root's swing is recomputed, to within float rounding and one quantisation step.
    EXPECT_LT(largest, 1e-4);
    EXPECT_GT(smallest_distance, 1e-3) << "the test needs distinct frames";
  }
  // A turn is not a no-op for the rows themselves: the heading column changes.
  const ClipFrames turned = TakeToClipFrames(testing::Yawed(first, 1.0));
  const ClipFrames plain = TakeToClipFrames(first);
  const FrameLayout layout{31};
  EXPECT_NEAR(turned.rows[layout.heading_offset()] - plain.rows[layout.heading_offset()], 1.0,
              1e-5);
}

TEST(PoseDistance, SatisfiesTheTriangleInequality) {
  const testing::ArchiveRows archive = testing::SynthArchive(3000, 21);
  const PoseFeatures features = archive.Features();
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<uint64_t> frame(0, features.frame_count() - 1);
  for (int triple_idx = 0; triple_idx < 20000; ++triple_idx) {
    const uint64_t a = frame(rng);
    const uint64_t b = frame(rng);
    const uint64_t c = frame(rng);
    // Rounding: sqrt of a float difference of values near 2 can be ~5e-4 off per joint when
    // two quaternions nearly coincide.
    ASSERT_LE(PoseDistance(features, a, c),
              PoseDistance(features, a, b) + PoseDistance(features, b, c) + 6e-3)
        << a << " " << b << " " << c;
  }
}

TEST(PoseDistance, LiesBetweenZeroAndSqrtTwoTimesTheWeightSum) {
  const std::vector<float> rows = testing::RandomRows(300, 31, 6);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 300, 31, WeightsOf(CmuSkeleton()), {0});
  const float bound = std::sqrt(2.0f) * 12.0f + 1e-4f;
  for (uint64_t a = 0; a < 300; ++a) {
    for (uint64_t b = 0; b < 300; b += 3) {
      const float distance = PoseDistance(features, a, b);
      ASSERT_GE(distance, 0.0f);
      ASSERT_LE(distance, bound);
    }
  }
}

TEST(PoseDistance, DependsOnlyOnTheWeightedJointsInProportionToTheirWeights) {
  const Skeleton skeleton = CmuSkeleton();
  const FrameLayout layout{31};
  std::vector<float> rows = testing::RandomRows(2, 31, 7);
  const PoseFeatures base = PoseFeatures::FromRows(rows.data(), 2, 31, WeightsOf(skeleton), {0});
  // Change every joint of weight 0 in frame 1: D is unchanged.
  std::vector<float> changed = rows;
  const std::vector<float> other = testing::RandomRows(1, 31, 8);
  for (uint32_t joint_idx = 0; joint_idx < 31; ++joint_idx) {
    if (skeleton.joint(joint_idx).weight > 0) continue;
    for (int component = 0; component < 4; ++component) {
      changed[layout.stride() + layout.quaternion_offset(joint_idx) + component] =
          other[layout.quaternion_offset(joint_idx) + component];
    }
  }
  const PoseFeatures unweighted_changed =
      PoseFeatures::FromRows(changed.data(), 2, 31, WeightsOf(skeleton), {0});
  EXPECT_EQ(PoseDistance(unweighted_changed, 0, 1), PoseDistance(base, 0, 1));
  // Doubling every weight doubles D.
  std::vector<float> doubled = WeightsOf(skeleton);
  for (float& weight : doubled) weight *= 2;
  const PoseFeatures heavier = PoseFeatures::FromRows(rows.data(), 2, 31, doubled, {0});
  EXPECT_FLOAT_EQ(PoseDistance(heavier, 0, 1), 2 * PoseDistance(base, 0, 1));
}

// --- The weights file -----------------------------------------------------------------------

std::string WriteFile(const testing::TempDir& dir, const std::string& text) {
  const std::string path = dir.File("weights.txt");
  std::ofstream(path) << text;
  return path;
}

TEST(PoseDistanceWeights, DefaultsAreTheSkeletonsWeights) {
  const Skeleton skeleton = CmuSkeleton();
  Result<std::vector<float>> weights = LoadDistanceWeights(skeleton, "");
  ASSERT_TRUE(weights.ok()) << weights.status().ToString();
  EXPECT_EQ(*weights, WeightsOf(skeleton));
  EXPECT_EQ(std::count(weights->begin(), weights->end(), 1.0f), 12);
}

TEST(PoseDistanceWeights, FileOverridesTheNamedJointsOnly) {
  const Skeleton skeleton = CmuSkeleton();
  testing::TempDir dir;
  const std::string path = WriteFile(dir,
                                     "# pose distance weights\n"
                                     "\n"
                                     "lfemur 0.5\n"
                                     "  head\t2   # the head counts too\n"
                                     "rtibia 0\n"
                                     "lfemur 0.25\n");  // the last line for a joint wins
  Result<std::vector<float>> weights = LoadDistanceWeights(skeleton, path);
  ASSERT_TRUE(weights.ok()) << weights.status().ToString();
  std::vector<float> expected = WeightsOf(skeleton);
  expected[skeleton.FindJoint("lfemur")] = 0.25f;
  expected[skeleton.FindJoint("head")] = 2.0f;
  expected[skeleton.FindJoint("rtibia")] = 0.0f;
  EXPECT_EQ(*weights, expected);
  // The features follow: head added, rtibia dropped.
  const std::vector<float> rows = testing::RandomRows(1, 31, 9);
  const PoseFeatures features = PoseFeatures::FromRows(rows.data(), 1, 31, *weights, {0});
  EXPECT_EQ(features.weighted_joint_count(), 12u);
}

void ExpectInvalid(const std::string& text, const std::string& where, const std::string& what) {
  const Skeleton skeleton = CmuSkeleton();
  testing::TempDir dir;
  const std::string path = WriteFile(dir, text);
  Result<std::vector<float>> weights = LoadDistanceWeights(skeleton, path);
  ASSERT_FALSE(weights.ok()) << text;
  EXPECT_TRUE(weights.status().IsInvalidArgument()) << weights.status().ToString();
  EXPECT_NE(weights.status().message().find(path + ":" + where), std::string::npos)
      << weights.status().ToString();
  EXPECT_NE(weights.status().message().find(what), std::string::npos)
      << weights.status().ToString();
}

TEST(PoseDistanceWeights, UnknownJointIsAnErrorNamingFileAndLine) {
  ExpectInvalid("lfemur 1\n# fine so far\nnose 1\n", "3:", "'nose'");
  // Names are the archive's canonical ones, matched exactly.
  ExpectInvalid("LeftUpLeg 1\n", "1:", "'LeftUpLeg'");
}

TEST(PoseDistanceWeights, NegativeWeightIsAnError) {
  ExpectInvalid("lfemur 1\nrfemur -0.5\n", "2:", "'-0.5'");
}

TEST(PoseDistanceWeights, GarbageIsAnError) {
  ExpectInvalid("lfemur heavy\n", "1:", "'heavy'");
  ExpectInvalid("lfemur 1.5x\n", "1:", "'1.5x'");
  ExpectInvalid("lfemur nan\n", "1:", "'nan'");
  ExpectInvalid("lfemur inf\n", "1:", "'inf'");
  ExpectInvalid("\nlfemur\n", "2:", "expected");
  ExpectInvalid("lfemur 1 2\n", "1:", "expected");
}

TEST(PoseDistanceWeights, MissingFileIsNotFound) {
  testing::TempDir dir;
  Result<std::vector<float>> weights = LoadDistanceWeights(CmuSkeleton(), dir.File("absent.txt"));
  ASSERT_FALSE(weights.ok());
  EXPECT_TRUE(weights.status().IsNotFound()) << weights.status().ToString();
}

}  // namespace
}  // namespace motif
