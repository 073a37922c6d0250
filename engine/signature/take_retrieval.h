// Judging a distance between takes against labels: leave-one-out k-nearest-neighbour
// classification and whole-take retrieval precision at k (Aristidou et al. 2018, section 6:
// supervised classification with kNN on signatures, and whole-sequence retrieval judged by
// whether the takes retrieved show the same action). Used for signatures with the EMD and for
// the baselines (DTW over the frames, signatures without TF-IDF) alike.
//
// Neighbours of item i: the other labelled items, by distance, ties to the lower index.
//  * kNN: the majority label among the k nearest; a tie between labels goes to the one whose
//    first member comes first in that order (the nearer one).
//  * precision@k: for each labelled item with at least k labelled others, the fraction of its k
//    nearest that share its label; averaged over those items.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace motif {

inline constexpr uint32_t kUnlabelled = UINT32_MAX;

struct KnnEvaluation {
  uint32_t k = 1;
  uint64_t labelled = 0;
  uint64_t correct = 0;
  double accuracy = 0;
  std::vector<uint32_t> predicted;               // per item; kUnlabelled if not labelled
  std::vector<std::vector<uint64_t>> confusion;  // [true label][predicted label]
};

// `labels[i]` < label_count, or kUnlabelled. Preconditions (checked, abort): a square matrix of
// labels.size() rows, k >= 1.
KnnEvaluation LeaveOneOutKnn(const Eigen::MatrixXd& distances, const std::vector<uint32_t>& labels,
                             uint32_t label_count, uint32_t k);

// The kNN vote: the majority label among `nearest_labels` (the neighbours' labels, nearest
// first, each < label_count); a tie between labels goes to the one that comes first. kUnlabelled
// when `nearest_labels` is empty.
uint32_t MajorityOfNearest(const std::vector<uint32_t>& nearest_labels, uint32_t label_count);

// As above; 0 when no item has k labelled others.
double PrecisionAtK(const Eigen::MatrixXd& distances, const std::vector<uint32_t>& labels,
                    uint32_t k);

// The up to `count` items nearest item `item` (itself excluded), nearest first, ties to the lower
// index; only labelled ones when `labelled_only`.
std::vector<uint32_t> NearestItems(const Eigen::MatrixXd& distances,
                                   const std::vector<uint32_t>& labels, uint32_t item,
                                   uint32_t count, bool labelled_only);

}  // namespace motif
