// Neighbour: one node of a matching-trellis column, the unit of the trellis file
// (docs/formats/trellis_file.md) and of every neighbour search (engine/trellis/neighbour.h).
#pragma once

#include <cstdint>

namespace motif {

struct Neighbour {
  uint32_t frame = 0;  // global frame index in the archive
  float distance = 0;  // pose distance D to the column's frame
  bool operator==(const Neighbour& other) const {
    return frame == other.frame && distance == other.distance;
  }
};

}  // namespace motif
