// Classifying takes by a distance between them (Aristidou et al. 2018, section 6.1), as
// `motifmine classify` does it:
//  * unsupervised: classical MDS of the distance matrix (classical_mds.h) into `dims`
//    dimensions, then k-means (k_means.h, seeded) into `groups` groups; scored against the
//    labels, when there are some, by the adjusted Rand index and the purity (each group counts
//    its most common label) over the labelled takes;
//  * supervised: leave-one-out k-nearest-neighbour accuracy with the labels, and whole-take
//    retrieval precision at `top` (take_retrieval.h).
// The distance is the EMD between TF-IDF signatures, between plain term frequencies (the
// "without TF-IDF" baseline), or DTW over the frames (take_dtw.h): the caller computes it.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "common/status.h"
#include "engine/signature/classical_mds.h"
#include "engine/signature/take_retrieval.h"

namespace motif {

struct ClassifyOptions {
  uint32_t groups = 0;  // 0: the number of labels, or 8 without labels (at most the takes)
  uint32_t dims = 8;    // MDS dimensions (at most takes - 1)
  uint32_t knn = 1;
  uint32_t top = 5;  // precision@top
  uint64_t seed = 1;
  int threads = 0;
};

struct TakeClassification {
  std::string distance;            // "emd", "emd-tf", "dtw"
  std::vector<std::string> names;  // the takes (clip names)
  std::vector<uint32_t> clips;     // their archive clip indices
  Eigen::MatrixXd distances;
  std::vector<std::string> label_names;  // sorted
  std::vector<uint32_t> labels;          // per take: index into label_names, or kUnlabelled
  MdsResult mds;
  std::vector<uint32_t> groups;  // per take: its k-means group
  uint32_t group_count = 0;
  double adjusted_rand_index = 0;  // labelled takes only; 0 without labels
  double purity = 0;
  KnnEvaluation knn;
  uint32_t top = 5;
  double precision_at_top = 0;
  std::vector<std::vector<uint32_t>> nearest;  // per take: its `top` nearest takes
  double seconds_distances = 0;
};

// Fills everything but distance, names, clips and seconds_distances, which the caller sets.
// `labels` per take (empty string: unlabelled). InvalidArgument: sizes that disagree, fewer than
// 2 takes, bad options.
Result<TakeClassification> ClassifyTakes(Eigen::MatrixXd distances,
                                         const std::vector<std::string>& labels,
                                         const ClassifyOptions& options);

// The document `motifmine classify` writes (docs/guide.md, "classify.json").
nlohmann::json ClassificationJson(const TakeClassification& result, const std::string& archive);

}  // namespace motif
