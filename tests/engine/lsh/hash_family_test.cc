// HashFamily (sign-invariant embedding, orthonormal projections, determinism) and QueryDistance
// (bit-identical to PoseDistance).
#include "engine/lsh/hash_family.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "common/split_mix64.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/query_distance.h"

namespace motif {
namespace {

constexpr uint32_t kJoints = 12;

// Random unit quaternions for `frames` frames of kJoints joints, all weighted (weights 0.5..1.5).
PoseFeatures RandomFeatures(uint64_t frames, uint64_t seed,
                            std::vector<float>* rows_out = nullptr) {
  SplitMix64 random(seed);
  const FrameLayout layout{kJoints};
  std::vector<float> rows(frames * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < frames; ++frame_idx) {
    for (uint32_t joint_idx = 0; joint_idx < kJoints; ++joint_idx) {
      double q[4];
      double norm = 0;
      for (double& value : q) {
        value = random.Gaussian();
        norm += value * value;
      }
      for (int component = 0; component < 4; ++component) {
        rows[frame_idx * layout.stride() + 4 * joint_idx + component] =
            static_cast<float>(q[component] / std::sqrt(norm));
      }
    }
  }
  std::vector<float> weights(kJoints);
  for (uint32_t joint_idx = 0; joint_idx < kJoints; ++joint_idx) {
    weights[joint_idx] = 0.5f + static_cast<float>(joint_idx) / kJoints;
  }
  if (rows_out) *rows_out = rows;
  return PoseFeatures::FromRows(rows.data(), frames, kJoints, weights, {0});
}

std::vector<float> Embedding(const HashFamily& family, const PoseFeatures& features,
                             uint64_t frame) {
  std::vector<float> embedding(family.embedding_dims());
  family.Embed(features.frame(frame), embedding.data());
  return embedding;
}

TEST(LshHashFamily, EmbeddingIgnoresQuaternionSigns) {
  std::vector<float> rows;
  const PoseFeatures features = RandomFeatures(8, 1, &rows);
  std::vector<float> flipped = rows;
  const FrameLayout layout{kJoints};
  for (uint32_t joint_idx = 0; joint_idx < kJoints; joint_idx += 2) {
    for (int component = 0; component < 4; ++component) {
      float& value = flipped[3 * layout.stride() + 4 * joint_idx + component];
      value = -value;
    }
  }
  const PoseFeatures flipped_features =
      PoseFeatures::FromRows(flipped.data(), 8, kJoints, features.weights(), {0});
  const HashFamily family = HashFamily::Draw(features.weights(), 2, 8, 0.1f, 5);
  EXPECT_EQ(Embedding(family, features, 3), Embedding(family, flipped_features, 3));
}

TEST(LshHashFamily, EmbeddingDistanceBracketsPoseDistance) {
  const PoseFeatures features = RandomFeatures(200, 2);
  const HashFamily family = HashFamily::Draw(features.weights(), 1, 4, 0.1f, 5);
  double max_weight_sum = 0;
  for (float weight : features.weights()) max_weight_sum += weight;
  for (uint64_t a = 0; a < 200; a += 3) {
    for (uint64_t b = 1; b < 200; b += 7) {
      const std::vector<float> ea = Embedding(family, features, a);
      const std::vector<float> eb = Embedding(family, features, b);
      double squared = 0;
      for (size_t dim = 0; dim < ea.size(); ++dim)
        squared += (ea[dim] - eb[dim]) * (ea[dim] - eb[dim]);
      const double l2 = std::sqrt(squared);
      const double pose = PoseDistance(features, a, b);
      // |e_a - e_b| <= D <= sqrt(2) * sum_k |De_k| <= sqrt(2 J) |e_a - e_b| (quantisation slack)
      EXPECT_LE(l2, pose + 1e-3) << a << " " << b;
      EXPECT_LE(pose, std::sqrt(2.0 * kJoints) * l2 + 1e-3) << a << " " << b;
    }
  }
}

TEST(LshHashFamily, ProjectionsOfATableAreOrthonormal) {
  const PoseFeatures features = RandomFeatures(2, 3);
  const float width = 0.25f;
  const uint32_t hashes = 10;
  const HashFamily family = HashFamily::Draw(features.weights(), 3, hashes, width, 9);
  const uint32_t dims = family.embedding_dims();
  const uint32_t rows = family.table_count() * (hashes + 1);
  // Project is affine: the offsets, then one column of the matrix per unit vector.
  std::vector<float> zero(dims, 0.0f);
  std::vector<float> offsets(rows);
  family.Project(zero.data(), offsets.data());
  std::vector<std::vector<double>> matrix(rows, std::vector<double>(dims));
  for (uint32_t dim = 0; dim < dims; ++dim) {
    std::vector<float> unit(dims, 0.0f);
    unit[dim] = 1.0f;
    std::vector<float> projected(rows);
    family.Project(unit.data(), projected.data());
    for (uint32_t row = 0; row < rows; ++row) matrix[row][dim] = projected[row] - offsets[row];
  }
  for (uint32_t table_idx = 0; table_idx < family.table_count(); ++table_idx) {
    for (uint32_t a = 0; a <= hashes; ++a) {
      // Hash rows are scaled by 1 / w, the sort row is unit.
      const double scale_a = a < hashes ? width : 1.0;
      EXPECT_GE(offsets[table_idx * (hashes + 1) + a], 0.0f);
      EXPECT_LT(offsets[table_idx * (hashes + 1) + a], 1.0f);
      for (uint32_t b = 0; b <= a; ++b) {
        const double scale_b = b < hashes ? width : 1.0;
        double dot = 0;
        for (uint32_t dim = 0; dim < dims; ++dim) {
          dot +=
              matrix[table_idx * (hashes + 1) + a][dim] * matrix[table_idx * (hashes + 1) + b][dim];
        }
        EXPECT_NEAR(dot * scale_a * scale_b, a == b ? 1.0 : 0.0, 1e-4)
            << "table " << table_idx << " rows " << a << ", " << b;
      }
    }
  }
}

TEST(LshHashFamily, SameSeedSameFunctionsOtherSeedOthers) {
  const PoseFeatures features = RandomFeatures(4, 4);
  const HashFamily first = HashFamily::Draw(features.weights(), 4, 12, 0.1f, 77);
  const HashFamily again = HashFamily::Draw(features.weights(), 4, 12, 0.1f, 77);
  const HashFamily other = HashFamily::Draw(features.weights(), 4, 12, 0.1f, 78);
  const std::vector<float> embedding = Embedding(first, features, 1);
  std::vector<float> a(4 * 13), b(4 * 13), c(4 * 13);
  first.Project(embedding.data(), a.data());
  again.Project(embedding.data(), b.data());
  other.Project(embedding.data(), c.data());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // A table's functions do not depend on how many tables are drawn.
  const HashFamily fewer = HashFamily::Draw(features.weights(), 2, 12, 0.1f, 77);
  std::vector<float> d(2 * 13);
  fewer.Project(embedding.data(), d.data());
  EXPECT_TRUE(std::equal(d.begin(), d.end(), a.begin()));
}

TEST(LshHashFamily, BucketKeyDependsOnEveryCell) {
  int32_t cells[6] = {0, 1, -1, 5, 7, -3};
  const uint32_t key = HashFamily::BucketKey(cells, 6);
  for (int idx = 0; idx < 6; ++idx) {
    int32_t changed[6];
    std::memcpy(changed, cells, sizeof(cells));
    changed[idx] += 1;
    EXPECT_NE(HashFamily::BucketKey(changed, 6), key) << idx;
  }
}

TEST(LshHashFamily, PositionCodeIsTheQuarterOfTheCellPerCoordinate) {
  const std::vector<float> weights(12, 1.0f);
  // 20 hashes: only the first 16 are coded, 2 bits each, coordinate i in bits 2i and 2i + 1.
  const HashFamily family = HashFamily::Draw(weights, 1, 20, 0.1f, 5);
  float coordinates[21] = {};
  const float fractions[4] = {0.1f, 0.3f, 0.6f, 0.99f};
  uint32_t expected = 0;
  for (int idx = 0; idx < 20; ++idx) {
    // Negative cells too: the quarter is of the position inside the cell, floor-based.
    const float cell = static_cast<float>(idx % 3) - 1.0f;
    coordinates[idx] = cell + fractions[idx % 4];
    if (idx < 16) expected |= static_cast<uint32_t>(idx % 4) << (2 * idx);
  }
  EXPECT_EQ(family.PositionCode(coordinates), expected);
  coordinates[0] = -0.9f;  // position 0.1 in cell -1: quarter 0
  coordinates[1] = -0.2f;  // position 0.8 in cell -1: quarter 3
  expected = (expected & ~0xfu) | (3u << 2);
  EXPECT_EQ(family.PositionCode(coordinates), expected);
}

TEST(LshQueryDistance, BitIdenticalToPoseDistance) {
  for (uint32_t joints : {12u, 13u, 3u}) {
    SplitMix64 random(joints);
    const uint64_t frames = 300;
    const FrameLayout layout{joints};
    std::vector<float> rows(frames * layout.stride());
    for (float& value : rows) value = static_cast<float>(random.Uniform() * 2 - 1);
    for (uint64_t frame_idx = 0; frame_idx < frames; ++frame_idx) {
      for (uint32_t joint_idx = 0; joint_idx < joints; ++joint_idx) {
        float* q = &rows[frame_idx * layout.stride() + 4 * joint_idx];
        const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int component = 0; component < 4; ++component) q[component] /= norm;
      }
    }
    // Frame 7 repeats frame 3 exactly, and frame 8 is frame 3 with signs flipped: zeros.
    std::copy_n(&rows[3 * layout.stride()], layout.stride(), &rows[7 * layout.stride()]);
    for (size_t idx = 0; idx < layout.stride(); ++idx) {
      rows[8 * layout.stride() + idx] = -rows[3 * layout.stride() + idx];
    }
    std::vector<float> weights(joints);
    for (uint32_t joint_idx = 0; joint_idx < joints; ++joint_idx) {
      weights[joint_idx] = 0.25f + 0.5f * static_cast<float>(random.Uniform());
    }
    const PoseFeatures features = PoseFeatures::FromRows(rows.data(), frames, joints, weights, {0});
    QueryDistance distance(features);
    for (uint64_t query = 0; query < frames; query += 5) {
      distance.SetQuery(query);
      for (uint64_t frame = 0; frame < frames; ++frame) {
        const float fast = distance.To(frame);
        const float exact = PoseDistance(features, query, frame);
        ASSERT_EQ(std::memcmp(&fast, &exact, sizeof(float)), 0)
            << joints << " joints, " << query << " to " << frame << ": " << fast << " vs " << exact;
        // With a limit: exact when within it, above it otherwise.
        const float limited = distance.To(frame, 0.5f * exact);
        if (exact > 0) {
          EXPECT_GT(limited, 0.5f * exact);
        }
        const float generous = distance.To(frame, exact);
        ASSERT_EQ(std::memcmp(&generous, &exact, sizeof(float)), 0);
      }
    }
    // The batch path (eight frames per AVX2 instruction where the CPU has it), any count.
    std::vector<uint32_t> frames_list;
    for (uint32_t frame = 0; frame < frames; frame += 3) frames_list.push_back(frame);
    for (uint64_t query : {0u, 3u, 101u}) {
      distance.SetQuery(query);
      for (uint32_t count : {1u, 7u, 8u, 9u, 16u, 23u, 100u}) {
        std::vector<float> out(count);
        distance.ToBatch(frames_list.data(), count, INFINITY, out.data());
        for (uint32_t idx = 0; idx < count; ++idx) {
          const float exact = PoseDistance(features, query, frames_list[idx]);
          ASSERT_EQ(std::memcmp(&out[idx], &exact, sizeof(float)), 0)
              << joints << " joints, batch of " << count << ", " << query << " to "
              << frames_list[idx] << ": " << out[idx] << " vs " << exact;
        }
        // With a limit: exact at or below it, above it otherwise.
        distance.ToBatch(frames_list.data(), count, 1.0f, out.data());
        for (uint32_t idx = 0; idx < count; ++idx) {
          const float exact = PoseDistance(features, query, frames_list[idx]);
          if (exact <= 1.0f) {
            ASSERT_EQ(std::memcmp(&out[idx], &exact, sizeof(float)), 0);
          } else {
            ASSERT_GT(out[idx], 1.0f);
          }
        }
      }
    }
    RecordProperty("batch_avx2", distance.batch_avx2() ? "yes" : "no");
    distance.SetQuery(3);
    EXPECT_EQ(distance.To(7), 0.0f);
    EXPECT_EQ(distance.To(8), 0.0f);
  }
}

}  // namespace
}  // namespace motif
