#include "engine/words/signature_change.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace motif {

double ChangeThreshold(const std::vector<std::vector<double>>& scores_per_take,
                       double deviations) {
  double sum = 0;
  double squares = 0;
  uint64_t count = 0;
  for (const std::vector<double>& scores : scores_per_take) {
    for (double score : scores) {
      if (!std::isfinite(score)) continue;
      sum += score;
      squares += score * score;
      ++count;
    }
  }
  if (count == 0) return std::numeric_limits<double>::infinity();
  const double mean = sum / static_cast<double>(count);
  const double variance = std::max(0.0, squares / static_cast<double>(count) - mean * mean);
  return mean + deviations * std::sqrt(variance);
}

std::vector<uint64_t> PickBoundaries(const std::vector<double>& scores, double threshold,
                                     uint32_t window) {
  std::vector<uint64_t> boundaries;
  const size_t n = scores.size();
  for (size_t at = 0; at < n; ++at) {
    if (!std::isfinite(scores[at]) || scores[at] <= threshold) continue;
    const size_t from = at > window ? at - window : 0;
    const size_t to = std::min(n, at + window + 1);
    bool peak = true;
    for (size_t other = from; other < to && peak; ++other) {
      if (other == at || !std::isfinite(scores[other])) continue;
      // The earlier of equal scores is the peak.
      peak = other < at ? scores[other] < scores[at] : scores[other] <= scores[at];
    }
    if (peak) boundaries.push_back(at + 1);
  }
  return boundaries;
}

std::vector<uint32_t> LinkageGroups(const Eigen::MatrixXd& distances, double threshold,
                                    uint32_t groups, Linkage kind) {
  const auto n = static_cast<size_t>(distances.rows());
  // linkage(a, b) between live groups, kept by the update of `kind`.
  Eigen::MatrixXd linkage = distances;
  std::vector<double> sizes(n, 1.0);
  std::vector<size_t> owner(n);  // each item's group, named by a live row of `linkage`
  std::vector<bool> live(n, true);
  for (size_t item = 0; item < n; ++item) owner[item] = item;
  const auto at = [](size_t row) { return static_cast<Eigen::Index>(row); };
  for (size_t live_groups = n; groups == 0 || live_groups > groups; --live_groups) {
    double best = std::numeric_limits<double>::infinity();
    size_t best_a = n;
    size_t best_b = n;
    for (size_t a = 0; a < n; ++a) {
      for (size_t b = a + 1; b < n && live[a]; ++b) {
        if (live[b] && linkage(at(a), at(b)) < best) {
          best = linkage(at(a), at(b));
          best_a = a;
          best_b = b;
        }
      }
    }
    if (best_a == n || (groups == 0 && !(best <= threshold))) break;
    for (size_t c = 0; c < n; ++c) {
      const double a = linkage(at(best_a), at(c));
      const double b = linkage(at(best_b), at(c));
      const double merged = kind == Linkage::kComplete
                                ? std::max(a, b)
                                : (sizes[best_a] * a + sizes[best_b] * b) /
                                      (sizes[best_a] + sizes[best_b]);
      linkage(at(best_a), at(c)) = merged;
      linkage(at(c), at(best_a)) = merged;
    }
    live[best_b] = false;
    sizes[best_a] += sizes[best_b];
    for (size_t item = 0; item < n; ++item) {
      if (owner[item] == best_b) owner[item] = best_a;
    }
  }
  // Groups numbered by their first item.
  std::vector<uint32_t> number(n, UINT32_MAX);
  std::vector<uint32_t> assignment(n, 0);
  uint32_t numbered = 0;
  for (size_t item = 0; item < n; ++item) {
    if (number[owner[item]] == UINT32_MAX) number[owner[item]] = numbered++;
    assignment[item] = number[owner[item]];
  }
  return assignment;
}

}  // namespace motif
