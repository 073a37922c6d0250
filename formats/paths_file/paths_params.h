// PathsParams: what a paths file's candidates were grown from and with, stored in its header
// (docs/formats/paths_file.md; encoded by paths_file_format.h). A leaf, so that the format, the
// writer and the reader all include it and not each other.
// Thread-safety: a value type.
#pragma once

#include <cstdint>

namespace motif {

// What the paths were grown from and with; stored in the header. Equal params mean the same
// candidates (the grower is deterministic), so `motifmine grow` reuses the file.
struct PathsParams {
  uint64_t trellis_identity = 0;  // TrellisFileReader::identity() of the trellis grown
  uint64_t archive_identity = 0;  // the archive's identity, as in the trellis's params
  uint64_t frame_count = 0;       // N: columns of the trellis, at most 2^32
  uint32_t branch = 0;            // B, at least 1
  uint64_t min_length = 0;        // lambda in frames, at least 1
  bool all_branches = false;      // every long path (GrowOptions::all_branches), or the
                                  // longest of each tree

  bool operator==(const PathsParams& other) const = default;
};

}  // namespace motif
