#include "engine/lsh/hash_family.h"

#include <algorithm>
#include <cmath>

#include "common/split_mix64.h"
#include "common/status.h"
#include "engine/distance/pose_features.h"

namespace motif {

HashFamily HashFamily::Draw(const std::vector<float>& joint_weights, uint32_t tables,
                            uint32_t hashes_per_table, float bucket_width, uint64_t seed) {
  MOTIF_CHECK(!joint_weights.empty());
  MOTIF_CHECK(tables > 0);
  MOTIF_CHECK(hashes_per_table > 0 && hashes_per_table <= kMaxHashesPerTable);
  MOTIF_CHECK(bucket_width > 0);
  HashFamily family;
  family.table_count_ = tables;
  family.hashes_per_table_ = hashes_per_table;
  family.embedding_dims_ = kDimsPerJoint * static_cast<uint32_t>(joint_weights.size());
  family.bucket_width_ = bucket_width;
  family.joint_weights_ = joint_weights;
  double squared_norm = 0;
  for (float weight : joint_weights) squared_norm += 0.5 * weight * weight;
  // |s| <= |e| <= sqrt(sum w^2 / 2); a little headroom for quantised |q| slightly above 1.
  family.sort_scale_ = static_cast<float>(32000.0 / std::max(1e-6, std::sqrt(squared_norm)));

  const uint32_t dims = family.embedding_dims_;
  const uint32_t rows_per_table = hashes_per_table + 1;
  MOTIF_CHECK(rows_per_table <= dims);
  const size_t row_count = static_cast<size_t>(tables) * rows_per_table;
  family.rows_.assign(row_count * dims, 0.0f);
  family.offsets_.assign(static_cast<size_t>(tables) * rows_per_table, 0.0f);
  for (uint32_t table_idx = 0; table_idx < tables; ++table_idx) {
    // One generator per table, seeded from the table index: a table's functions do not depend
    // on how many tables there are.
    SplitMix64 random(seed ^ (0x9e3779b97f4a7c15ull * (table_idx + 1)));
    std::vector<std::vector<double>> basis;
    while (basis.size() < rows_per_table) {
      std::vector<double> row(dims);
      for (double& value : row) value = random.Gaussian();
      // Gram-Schmidt (twice, for stability) against the rows drawn so far.
      for (int pass = 0; pass < 2; ++pass) {
        for (const std::vector<double>& previous : basis) {
          double dot = 0;
          for (uint32_t dim = 0; dim < dims; ++dim) dot += row[dim] * previous[dim];
          for (uint32_t dim = 0; dim < dims; ++dim) row[dim] -= dot * previous[dim];
        }
      }
      double norm = 0;
      for (double value : row) norm += value * value;
      norm = std::sqrt(norm);
      if (norm < 1e-6) continue;  // (practically never) a degenerate draw: draw again
      for (double& value : row) value /= norm;
      basis.push_back(std::move(row));
    }
    for (uint32_t row_idx = 0; row_idx < rows_per_table; ++row_idx) {
      const bool hash_row = row_idx < hashes_per_table;
      const double scale = hash_row ? 1.0 / bucket_width : 1.0;
      const size_t column = static_cast<size_t>(table_idx) * rows_per_table + row_idx;
      for (uint32_t dim = 0; dim < dims; ++dim) {
        family.rows_[dim * row_count + column] = static_cast<float>(basis[row_idx][dim] * scale);
      }
      family.offsets_[table_idx * rows_per_table + row_idx] =
          hash_row ? static_cast<float>(random.Uniform()) : 0.0f;
    }
  }
  return family;
}

void HashFamily::Embed(const int16_t* frame, float* embedding) const {
  constexpr float kInverse = 1.0f / PoseFeatures::kQuantScale;
  constexpr float kInverseSqrt2 = 0.70710678118654752f;
  const size_t joint_count = joint_weights_.size();
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const float weight = joint_weights_[joint_idx];
    const float q0 = frame[4 * joint_idx + 0] * kInverse;
    const float q1 = frame[4 * joint_idx + 1] * kInverse;
    const float q2 = frame[4 * joint_idx + 2] * kInverse;
    const float q3 = frame[4 * joint_idx + 3] * kInverse;
    float* out = embedding + kDimsPerJoint * joint_idx;
    const float diagonal = weight * kInverseSqrt2;
    out[0] = diagonal * q0 * q0;
    out[1] = diagonal * q1 * q1;
    out[2] = diagonal * q2 * q2;
    out[3] = diagonal * q3 * q3;
    out[4] = weight * q0 * q1;
    out[5] = weight * q0 * q2;
    out[6] = weight * q0 * q3;
    out[7] = weight * q1 * q2;
    out[8] = weight * q1 * q3;
    out[9] = weight * q2 * q3;
  }
}

void HashFamily::Project(const float* embedding, float* projections) const {
  // Column-major over the embedding: each output is summed in the same order as a row-major
  // dot product would be, but the inner loop runs over outputs and vectorises without
  // reassociating any sum (the build and the queries must hash a frame bit-identically).
  const size_t row_count = offsets_.size();
  const size_t dims = embedding_dims_;
  std::copy(offsets_.begin(), offsets_.end(), projections);
  for (size_t dim = 0; dim < dims; ++dim) {
    const float value = embedding[dim];
    const float* column = &rows_[dim * row_count];
    for (size_t row_idx = 0; row_idx < row_count; ++row_idx) {
      projections[row_idx] += column[row_idx] * value;
    }
  }
}

uint32_t HashFamily::BucketKey(const int32_t* cells, uint32_t count) {
  uint64_t hash = 0x243f6a8885a308d3ull;
  for (uint32_t idx = 0; idx < count; ++idx) {
    hash ^= static_cast<uint32_t>(cells[idx]);
    hash *= 0x9fb21c651e98df25ull;
    hash ^= hash >> 29;
  }
  hash *= 0xd6e8feb86659fd93ull;
  hash ^= hash >> 32;
  return static_cast<uint32_t>(hash);
}

uint32_t HashFamily::KeyOfCoordinates(const float* coordinates) const {
  int32_t cells[kMaxHashesPerTable];
  for (uint32_t idx = 0; idx < hashes_per_table_; ++idx) {
    cells[idx] = static_cast<int32_t>(std::floor(coordinates[idx]));
  }
  return BucketKey(cells, hashes_per_table_);
}

uint32_t HashFamily::PositionCode(const float* coordinates) const {
  const uint32_t coded = std::min(hashes_per_table_, kCodedHashes);
  uint32_t code = 0;
  for (uint32_t idx = 0; idx < coded; ++idx) {
    const float fraction = coordinates[idx] - std::floor(coordinates[idx]);
    const uint32_t quarter = std::min(3u, static_cast<uint32_t>(fraction * 4.0f));
    code |= quarter << (2 * idx);
  }
  return code;
}

int16_t HashFamily::QuantiseSortValue(float sort_value) const {
  const float scaled = std::round(sort_value * sort_scale_);
  return static_cast<int16_t>(std::clamp(scaled, -32767.0f, 32767.0f));
}

}  // namespace motif
