#include "engine/signature/take_dtw.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/distance/distance_kernel.h"

namespace motif {
namespace {

constexpr uint32_t kRowBlock = 64;

std::vector<uint64_t> Subsampled(const TakeFrames& take, uint32_t step) {
  std::vector<uint64_t> frames;
  for (uint64_t frame = take.first_frame; frame < take.end_frame; frame += step)
    frames.push_back(frame);
  return frames;
}

}  // namespace

double TakeDtw(const PoseFeatures& features, const TakeFrames& a, const TakeFrames& b,
               uint32_t step) {
  MOTIF_CHECK(step >= 1);
  MOTIF_CHECK(a.end_frame <= features.frame_count() && b.end_frame <= features.frame_count());
  const std::vector<uint64_t> rows = Subsampled(a, step);
  const std::vector<uint64_t> cols = Subsampled(b, step);
  MOTIF_CHECK(!rows.empty() && !cols.empty());
  const DistanceKernel kernel(features);
  FrameBlock column_block;
  column_block.LoadFrames(features, cols.data(), static_cast<uint32_t>(cols.size()));
  const size_t m = cols.size();
  std::vector<float> local(static_cast<size_t>(kRowBlock) * m);
  std::vector<double> previous(m, std::numeric_limits<double>::infinity());
  std::vector<double> current(m);
  FrameBlock row_block;
  for (size_t first = 0; first < rows.size(); first += kRowBlock) {
    const uint32_t count = static_cast<uint32_t>(std::min<size_t>(kRowBlock, rows.size() - first));
    row_block.LoadFrames(features, rows.data() + first, count);
    kernel.Compute(row_block, column_block, local.data(), m);
    for (uint32_t r = 0; r < count; ++r) {
      const float* cost = &local[static_cast<size_t>(r) * m];
      const bool first_row = first + r == 0;
      for (size_t j = 0; j < m; ++j) {
        double best;
        if (first_row) {
          best = j == 0 ? 0.0 : current[j - 1];
        } else {
          best = previous[j];
          if (j > 0) best = std::min({best, current[j - 1], previous[j - 1]});
        }
        current[j] = best + cost[j];
      }
      std::swap(previous, current);
    }
  }
  return previous[m - 1] / static_cast<double>(rows.size() + m);
}

Result<Eigen::MatrixXd> TakeDtwMatrix(const PoseFeatures& features,
                                      const std::vector<TakeFrames>& takes, uint32_t step,
                                      int threads,
                                      const std::function<void(uint64_t, uint64_t)>& progress) {
  if (step == 0) return Status::InvalidArgument("take DTW: step must be >= 1");
  for (size_t idx = 0; idx < takes.size(); ++idx) {
    if (takes[idx].first_frame >= takes[idx].end_frame ||
        takes[idx].end_frame > features.frame_count()) {
      return Status::InvalidArgument("take DTW: take " + std::to_string(idx) +
                                     " is empty or outside the archive");
    }
  }
  const size_t n = takes.size();
  Eigen::MatrixXd distances =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, n, 1), [&](const tbb::blocked_range<size_t>& range) {
          for (size_t row = range.begin(); row != range.end(); ++row) {
            for (size_t col = row + 1; col < n; ++col) {
              const double distance = TakeDtw(features, takes[row], takes[col], step);
              distances(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(col)) = distance;
              distances(static_cast<Eigen::Index>(col), static_cast<Eigen::Index>(row)) = distance;
            }
            if (progress) progress(++done, n);
          }
        });
  });
  return distances;
}

}  // namespace motif
