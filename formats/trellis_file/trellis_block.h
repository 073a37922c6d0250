// TrellisBlock: the decoded columns of one column block of a trellis file
// (docs/formats/trellis_file.md, section 4.3), what the block codec decodes into and the reader
// hands out. A leaf, so that the codec does not include the reader.
// Thread-safety: a value type.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/trellis_file/trellis_column.h"

namespace motif {

// One decoded block: columns [first_column, first_column + column_count).
struct TrellisBlock {
  uint64_t first_column = 0;
  uint32_t column_count = 0;
  std::vector<uint32_t> offsets;      // column_count + 1 entries into `neighbours`
  std::vector<Neighbour> neighbours;  // column c: [offsets[c], offsets[c + 1])
};

}  // namespace motif
