// HashFamily: the locality-sensitive hash functions of the LSH index, drawn from a seed.
//
// Embedding (sign-invariant). For each weighted joint k with quaternion q and weight w_k, the 10
// unique entries of q q^T, off-diagonal ones times sqrt(2), all divided by sqrt(2) and times w_k:
//   e_k = w_k [q0^2/r2, q1^2/r2, q2^2/r2, q3^2/r2, q0q1, q0q2, q0q3, q1q2, q1q3, q2q3], r2 =
//   sqrt 2.
// q and -q give the same e_k, so no hemisphere split can separate true neighbours. Per joint,
// |e_k(q) - e_k(p)|^2 = w_k^2 (1 - (q.p)^2) = w_k^2 d^2 (1 + |q.p|) / 2 with
// d = min(|q - p|, |q + p|), so d / sqrt(2) <= |De_k| / w_k <= d; summed over joints:
//   |e_i - e_j| <= D(i, j) <= sqrt(2 J_w) |e_i - e_j|   (J_w weighted joints, unit weights).
// The embedding has 10 J_w dimensions (120 for the 12 CMU joints).
//
// Hashes (Datar et al. 2004, p-stable LSH): table t has m orthonormal random directions a_ti
// (Gaussian rows, Gram-Schmidt), offsets b_ti uniform in [0, 1) and a width w; the cell
// coordinate is x_ti = a_ti.e / w + b_ti and the hash floor(x_ti). Because the rows are unit and
// orthogonal, a bucket whose cell differs from the query's has a distance bound: any frame in it
// has D >= |e - e_q| >= w * sqrt(sum of squared distances, in cells, to the crossed cell
// boundaries). One more unit direction u_t orthogonal to the a_ti gives each frame a sort value
// s = u_t.e inside its bucket, so |s - s_q| adds to that bound (LshSearch scans a bucket outward
// from s_q). Sort values are quantised to int16 over [-|e|max, |e|max].
// Thread-safety: immutable once drawn; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <vector>

namespace motif {

class HashFamily {
 public:
  static constexpr uint32_t kDimsPerJoint = 10;
  static constexpr uint32_t kMaxHashesPerTable = 32;

  // Draws `tables` tables of `hashes_per_table` (1..kMaxHashesPerTable) hashes for frames with
  // the given weighted-joint weights (PoseFeatures::weights()). The same arguments give the same
  // family on every platform (own RNG and Box-Muller, no <random> distributions).
  static HashFamily Draw(const std::vector<float>& joint_weights, uint32_t tables,
                         uint32_t hashes_per_table, float bucket_width, uint64_t seed);

  uint32_t table_count() const { return table_count_; }
  uint32_t hashes_per_table() const { return hashes_per_table_; }
  float bucket_width() const { return bucket_width_; }
  uint32_t embedding_dims() const { return embedding_dims_; }

  // e of one frame of PoseFeatures (4 J_w int16 values) into `embedding` (embedding_dims()).
  void Embed(const int16_t* frame, float* embedding) const;

  // All projections of an embedding: for table t, values [t * (m + 1), t * (m + 1) + m) are the
  // cell coordinates x_ti (hash = floor) and value t * (m + 1) + m is the sort value s.
  // `projections` holds table_count() * (hashes_per_table() + 1) floats.
  void Project(const float* embedding, float* projections) const;

  // 32-bit key of a bucket from its m cell indices (a mixing hash; different cells collide with
  // probability ~2^-32, which only adds candidates).
  static uint32_t BucketKey(const int32_t* cells, uint32_t count);
  // Floor of each coordinate, then BucketKey.
  uint32_t KeyOfCoordinates(const float* coordinates) const;

  // Where a frame sits inside its cell: 2 bits per hash coordinate (the quarter of the cell its
  // x_ti falls in) for the first kCodedHashes coordinates. A query ranks the entries of the
  // buckets it probes by the distance this code implies (LshSearch), which orders candidates
  // far better than the cell alone at 4 bytes per entry.
  static constexpr uint32_t kCodedHashes = 16;
  uint32_t PositionCode(const float* coordinates) const;

  // Sort value quantised: round(s * scale) clamped to int16.
  int16_t QuantiseSortValue(float sort_value) const;
  // Sort value units per int16 step (1 / scale).
  float sort_value_step() const { return 1.0f / sort_scale_; }

 private:
  uint32_t table_count_ = 0;
  uint32_t hashes_per_table_ = 0;
  uint32_t embedding_dims_ = 0;
  float bucket_width_ = 0;
  float sort_scale_ = 1;
  std::vector<float> joint_weights_;
  // The (table_count * (m + 1)) x embedding_dims projection matrix stored column-major (element
  // [dim * row_count + row]); the m hash rows of each table are pre-divided by w.
  std::vector<float> rows_;
  std::vector<float> offsets_;  // b per row (0 for the sort rows)
};

}  // namespace motif
