// Comparing two trellis files of the same archive entry by entry: the (column, frame) pairs
// they hold, and the share of them they have in common. Header-only: the test links the trellis
// file library.
#pragma once

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_file_reader.h"

namespace motif::testing {

// Every (column, frame) entry of a trellis file (a failed open or read is a test failure).
inline std::set<std::pair<uint64_t, uint32_t>> TrellisEntries(const std::string& path) {
  std::set<std::pair<uint64_t, uint32_t>> entries;
  auto reader = TrellisFileReader::Open(path);
  EXPECT_TRUE(reader.ok()) << path;
  if (!reader.ok()) return entries;
  std::vector<std::vector<Neighbour>> columns;
  EXPECT_TRUE((*reader)->ReadColumns(0, (*reader)->column_count(), &columns).ok());
  for (uint64_t column = 0; column < columns.size(); ++column) {
    for (const Neighbour& neighbour : columns[column]) entries.insert({column, neighbour.frame});
  }
  return entries;
}

// The entries two trellises have in common, as a share of the larger one's.
inline double SharedTrellisEntries(const std::string& a_path, const std::string& b_path) {
  const auto a = TrellisEntries(a_path);
  const auto b = TrellisEntries(b_path);
  std::vector<std::pair<uint64_t, uint32_t>> shared;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
  return static_cast<double>(shared.size()) / static_cast<double>(std::max(a.size(), b.size()));
}

}  // namespace motif::testing
