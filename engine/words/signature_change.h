// Unsupervised segmentation of takes by their motion signatures: boundaries where the words
// before and after differ most, and segments grouped by signature (docs/design/signatures.md,
// "Segmentation"). For a take of m words and a window of w words:
//  * the change score at word boundary b (between words b - 1 and b) is the EMD between the
//    signatures of words [b - w, b) and [b, b + w), each clipped at the take's ends; it is
//    scored where both sides hold at least ceil(w / 2) words;
//  * a boundary is a score that is the largest within w words either side (the earlier on a
//    tie) and above the threshold;
//  * the segments between boundaries are grouped by complete linkage on the EMD between their
//    whole signatures: two groups merge while every pair across them is within the threshold,
//    so a group never holds two segments farther apart than a boundary would separate.
// The threshold is one number for the run (ChangeThreshold): the mean plus one standard
// deviation of every score of every take segmented, so a take that never changes gets few
// boundaries and a take of several activities those that stand out.
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

// The mean plus one standard deviation of the finite scores; +infinity when there are none.
double ChangeThreshold(const std::vector<std::vector<double>>& scores_per_take);

// The boundaries b (1 .. m - 1), increasing.
std::vector<uint64_t> PickBoundaries(const std::vector<double>& scores, double threshold,
                                     uint32_t window);

// Complete-linkage groups of n items (0 .. groups - 1, numbered by first item), merging the
// closest pair of groups while its largest distance is at most `threshold`. Ties: the pair with
// the lower indices. O(n^3) time and O(n^2) memory for the n segments of a run.
std::vector<uint32_t> CompleteLinkageGroups(const Eigen::MatrixXd& distances, double threshold);

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
