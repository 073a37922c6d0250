#include "engine/signature/signature_matrix.h"

#include <atomic>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/earth_movers_distance.h"

namespace motif {

Result<Eigen::MatrixXd> SignatureDistanceMatrix(
    const std::vector<std::vector<double>>& signatures, const Eigen::MatrixXd& ground, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress) {
  const size_t n = signatures.size();
  for (size_t idx = 0; idx < n; ++idx) {
    if (signatures[idx].size() != static_cast<size_t>(ground.rows())) {
      return Status::InvalidArgument("signature " + std::to_string(idx) + " has " +
                                     std::to_string(signatures[idx].size()) + " bins for " +
                                     std::to_string(ground.rows()) + " motifs");
    }
  }
  Eigen::MatrixXd distances =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  std::vector<Status> row_status(n);
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, n, 1), [&](const tbb::blocked_range<size_t>& range) {
          EarthMoversDistance emd;
          for (size_t row = range.begin(); row != range.end(); ++row) {
            for (size_t col = row + 1; col < n; ++col) {
              Result<double> distance = emd.Distance(signatures[row], signatures[col], ground);
              if (!distance.ok()) {
                row_status[row] = distance.status().WithContext(
                    "signatures " + std::to_string(row) + " and " + std::to_string(col));
                break;
              }
              distances(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(col)) = *distance;
              distances(static_cast<Eigen::Index>(col), static_cast<Eigen::Index>(row)) = *distance;
            }
            if (progress) progress(++done, n);
          }
        });
  });
  for (const Status& status : row_status) MOTIF_RETURN_IF_ERROR(status);
  return distances;
}

}  // namespace motif
