#include "engine/signature/take_retrieval.h"

#include <algorithm>
#include <numeric>

#include "common/status.h"

namespace motif {

std::vector<uint32_t> NearestItems(const Eigen::MatrixXd& distances,
                                   const std::vector<uint32_t>& labels, uint32_t item,
                                   uint32_t count, bool labelled_only) {
  std::vector<uint32_t> others;
  for (uint32_t other = 0; other < labels.size(); ++other) {
    if (other == item || (labelled_only && labels[other] == kUnlabelled)) continue;
    others.push_back(other);
  }
  const auto closer = [&](uint32_t a, uint32_t b) {
    const double da = distances(item, a);
    const double db = distances(item, b);
    return da < db || (da == db && a < b);
  };
  const size_t keep = std::min<size_t>(count, others.size());
  std::partial_sort(others.begin(), others.begin() + static_cast<std::ptrdiff_t>(keep),
                    others.end(), closer);
  others.resize(keep);
  return others;
}

uint32_t MajorityOfNearest(const std::vector<uint32_t>& nearest_labels, uint32_t label_count) {
  std::vector<uint32_t> votes(label_count, 0);
  for (uint32_t label : nearest_labels) ++votes[label];
  uint32_t most = 0;
  for (uint32_t count : votes) most = std::max(most, count);
  for (uint32_t label : nearest_labels) {  // the nearest label among those with the most votes
    if (votes[label] == most) return label;
  }
  return kUnlabelled;
}

KnnEvaluation LeaveOneOutKnn(const Eigen::MatrixXd& distances, const std::vector<uint32_t>& labels,
                             uint32_t label_count, uint32_t k) {
  MOTIF_CHECK(k >= 1);
  MOTIF_CHECK(distances.rows() == static_cast<Eigen::Index>(labels.size()) &&
              distances.cols() == distances.rows());
  KnnEvaluation result;
  result.k = k;
  result.predicted.assign(labels.size(), kUnlabelled);
  result.confusion.assign(label_count, std::vector<uint64_t>(label_count, 0));
  for (uint32_t item = 0; item < labels.size(); ++item) {
    if (labels[item] == kUnlabelled) continue;
    const std::vector<uint32_t> nearest = NearestItems(distances, labels, item, k, true);
    if (nearest.empty()) continue;
    std::vector<uint32_t> nearest_labels;
    for (uint32_t other : nearest) nearest_labels.push_back(labels[other]);
    const uint32_t predicted = MajorityOfNearest(nearest_labels, label_count);
    result.predicted[item] = predicted;
    ++result.labelled;
    result.correct += predicted == labels[item];
    ++result.confusion[labels[item]][predicted];
  }
  result.accuracy = result.labelled
                        ? static_cast<double>(result.correct) / static_cast<double>(result.labelled)
                        : 0.0;
  return result;
}

double PrecisionAtK(const Eigen::MatrixXd& distances, const std::vector<uint32_t>& labels,
                    uint32_t k) {
  double sum = 0;
  uint64_t items = 0;
  for (uint32_t item = 0; item < labels.size(); ++item) {
    if (labels[item] == kUnlabelled) continue;
    const std::vector<uint32_t> nearest = NearestItems(distances, labels, item, k, true);
    if (nearest.size() < k) continue;
    uint32_t same = 0;
    for (uint32_t other : nearest) same += labels[other] == labels[item];
    sum += static_cast<double>(same) / k;
    ++items;
  }
  return items ? sum / static_cast<double>(items) : 0.0;
}

}  // namespace motif
