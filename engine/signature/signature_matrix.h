// The Earth Mover's Distance between every pair of signatures (earth_movers_distance.h): the
// distance matrix that classification (MDS, k-nearest neighbours) and whole-take retrieval work
// on (Aristidou et al. 2018, section 6). n (n - 1) / 2 EMDs, in parallel over fixed rows, each
// task with its own solver; every entry is one exact EMD, so the matrix does not depend on the
// thread count. Symmetric with a zero diagonal.
// Thread-safety: a pure function; it runs in its own task_arena.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"

namespace motif {

// InvalidArgument: a signature of another size than the ground distance, or one EarthMoversDistance
// refuses (no mass, negative or non-finite values; the first such pair, by row then column).
// `progress(done, total)` counts rows.
Result<Eigen::MatrixXd> SignatureDistanceMatrix(
    const std::vector<std::vector<double>>& signatures, const Eigen::MatrixXd& ground, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

}  // namespace motif
