#include "engine/distance/distance_kernel.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/engine/distance/distance_test_util.h"

namespace motif {
namespace {

using testing::CmuSkeleton;
using testing::WeightsOf;

void ExpectKernelMatchesScalar(const DistanceKernel& kernel, const PoseFeatures& features,
                               uint64_t first_query, uint32_t query_count, uint64_t first_candidate,
                               uint32_t candidate_count) {
  FrameBlock queries;
  FrameBlock candidates;
  queries.LoadRange(features, first_query, query_count);
  candidates.LoadRange(features, first_candidate, candidate_count);
  const size_t stride = candidate_count + 3;  // a stride wider than the block is allowed
  std::vector<float> out(query_count * stride, -1.0f);
  kernel.Compute(queries, candidates, out.data(), stride);
  uint64_t mismatches = 0;
  for (uint32_t query_idx = 0; query_idx < query_count; ++query_idx) {
    for (uint32_t candidate_idx = 0; candidate_idx < candidate_count; ++candidate_idx) {
      const float expected =
          PoseDistance(features, first_query + query_idx, first_candidate + candidate_idx);
      const float actual = out[query_idx * stride + candidate_idx];
      ASSERT_NEAR(actual, expected, 1e-5) << query_idx << " " << candidate_idx;
      mismatches += actual != expected;
    }
    for (size_t pad = candidate_count; pad < stride; ++pad) {
      ASSERT_EQ(out[query_idx * stride + pad], -1.0f) << "wrote past the block";
    }
  }
  EXPECT_EQ(mismatches, 0u) << "not bit-identical to PoseDistance";
}

// Both code paths of the kernel: the portable one always, the AVX2 one where the CPU has it.
std::vector<DistanceKernel::Simd> SimdPaths() {
  std::vector<DistanceKernel::Simd> paths = {DistanceKernel::Simd::kPortable};
  if (DistanceKernel::BestSimd() == DistanceKernel::Simd::kAvx2) {
    paths.push_back(DistanceKernel::Simd::kAvx2);
  }
  return paths;
}

// Every pair of the two blocks against PoseDistance, on every code path. The kernel does
// PoseDistance's operations in PoseDistance's order, so the values are expected to be equal
// bit for bit (well within the 1e-5 the trellis needs).
void ExpectMatchesScalar(const PoseFeatures& features, uint64_t first_query, uint32_t query_count,
                         uint64_t first_candidate, uint32_t candidate_count) {
  for (DistanceKernel::Simd simd : SimdPaths()) {
    SCOPED_TRACE(simd == DistanceKernel::Simd::kAvx2 ? "avx2" : "portable");
    const DistanceKernel kernel(features, simd);
    ASSERT_EQ(kernel.simd(), simd);
    ExpectKernelMatchesScalar(kernel, features, first_query, query_count, first_candidate,
                              candidate_count);
  }
}

TEST(DistanceKernel, MatchesScalarPoseDistanceOnRandomFrames) {
  const std::vector<float> rows = testing::RandomRows(600, 31, 1);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 600, 31, WeightsOf(CmuSkeleton()), {0});
  ExpectMatchesScalar(features, 0, 64, 64, 512);
  // Blocks that are not whole tiles, and overlapping ranges (a frame against itself: 0).
  ExpectMatchesScalar(features, 5, 37, 0, 101);
  ExpectMatchesScalar(features, 599, 1, 590, 10);
  ExpectMatchesScalar(features, 100, 17, 3, 1);
}

TEST(DistanceKernel, MatchesScalarPoseDistanceOnSyntheticMotion) {
  const testing::ArchiveRows archive = testing::SynthArchive(3000, 2);
  const PoseFeatures features = archive.Features();
  ASSERT_EQ(features.weighted_joint_count(), 12u);
  // Neighbouring frames of one clip: the smallest distances, where rounding matters most.
  ExpectMatchesScalar(features, 1000, 48, 990, 80);
  ExpectMatchesScalar(features, 0, 33, 1500, 1024);
}

TEST(DistanceKernel, MatchesScalarPoseDistanceForAnyJointCount) {
  for (uint32_t joint_count : {1u, 3u, 4u, 31u}) {
    SCOPED_TRACE(joint_count);
    const std::vector<float> rows = testing::RandomRows(100, joint_count, joint_count);
    std::vector<float> weights(joint_count);
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      weights[joint_idx] = 0.25f + 0.5f * static_cast<float>(joint_idx % 3);
    }
    const PoseFeatures features =
        PoseFeatures::FromRows(rows.data(), 100, joint_count, weights, {0});
    ExpectMatchesScalar(features, 0, 50, 50, 50);
  }
}

TEST(DistanceKernel, IsZeroOnTheDiagonalAndSymmetric) {
  const std::vector<float> rows = testing::RandomRows(70, 31, 3);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 70, 31, WeightsOf(CmuSkeleton()), {0});
  for (DistanceKernel::Simd simd : SimdPaths()) {
    const DistanceKernel kernel(features, simd);
    FrameBlock block;
    block.LoadRange(features, 0, 70);
    std::vector<float> out(70 * 70);
    kernel.Compute(block, block, out.data(), 70);
    for (uint32_t frame_idx = 0; frame_idx < 70; ++frame_idx) {
      EXPECT_EQ(out[frame_idx * 70 + frame_idx], 0.0f);
      for (uint32_t other = 0; other < 70; ++other) {
        ASSERT_EQ(out[frame_idx * 70 + other], out[other * 70 + frame_idx]);
      }
    }
  }
}

TEST(DistanceKernel, PicksAvx2OnlyWhereTheCpuHasIt) {
  const DistanceKernel portable(std::vector<float>{1.0f}, DistanceKernel::Simd::kPortable);
  EXPECT_EQ(portable.simd(), DistanceKernel::Simd::kPortable);
  const DistanceKernel best(std::vector<float>{1.0f});
  EXPECT_EQ(best.simd(), DistanceKernel::BestSimd());
#if defined(__x86_64__)
  EXPECT_EQ(DistanceKernel::BestSimd() == DistanceKernel::Simd::kAvx2,
            static_cast<bool>(__builtin_cpu_supports("avx2")));
#endif
}

TEST(DistanceKernel, LoadFramesGathersTheListedFramesInOrder) {
  const std::vector<float> rows = testing::RandomRows(300, 31, 4);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 300, 31, WeightsOf(CmuSkeleton()), {0});
  const std::vector<uint64_t> listed = {299, 0,  17, 17, 150, 3,  42, 255, 8,  9,
                                        10,  11, 12, 13, 14,  15, 16, 100, 200};
  FrameBlock gathered;
  gathered.LoadFrames(features, listed.data(), static_cast<uint32_t>(listed.size()));
  ASSERT_EQ(gathered.frame_count(), listed.size());
  FrameBlock single;
  for (uint32_t slot = 0; slot < listed.size(); ++slot) {
    single.LoadRange(features, listed[slot], 1);
    for (uint32_t joint_idx = 0; joint_idx < 12; ++joint_idx) {
      for (uint32_t row_idx = 0; row_idx < FrameBlock::kRowsPerJoint; ++row_idx) {
        ASSERT_EQ(gathered.value(slot, joint_idx, row_idx), single.value(0, joint_idx, row_idx));
      }
    }
  }
  const DistanceKernel kernel(features);
  FrameBlock candidates;
  candidates.LoadRange(features, 0, 300);
  std::vector<float> out(listed.size() * 300);
  kernel.Compute(gathered, candidates, out.data(), 300);
  for (uint32_t slot = 0; slot < listed.size(); ++slot) {
    for (uint64_t candidate = 0; candidate < 300; candidate += 7) {
      ASSERT_EQ(out[slot * 300 + candidate], PoseDistance(features, listed[slot], candidate));
    }
  }
}

TEST(DistanceKernel, ComputeRowsWritesOnlyTheRequestedQueries) {
  const std::vector<float> rows = testing::RandomRows(100, 31, 5);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 100, 31, WeightsOf(CmuSkeleton()), {0});
  for (DistanceKernel::Simd simd : SimdPaths()) {
    const DistanceKernel kernel(features, simd);
    FrameBlock queries;
    queries.LoadRange(features, 0, 40);
    FrameBlock candidates;
    candidates.LoadRange(features, 40, 60);
    std::vector<float> out(10 * 60, -1.0f);
    kernel.ComputeRows(queries, 25, 9, candidates, out.data(), 60);
    for (uint32_t query_idx = 0; query_idx < 9; ++query_idx) {
      for (uint32_t candidate_idx = 0; candidate_idx < 60; ++candidate_idx) {
        ASSERT_EQ(out[query_idx * 60 + candidate_idx],
                  PoseDistance(features, 25 + query_idx, 40 + candidate_idx));
      }
    }
    for (uint32_t candidate_idx = 0; candidate_idx < 60; ++candidate_idx) {
      ASSERT_EQ(out[9 * 60 + candidate_idx], -1.0f);
    }
  }
}

TEST(DistanceKernel, ReusedBlocksForgetTheirPreviousFrames) {
  const std::vector<float> rows = testing::RandomRows(200, 31, 6);
  const PoseFeatures features =
      PoseFeatures::FromRows(rows.data(), 200, 31, WeightsOf(CmuSkeleton()), {0});
  const DistanceKernel kernel(features);
  FrameBlock queries;
  FrameBlock candidates;
  queries.LoadRange(features, 0, 100);
  candidates.LoadRange(features, 0, 200);  // large, then smaller: padding must be clean
  candidates.LoadRange(features, 150, 21);
  queries.LoadRange(features, 10, 3);
  std::vector<float> out(3 * 21);
  kernel.Compute(queries, candidates, out.data(), 21);
  for (uint32_t query_idx = 0; query_idx < 3; ++query_idx) {
    for (uint32_t candidate_idx = 0; candidate_idx < 21; ++candidate_idx) {
      ASSERT_EQ(out[query_idx * 21 + candidate_idx],
                PoseDistance(features, 10 + query_idx, 150 + candidate_idx));
    }
  }
}

}  // namespace
}  // namespace motif
