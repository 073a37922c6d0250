// The adjusted Rand index (Hubert & Arabie 1985) of two labelings: how alike two groupings of the
// same items are, 1 for the same grouping, about 0 for a random one, negative for worse. Used to
// score found motifs against planted ones and classified takes against their labels.
// Thread-safety: a pure function.
#pragma once

#include <cstdint>
#include <vector>

namespace motif {

// The adjusted Rand index of two labelings of the same items (equal sizes). With fewer than two
// items, or when both put every item in one cluster or both put each item alone, it is 1 (the
// labelings agree perfectly; the formula is 0/0 there).
double AdjustedRandIndex(const std::vector<uint32_t>& labels_a,
                         const std::vector<uint32_t>& labels_b);

}  // namespace motif
