// Affinity profiles: the signatures of unsupervised segmentation (docs/design/signatures.md,
// section 11, "Unsupervised"). Every word of the takes being segmented is described by its
// affinity to every word of them,
//
//   A(i, j) = exp(-DTW(i, j)^2 / (s_i s_j)),   s_i = the DTW from word i to its k-th nearest word
//
// (a Gaussian kernel with self-tuning local scales, Zelnik-Manor & Perona 2004), and a stretch of
// words by the mean of its words' profiles (the kernel mean embedding of its bag of words). Two
// stretches are compared by the Euclidean distance between their mean profiles. Unlike the TF-IDF
// signature over the motifs, nothing here is trained, so the result does not depend on a seed;
// unlike the EMD between two bags of words, the words of one activity are alike through the
// words they all resemble, whatever the phase of the movement each starts at.
//
// Cost for N words and C = min(N, kMaxProfileColumns) columns (every word, or C words spread
// evenly): N x C DTWs, and 4 N C bytes of profiles (floats; their means are summed in double),
// so both stay linear in N beyond C words.
// Thread-safety: immutable once built; built in parallel, each value computed alone, so the
// result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/signature/word_distance.h"
#include "engine/words/word_bags.h"

namespace motif {

// The neighbour whose distance sets a word's scale.
constexpr uint32_t kProfileScaleNeighbour = 20;
// Columns of the profiles at most: the profiles hold 4 bytes per word and column (16 KB a word
// at 4096 columns), the DTWs between the column words 64 MB.
constexpr uint64_t kMaxProfileColumns = 4096;

// Words [first, end) of one clip.
struct WordRange {
  uint32_t clip = 0;
  uint64_t first = 0;
  uint64_t end = 0;
};

class AffinityProfiles {
 public:
  // The profiles of every word of `clips` (all in `words`). `progress(done, total)` counts words.
  static AffinityProfiles Compute(const WordsOfClips& words, const std::vector<uint32_t>& clips,
                                  const std::vector<uint64_t>& clip_words,
                                  const WordDistance& distance, int threads,
                                  const std::function<void(uint64_t, uint64_t)>& progress);

  // The mean profile of a stretch. Precondition: a clip given, first < end <= its words.
  Eigen::VectorXd Mean(const WordRange& range) const;
  // || Mean(a) - Mean(b) ||.
  double Distance(const WordRange& a, const WordRange& b) const;

 private:
  // Per clip, the row of its first word in rows_ (one row per word, clips in the order given).
  std::vector<uint64_t> first_row_;
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows_;
};

// The change scores of one clip (ChangeScores of signature_change.h): the distance between the
// mean profiles of the `window` words before and after each boundary.
std::vector<double> ProfileChangeScores(const AffinityProfiles& profiles, uint32_t clip,
                                        uint64_t words, uint32_t window);

// The distances between the mean profiles of every two pieces (symmetric, zero diagonal).
Eigen::MatrixXd ProfilePieceDistances(const AffinityProfiles& profiles,
                                      const std::vector<WordRange>& pieces);

}  // namespace motif
