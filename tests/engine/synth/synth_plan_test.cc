#include "engine/synth/synth_plan.h"

#include <gtest/gtest.h>

#include <chrono>
#include <map>

#include "tests/engine/synth/synth_test_util.h"

namespace motif {
namespace {

TEST(SynthPlan, ClipsAddUpAndTheLastTakesTheRemainder) {
  SynthOptions options;
  options.frames = 1'000'003;
  options.motifs = 0;
  options.clip_seconds_min = 20;
  options.clip_seconds_max = 60;
  Result<SynthPlan> plan = SynthPlan::Create(options);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  uint64_t total = 0;
  const std::vector<uint64_t>& clips = plan->clip_frames();
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    total += clips[clip_idx];
    if (clip_idx + 1 < clips.size()) {
      EXPECT_GE(clips[clip_idx], 2400u);
      EXPECT_LE(clips[clip_idx], 7200u);
    }
  }
  EXPECT_EQ(total, options.frames);
  EXPECT_LE(clips.back(), 7200u);
  EXPECT_TRUE(plan->truth().empty());
  EXPECT_EQ(SynthPlan::ClipName(0), "synth_000000");
  EXPECT_EQ(SynthPlan::ClipName(123), "synth_000123");
  EXPECT_EQ(SynthPlan::ClipName(1234567), "synth_1234567");
}

// 100 million frames, 15,000 motifs (about 67,000 instances): the plan is O(clips + instances)
// and placement O(instances log clips), so it takes well under a second or two.
TEST(SynthPlan, PlacesTensOfThousandsOfInstancesInAHugeArchive) {
  SynthOptions options;
  options.frames = 100'000'000;
  options.motifs = 15'000;
  options.seed = 99;
  const auto begin = std::chrono::steady_clock::now();
  Result<SynthPlan> plan = SynthPlan::Create(options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  RecordProperty("plan_seconds", std::to_string(seconds));
  RecordProperty("instances", std::to_string(plan->truth().size()));
  EXPECT_LT(seconds, 10.0);
  EXPECT_GT(plan->truth().size(), 50'000u);
  std::map<std::string, uint64_t> lengths;
  for (uint64_t clip_idx = 0; clip_idx < plan->clip_count(); ++clip_idx) {
    lengths[SynthPlan::ClipName(clip_idx)] = plan->clip_frames()[clip_idx];
  }
  testing::ExpectValidTruth(plan->truth(), lengths, options);
  // Per-clip ranges agree with the instances' clips.
  size_t seen = 0;
  for (uint64_t clip_idx = 0; clip_idx < plan->clip_count(); ++clip_idx) {
    size_t first = 0;
    size_t count = 0;
    plan->ClipInstances(clip_idx, &first, &count);
    EXPECT_EQ(first, seen);
    for (size_t idx = first; idx < first + count; ++idx) {
      ASSERT_EQ(plan->instances()[idx].clip_idx, clip_idx);
    }
    seen += count;
  }
  EXPECT_EQ(seen, plan->instances().size());
}

TEST(SynthPlan, TimeMapsAreMonotoneAndSpanTheMotif) {
  SynthOptions options;
  options.frames = 120 * 3600;
  options.motifs = 30;
  Result<SynthPlan> plan = SynthPlan::Create(options);
  ASSERT_TRUE(plan.ok());
  size_t nonuniform = 0;
  for (const PlannedInstance& instance : plan->instances()) {
    const double frames = static_cast<double>(instance.frames());
    const double last = static_cast<double>(instance.motif_frames - 1);
    EXPECT_NEAR(instance.MotifTime(0), 0.0, 1e-9);
    EXPECT_NEAR(instance.MotifTime(frames - 1), last, 1e-9);
    double previous = instance.MotifTime(-10);
    double largest_shift = 0;
    for (double offset = -9; offset < frames + 10; offset += 1) {
      const double time = instance.MotifTime(offset);
      ASSERT_GT(time, previous) << "the time map must be strictly increasing";
      previous = time;
      if (offset >= 0 && offset < frames) {
        largest_shift = std::max(largest_shift, std::abs(time - last * offset / (frames - 1)));
      }
    }
    if (instance.truth.nonuniform) {
      ++nonuniform;
      EXPECT_GT(largest_shift, 0.03 * last) << "a non-uniform warp must really bend time";
    } else {
      EXPECT_LT(largest_shift, 1e-6);
    }
  }
  EXPECT_GT(nonuniform, 0u);
}

TEST(SynthPlan, SameSeedSamePlan) {
  SynthOptions options;
  options.frames = 120 * 3600;
  options.motifs = 25;
  options.seed = 5;
  Result<SynthPlan> a = SynthPlan::Create(options);
  Result<SynthPlan> b = SynthPlan::Create(options);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->truth().size(), b->truth().size());
  for (size_t idx = 0; idx < a->truth().size(); ++idx) {
    EXPECT_EQ(a->truth()[idx].clip, b->truth()[idx].clip);
    EXPECT_EQ(a->truth()[idx].start, b->truth()[idx].start);
    EXPECT_EQ(a->truth()[idx].warp, b->truth()[idx].warp);
  }
  options.seed = 6;
  Result<SynthPlan> c = SynthPlan::Create(options);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(a->clip_frames(), c->clip_frames());
}

}  // namespace
}  // namespace motif
