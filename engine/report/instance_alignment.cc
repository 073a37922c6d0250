#include "engine/report/instance_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/distance/joint_term.h"

namespace motif {
namespace {

float SampleDistance(const Skeleton& skeleton, const float* a, const float* b) {
  float total = 0;
  for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
    const float weight = skeleton.joint(joint).weight;
    if (weight <= 0) continue;
    float dot = 0, norm_a = 0, norm_b = 0;
    for (int component = 0; component < 4; ++component) {
      const float qa = a[4 * joint + component];
      const float qb = b[4 * joint + component];
      dot += qa * qb;
      norm_a += qa * qa;
      norm_b += qb * qb;
    }
    total += weight * JointTermFromSums<ScalarLanes>(norm_a, norm_b, dot);
  }
  return total;
}

std::vector<uint32_t> Linear(uint32_t reference_samples, uint32_t instance_samples) {
  std::vector<uint32_t> map(reference_samples, 0);
  for (uint32_t r = 0; r < reference_samples && reference_samples > 1; ++r) {
    map[r] = static_cast<uint32_t>(
        std::llround(static_cast<double>(r) * (instance_samples - 1) / (reference_samples - 1)));
  }
  return map;
}

}  // namespace

std::vector<uint32_t> AlignToReference(const Skeleton& skeleton, size_t stride,
                                       const std::vector<float>& reference,
                                       uint32_t reference_samples,
                                       const std::vector<float>& instance,
                                       uint32_t instance_samples) {
  const uint64_t cells = uint64_t{reference_samples} * instance_samples;
  if (reference_samples == 0 || instance_samples == 0) return {};
  if (cells > kMaxAlignmentCells) return Linear(reference_samples, instance_samples);
  const size_t n = reference_samples, m = instance_samples;
  // cost[r][k]: the least summed distance of a path from (0, 0) to (r, k), steps (1,1), (1,0),
  // (0,1); ties prefer the diagonal, then advancing the reference.
  std::vector<double> cost(n * m, std::numeric_limits<double>::infinity());
  for (size_t r = 0; r < n; ++r) {
    for (size_t k = 0; k < m; ++k) {
      const double here = SampleDistance(skeleton, &reference[r * stride], &instance[k * stride]);
      double best = r == 0 && k == 0 ? 0.0 : std::numeric_limits<double>::infinity();
      if (r > 0 && k > 0) best = std::min(best, cost[(r - 1) * m + k - 1]);
      if (r > 0) best = std::min(best, cost[(r - 1) * m + k]);
      if (k > 0) best = std::min(best, cost[r * m + k - 1]);
      cost[r * m + k] = best + here;
    }
  }
  // Back from (n-1, m-1): each reference sample keeps the nearest of the instance samples the
  // path pairs it with (the earliest of equals).
  std::vector<uint32_t> map(n, 0);
  std::vector<float> nearest(n, std::numeric_limits<float>::infinity());
  size_t r = n - 1, k = m - 1;
  while (true) {
    const float distance = SampleDistance(skeleton, &reference[r * stride], &instance[k * stride]);
    if (distance <= nearest[r]) {
      nearest[r] = distance;
      map[r] = static_cast<uint32_t>(k);
    }
    if (r == 0 && k == 0) break;
    if (r == 0) {
      --k;
      continue;
    }
    if (k == 0) {
      --r;
      continue;
    }
    const double diagonal = cost[(r - 1) * m + k - 1];
    const double up = cost[(r - 1) * m + k];
    const double left = cost[r * m + k - 1];
    if (diagonal <= up && diagonal <= left) {
      --r;
      --k;
    } else if (up <= left) {
      --r;
    } else {
      --k;
    }
  }
  return map;
}

}  // namespace motif
