// PathCandidate: one continuous path of the matching trellis that died with at least lambda
// frames on both sides (docs/design/algorithm.md step 3). It links two motif instances: the top-row
// segment (the columns the path crossed) and the matched segment (the frames its nodes were).
// The grower (engine/grow/) writes these to a paths file (docs/formats/paths_file.md), which
// clustering (engine/cluster/) reads; the type lives with the file format it is stored in.
// All frame numbers are global archive frame indices; ranges are half-open [start, end).
#pragma once

#include <cstdint>

namespace motif {

struct PathCandidate {
  uint64_t top_start = 0;    // first column of the top-row segment
  uint64_t top_end = 0;      // one past the last column
  uint64_t match_start = 0;  // first matched frame (the node of the path's first column)
  uint64_t match_end = 0;    // one past the last matched frame
  // The tree the path belongs to: its root node (a node of column root_column with no
  // ancestor, frame root_frame). Several candidates may share a root (the tree branched);
  // clustering keeps the longest per root.
  uint64_t root_column = 0;
  uint64_t root_frame = 0;

  uint64_t top_length() const { return top_end - top_start; }
  uint64_t match_length() const { return match_end - match_start; }
  bool operator==(const PathCandidate& other) const = default;
};

}  // namespace motif
