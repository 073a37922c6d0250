#include "engine/evaluation/label_assignment.h"

#include <algorithm>
#include <limits>

namespace motif {

namespace {

// Minimum-cost assignment of every row of an n x m cost matrix (n <= m) to a distinct column:
// the shortest augmenting path method with row and column potentials. Returns the column of
// each row.
std::vector<int32_t> MinimumCostRowAssignment(const Eigen::MatrixXd& cost) {
  const Eigen::Index n = cost.rows();
  const Eigen::Index m = cost.cols();
  const double infinity = std::numeric_limits<double>::infinity();
  // 1-based as in the textbook form; index 0 is the virtual column of the row being added.
  std::vector<double> row_potential(n + 1, 0.0), column_potential(m + 1, 0.0);
  std::vector<Eigen::Index> row_of_column(m + 1, 0), previous(m + 1, 0);
  for (Eigen::Index row = 1; row <= n; ++row) {
    row_of_column[0] = row;
    Eigen::Index column = 0;
    std::vector<double> slack(m + 1, infinity);
    std::vector<bool> used(m + 1, false);
    do {
      used[column] = true;
      const Eigen::Index current_row = row_of_column[column];
      double delta = infinity;
      Eigen::Index next = 0;
      for (Eigen::Index j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced =
            cost(current_row - 1, j - 1) - row_potential[current_row] - column_potential[j];
        if (reduced < slack[j]) {
          slack[j] = reduced;
          previous[j] = column;
        }
        if (slack[j] < delta) {
          delta = slack[j];
          next = j;
        }
      }
      for (Eigen::Index j = 0; j <= m; ++j) {
        if (used[j]) {
          row_potential[row_of_column[j]] += delta;
          column_potential[j] -= delta;
        } else {
          slack[j] -= delta;
        }
      }
      column = next;
    } while (row_of_column[column] != 0);
    do {  // flip the augmenting path back to the virtual column
      const Eigen::Index before = previous[column];
      row_of_column[column] = row_of_column[before];
      column = before;
    } while (column != 0);
  }
  std::vector<int32_t> column_of_row(n, kUnmatched);
  for (Eigen::Index j = 1; j <= m; ++j) {
    if (row_of_column[j] != 0) column_of_row[row_of_column[j] - 1] = static_cast<int32_t>(j - 1);
  }
  return column_of_row;
}

}  // namespace

std::vector<int32_t> MaximumAgreementAssignment(const Eigen::MatrixXd& agreement) {
  const Eigen::Index rows = agreement.rows();
  const Eigen::Index cols = agreement.cols();
  if (rows == 0 || cols == 0) return std::vector<int32_t>(rows, kUnmatched);
  // The method assigns every row of a matrix with no more rows than columns: transpose when
  // there are more rows, and minimise the negated agreement.
  if (rows <= cols) return MinimumCostRowAssignment(-agreement);
  const std::vector<int32_t> row_of_column = MinimumCostRowAssignment(-agreement.transpose());
  std::vector<int32_t> column_of_row(rows, kUnmatched);
  for (Eigen::Index col = 0; col < cols; ++col) {
    column_of_row[row_of_column[col]] = static_cast<int32_t>(col);
  }
  return column_of_row;
}

}  // namespace motif
