// FrameResampler and SlerpQuaternion: slerp resampling checked on cases with exact answers
// (constant rotations, constant-rate turns about one axis sampled at 120, 100, 50 and 30 Hz
// and resampled to 24 Hz), shortest-arc handling and sign-flip invariance, and the features
// against the trellis's PoseFeatures, byte for byte.
#include "engine/signature/frame_resampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "engine/distance/pose_features.h"
#include "engine/signature/clip_words.h"
#include "engine/signature/word_distance.h"
#include "formats/motion/quaternion_math.h"
#include "tests/engine/signature/word_test_util.h"

namespace motif {
namespace {

using testing::AngleTo;
using testing::AxisMotion;

void ToFloats(const Eigen::Quaterniond& q, float* out) {
  out[0] = static_cast<float>(q.w());
  out[1] = static_cast<float>(q.x());
  out[2] = static_cast<float>(q.y());
  out[3] = static_cast<float>(q.z());
}

TEST(SlerpQuaternion, HalfwayAboutOneAxis) {
  float a[4];
  float b[4];
  float out[4];
  ToFloats(Eigen::Quaterniond::Identity(), a);
  ToFloats(AxisRotation(Axis::kZ, kPi / 2), b);
  for (double alpha : {0.25, 0.5, 0.75, 1.0}) {
    SlerpQuaternion(a, b, alpha, out);
    EXPECT_LT(AngleTo(out, AxisRotation(Axis::kZ, alpha * kPi / 2)), 1e-6) << alpha;
    EXPECT_NEAR(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3], 1.0, 1e-6);
  }
}

TEST(SlerpQuaternion, AlphaZeroCopiesTheFirstExactly) {
  float a[4];
  float b[4];
  float out[4];
  ToFloats(Eigen::Quaterniond(0.3, -0.5, 0.7, 0.1).normalized(), a);
  ToFloats(Eigen::Quaterniond(-0.2, 0.4, 0.1, 0.9).normalized(), b);
  SlerpQuaternion(a, b, 0.0, out);
  EXPECT_EQ(std::memcmp(a, out, sizeof(a)), 0);
}

TEST(SlerpQuaternion, TakesTheShortestArcWhateverTheSigns) {
  // 0 and 300 degrees about X: the short way is -60 degrees, so halfway is -30 degrees, not 150.
  float a[4];
  float b[4];
  float negated[4];
  float out[4];
  float out_negated[4];
  ToFloats(Eigen::Quaterniond::Identity(), a);
  ToFloats(AxisRotation(Axis::kX, DegreesToRadians(300)), b);  // w < 0: a.b < 0
  for (int component = 0; component < 4; ++component) negated[component] = -b[component];
  for (double alpha : {0.1, 0.5, 0.9}) {
    SlerpQuaternion(a, b, alpha, out);
    SlerpQuaternion(a, negated, alpha, out_negated);
    EXPECT_LT(AngleTo(out, AxisRotation(Axis::kX, DegreesToRadians(-60 * alpha))), 1e-6);
    EXPECT_EQ(std::memcmp(out, out_negated, sizeof(out)), 0) << "-b is the same rotation as b";
    EXPECT_GE(out[0], 0.0f) << "the result stays on a's side";
  }
}

TEST(FrameResampler, ConstantRotationIsExact) {
  AxisMotion motion;
  ClipFrames clip = motion.Clip("c", 2);
  // Make frame 1 the same as frame 0.
  const size_t stride = FrameLayout{motion.joint_count}.stride();
  std::copy(clip.rows.begin(), clip.rows.begin() + stride, clip.rows.begin() + stride);
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  auto resampler =
      FrameResampler::Create(FrameLayout{motion.joint_count}, testing::JointWeightsOf(skeleton));
  ASSERT_TRUE(resampler.ok()) << resampler.status().ToString();
  std::vector<float> out(stride);
  for (double alpha : {0.0, 0.2, 0.5, 0.8, 1.0}) {
    resampler->InterpolateRow(&clip.rows[0], &clip.rows[stride], alpha, out.data());
    EXPECT_EQ(std::memcmp(out.data(), clip.rows.data(), stride * sizeof(float)), 0) << alpha;
  }
}

// A clip turning at constant rates, sampled at `fps` and resampled to 24 Hz: every sample is the
// rotation at its own time, k / 24 s, and the root values are their linear functions of time.
void ExpectExact24HzSamples(double fps, uint32_t flip_every) {
  AxisMotion motion;
  motion.fps = fps;
  const uint64_t frames = static_cast<uint64_t>(4 * fps) + 1;  // 4 s: angles well past 2 pi
  const ClipFrames clip = motion.Clip("c", frames, flip_every);
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  const ClipWords words = testing::WordsOfClip(clip, skeleton);
  EXPECT_EQ(words.grid().sample_count(), 97u) << fps;  // 4 s at 24 Hz, both ends included
  const std::vector<float> resampled = words.ResampledRows();
  const FrameLayout layout{motion.joint_count};
  double worst = 0;
  for (uint64_t sample = 0; sample < words.grid().sample_count(); ++sample) {
    const double seconds = static_cast<double>(sample) / 24.0;
    const float* row = &resampled[sample * layout.stride()];
    for (uint32_t joint = 0; joint < motion.joint_count; ++joint) {
      worst = std::max(
          worst, AngleTo(row + layout.quaternion_offset(joint), motion.Rotation(joint, seconds)));
    }
    EXPECT_NEAR(row[layout.height_offset()], motion.Height(seconds), 1e-6);
    EXPECT_NEAR(row[layout.velocity_offset()], motion.VelocityX(seconds), 1e-6);
    EXPECT_NEAR(row[layout.velocity_offset() + 1], motion.VelocityZ(seconds), 1e-6);
    EXPECT_NEAR(row[layout.heading_offset()], motion.Heading(seconds), 1e-6);
  }
  // float inputs carry 6e-8 per component; the slerp itself is exact for constant-rate turns.
  EXPECT_LT(worst, 1e-6) << "source " << fps << " Hz, flip every " << flip_every;
}

TEST(FrameResampler, TurnAboutOneAxisAt120HzGivesTheExact24HzAngles) {
  ExpectExact24HzSamples(120, 0);
}

TEST(FrameResampler, TurnAboutOneAxisAtOtherRatesGivesTheExact24HzAngles) {
  // 100 Hz: alpha in steps of 1/6; 50 Hz: 1/12; 30 Hz: quarters.
  for (double fps : {100.0, 50.0, 30.0}) ExpectExact24HzSamples(fps, 0);
}

TEST(FrameResampler, StoredSignsDoNotMatter) {
  // Every third source frame stored as -q: the slerp takes the short way regardless.
  for (double fps : {120.0, 100.0, 30.0}) ExpectExact24HzSamples(fps, 3);
}

TEST(FrameResampler, FlippedSignsGiveTheSameWordsUpToSign) {
  const testing::SynthClips synth = testing::MakeSynthClips(3000, 5);
  ASSERT_FALSE(synth.clips.empty());
  const ClipFrames& clip = testing::LongestClip(synth);
  ClipFrames flipped = clip;
  const FrameLayout layout{static_cast<uint32_t>(synth.skeleton.joint_count())};
  // Negate pseudo-random joints of pseudo-random frames.
  uint64_t state = 12345;
  for (uint64_t frame = 0; frame < flipped.info.frame_count; ++frame) {
    for (uint32_t joint = 0; joint < layout.joint_count; ++joint) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      if ((state >> 33) % 3 != 0) continue;
      float* q = &flipped.rows[frame * layout.stride() + layout.quaternion_offset(joint)];
      for (int component = 0; component < 4; ++component) q[component] = -q[component];
    }
  }
  const ClipWords original = testing::WordsOfClip(clip, synth.skeleton);
  const ClipWords negated = testing::WordsOfClip(flipped, synth.skeleton);
  WordBatch a;
  WordBatch b;
  original.AllWords(&a);
  negated.AllWords(&b);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 10u);
  const size_t values = a.feature_values();
  for (size_t word = 0; word < a.size(); ++word) {
    for (uint32_t frame = 0; frame < a.word_frames(); ++frame) {
      for (size_t joint = 0; joint < values / 4; ++joint) {
        const int16_t* p = a.word(word) + frame * values + 4 * joint;
        const int16_t* q = b.word(word) + frame * values + 4 * joint;
        const bool same = p[0] == q[0] && p[1] == q[1] && p[2] == q[2] && p[3] == q[3];
        const bool opposite = p[0] == -q[0] && p[1] == -q[1] && p[2] == -q[2] && p[3] == -q[3];
        ASSERT_TRUE(same || opposite) << "word " << word << " frame " << frame;
      }
    }
  }
  const WordDistance distance(original.resampler().weights(), a.word_frames());
  for (size_t word = 0; word + 5 < a.size(); ++word) {
    EXPECT_EQ(distance.Dtw(a.word(word), b.word(word)), 0.0);
    EXPECT_EQ(distance.Dtw(a.word(word), a.word(word + 5)),
              distance.Dtw(b.word(word), b.word(word + 5)));
  }
}

TEST(FrameResampler, FeaturesAreThoseOfPoseFeatures) {
  const testing::SynthClips synth = testing::MakeSynthClips(3000, 6);
  ASSERT_FALSE(synth.clips.empty());
  const ClipWords words = testing::WordsOfClip(synth.clips[0], synth.skeleton);
  const std::vector<float> resampled = words.ResampledRows();
  const uint64_t samples = words.grid().sample_count();
  const std::vector<float> weights = testing::JointWeightsOf(synth.skeleton);
  const PoseFeatures features = PoseFeatures::FromRows(
      resampled.data(), samples, static_cast<uint32_t>(synth.skeleton.joint_count()), weights, {0});
  const FrameResampler& resampler = words.resampler();
  EXPECT_EQ(resampler.weights(), features.weights());
  EXPECT_EQ(resampler.joints(), features.joints());
  EXPECT_EQ(resampler.weighted_joint_count(), 12u) << "the CMU skeleton's default weights";
  const size_t stride = resampler.layout().stride();
  std::vector<int16_t> from_row(resampler.feature_values());
  std::vector<int16_t> direct(resampler.feature_values());
  const size_t bytes = from_row.size() * sizeof(int16_t);
  const std::vector<float>& source = words.source_rows();
  for (uint64_t sample = 0; sample < samples; ++sample) {
    resampler.RowFeatures(&resampled[sample * stride], from_row.data());
    ASSERT_EQ(std::memcmp(from_row.data(), features.frame(sample), bytes), 0) << sample;
    const SourcePosition position = words.grid().Sample(sample);
    resampler.InterpolateFeatures(&source[position.lower * stride],
                                  &source[position.upper * stride], position.alpha, direct.data());
    ASSERT_EQ(std::memcmp(direct.data(), from_row.data(), bytes), 0) << sample;
  }
  // And the word distance's D is the trellis's D, bit for bit.
  const WordDistance distance(resampler.weights(), 16);
  for (uint64_t sample = 1; sample < samples; sample += 7) {
    const float expected = PoseDistance(features, sample - 1, sample);
    const float actual = distance.FrameDistance(features.frame(sample - 1), features.frame(sample));
    EXPECT_EQ(std::memcmp(&expected, &actual, sizeof(float)), 0) << sample;
  }
}

TEST(FrameResampler, RejectsBadWeights) {
  const FrameLayout layout{3};
  EXPECT_TRUE(FrameResampler::Create(layout, {1, 0, 1}).ok());
  EXPECT_EQ(FrameResampler::Create(layout, {1, 1}).status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(FrameResampler::Create(layout, {0, 0, 0}).status().code(),
            Status::Code::kInvalidArgument);
  EXPECT_EQ(FrameResampler::Create(layout, {1, -1, 1}).status().code(),
            Status::Code::kInvalidArgument);
  EXPECT_EQ(FrameResampler::Create(layout, {1, std::nanf(""), 1}).status().code(),
            Status::Code::kInvalidArgument);
}

}  // namespace
}  // namespace motif
