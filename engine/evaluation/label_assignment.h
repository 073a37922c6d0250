// The one-to-one pairing of groups with labels that agrees on the most frames (the assignment
// problem, solved exactly by the Hungarian method: Kuhn 1955, Munkres 1957, in the O(n^2 m)
// form with potentials). Used by the one-to-one rule of frame-label scoring
// (frame_label_score.h); a group or label left without a partner is unmatched.
// Thread-safety: a pure function.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace motif {

inline constexpr int32_t kUnmatched = -1;

// For a rows x cols matrix of non-negative agreements, a column per row (kUnmatched when there
// are more rows than columns and the row is left out), no column used twice, whose total
// agreement is the largest possible. Among equal totals the pairing is deterministic.
std::vector<int32_t> MaximumAgreementAssignment(const Eigen::MatrixXd& agreement);

}  // namespace motif
