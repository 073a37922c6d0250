// TF-IDF motion signatures (Aristidou et al. 2018, section 5): a run of motion words (a whole take,
// or any window of consecutive words) becomes a histogram over the k motifs, each word counting
// for its nearest motif, weighted so a motif matters in proportion to how often the run uses it
// and in inverse proportion to how many takes of the archive use it.
//
// For a run W of |W| words, a motif m, an archive of N takes of which df(m) use m at least once:
//
//   tf(m, W)  = (words of W whose motif is m) / |W|
//   idf(m)    = ln((1 + N) / (1 + df(m))) + 1
//   sig(W)[m] = tf(m, W) * idf(m)
//
// Why this idf (the "smooth" variant, scikit-learn's default, so values can be checked there):
//  * it is never 0: with ln(N / df), a motif used by every take (the T-pose, standing still)
//    weighs 0, and a window made only of such words would have a signature with no mass, for
//    which the EMD (which compares distributions) is undefined;
//  * it is never negative: ln(N / (1 + df)) is ln(N / (N + 1)) < 0 at df = N, and a negative
//    mass is not a histogram;
//  * it is finite at df = 0 (a motif no take of the archive uses, possible once takes are added
//    after the motifs were built, or when the idf comes from a subset of the takes).
// A motif in every take weighs 1; one in a single take weighs ln((1 + N) / 2) + 1.
// tf divides by |W| so signatures of runs of different lengths are comparable; under the EMD's
// normalisation (EmdMass::kNormalize) that division cancels anyway. The archive's idf is used for
// every run, including windows of words and queries from outside the archive.
// Thread-safety: immutable after construction; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/status.h"

namespace motif {

class TfIdf {
 public:
  // Document frequencies from every take's motif ids (one vector per take, ids < motif_count).
  // A take with no words counts in N but uses no motif.
  // InvalidArgument: motif_count = 0, no takes, a motif id >= motif_count.
  static Result<TfIdf> Fit(std::span<const std::vector<uint32_t>> takes, uint32_t motif_count);

  // From counts gathered elsewhere (a saved model, a streaming count): N = take_count,
  // document_frequencies[m] = takes using motif m.
  // InvalidArgument: no motifs, take_count = 0, a frequency above take_count.
  static Result<TfIdf> FromDocumentFrequencies(uint64_t take_count,
                                               std::vector<uint64_t> document_frequencies);

  // The signature of a run of words given by their motif ids (a take, or any window).
  // InvalidArgument: no words, a motif id >= motif_count().
  Result<std::vector<double>> Signature(std::span<const uint32_t> words) const;

  // tf alone: the signature without the idf weighting (a baseline). Same errors.
  static Result<std::vector<double>> TermFrequencies(std::span<const uint32_t> words,
                                                     uint32_t motif_count);

  // idf(m) = ln((1 + N) / (1 + df)) + 1 (the formula above), exposed for tests and documents.
  static double InverseDocumentFrequency(uint64_t take_count, uint64_t document_frequency);

  uint32_t motif_count() const { return static_cast<uint32_t>(idf_.size()); }
  uint64_t take_count() const { return take_count_; }
  const std::vector<uint64_t>& document_frequencies() const { return document_frequencies_; }
  const std::vector<double>& idf() const { return idf_; }

 private:
  TfIdf(uint64_t take_count, std::vector<uint64_t> document_frequencies);

  uint64_t take_count_ = 0;
  std::vector<uint64_t> document_frequencies_;
  std::vector<double> idf_;
};

}  // namespace motif
