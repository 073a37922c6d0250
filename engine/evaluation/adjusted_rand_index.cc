#include "engine/evaluation/adjusted_rand_index.h"

#include <map>
#include <utility>

#include "common/status.h"

namespace motif {

namespace {

double PairsOf(uint64_t count) {
  return static_cast<double>(count) * static_cast<double>(count > 0 ? count - 1 : 0) / 2.0;
}

}  // namespace

double AdjustedRandIndex(const std::vector<uint32_t>& labels_a,
                         const std::vector<uint32_t>& labels_b) {
  MOTIF_CHECK(labels_a.size() == labels_b.size());
  const uint64_t n = labels_a.size();
  if (n < 2) return 1.0;
  std::map<std::pair<uint32_t, uint32_t>, uint64_t> table;
  std::map<uint32_t, uint64_t> rows;
  std::map<uint32_t, uint64_t> cols;
  for (size_t idx = 0; idx < n; ++idx) {
    ++table[{labels_a[idx], labels_b[idx]}];
    ++rows[labels_a[idx]];
    ++cols[labels_b[idx]];
  }
  // Both trivial in the same way: perfect agreement (the formula below would be 0/0).
  if ((rows.size() == 1 && cols.size() == 1) || (rows.size() == n && cols.size() == n)) {
    return 1.0;
  }
  double index = 0;
  for (const auto& [cell, count] : table) index += PairsOf(count);
  double sum_rows = 0;
  double sum_cols = 0;
  for (const auto& [label, count] : rows) sum_rows += PairsOf(count);
  for (const auto& [label, count] : cols) sum_cols += PairsOf(count);
  const double expected = sum_rows * sum_cols / PairsOf(n);
  const double maximum = (sum_rows + sum_cols) / 2.0;
  if (maximum == expected) return 1.0;
  return (index - expected) / (maximum - expected);
}

}  // namespace motif
