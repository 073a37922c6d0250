// Unsupervised segmentation of takes by their motion signatures: boundaries where the words
// before and after differ most, and segments grouped by signature (docs/design/signatures.md,
// "Segmentation"). For a take of m words and a window of w words:
//  * the change score at word boundary b (between words b - 1 and b) is the distance between the
//    signatures of words [b - w, b) and [b, b + w), each clipped at the take's ends; it is
//    scored where both sides hold at least ceil(w / 2) words;
//  * a boundary is a score that is the largest within w words either side (the earlier on a
//    tie) and above the threshold;
//  * the segments between boundaries are grouped by agglomerative linkage on the distance
//    between their whole signatures, while the groups are within a group threshold.
// The threshold is one number for the run (ChangeThreshold): the mean plus some standard
// deviations of every score of every take segmented, so a take that never changes gets few
// boundaries and a take of several activities those that stand out. With the motif signatures
// it is one deviation, and the grouping is complete linkage at the same threshold, so a group
// never holds two segments farther apart than a boundary would separate; with the affinity
// profiles the rules of docs/design/signatures.md, section 11.
// Thread-safety: pure functions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace motif {

// Scores of boundaries b = 1 .. m - 1 (index b - 1), NaN where not scored. `distance(a, b)` is
// called with the word ranges [first, end) of the two sides.
template <typename Distance>
std::vector<double> ChangeScores(uint64_t words, uint32_t window, Distance&& distance);

// The mean plus `deviations` standard deviations of the finite scores; +infinity when there are
// none.
double ChangeThreshold(const std::vector<std::vector<double>>& scores_per_take,
                       double deviations = 1.0);

// The boundaries b (1 .. m - 1), increasing.
std::vector<uint64_t> PickBoundaries(const std::vector<double>& scores, double threshold,
                                     uint32_t window);

// How the distance between two groups follows from their items' distances.
enum class Linkage {
  kComplete,  // the largest
  kAverage,   // the mean over every pair across them (UPGMA)
};

// Agglomerative groups of n items (0 .. groups - 1, numbered by first item), merging the closest
// pair of groups while their linkage distance is at most `threshold`, or, when `groups` is not 0,
// until min(groups, n) groups remain whatever the distances. Ties: the pair with the lower
// indices. O(n^3) time and O(n^2) memory for the n segments of a run.
std::vector<uint32_t> LinkageGroups(const Eigen::MatrixXd& distances, double threshold,
                                    uint32_t groups, Linkage linkage);

// LinkageGroups with complete linkage.
inline std::vector<uint32_t> CompleteLinkageGroups(const Eigen::MatrixXd& distances,
                                                   double threshold, uint32_t groups = 0) {
  return LinkageGroups(distances, threshold, groups, Linkage::kComplete);
}

template <typename Distance>
std::vector<double> ChangeScores(uint64_t words, uint32_t window, Distance&& distance) {
  std::vector<double> scores(words > 0 ? words - 1 : 0, std::numeric_limits<double>::quiet_NaN());
  const uint64_t least = (window + 1) / 2;
  for (uint64_t b = 1; b < words; ++b) {
    const uint64_t first = b > window ? b - window : 0;
    const uint64_t end = std::min<uint64_t>(words, b + window);
    if (b - first < least || end - b < least) continue;
    scores[b - 1] = distance(first, b, b, end);
  }
  return scores;
}

}  // namespace motif
