#include "common/rank_group.h"

#include <algorithm>

namespace motif {

std::vector<uint64_t> PartStarts(uint64_t count, int parts, uint64_t align) {
  const uint64_t units = (count + align - 1) / align;
  std::vector<uint64_t> starts(static_cast<size_t>(parts) + 1);
  for (int part = 0; part <= parts; ++part) {
    const uint64_t unit = units * static_cast<uint64_t>(part) / static_cast<uint64_t>(parts);
    starts[static_cast<size_t>(part)] = std::min(count, unit * align);
  }
  return starts;
}

RankShare ShareOf(uint64_t count, const RankGroup* ranks, uint64_t align) {
  if (ranks == nullptr || ranks->size() <= 1) return {{0, count}, 0};
  return {PartStarts(count, ranks->size(), align), static_cast<size_t>(ranks->rank())};
}

}  // namespace motif
