#include "engine/grow/reference_grower.h"

#include <algorithm>
#include <string>

#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

namespace {

struct ReferenceLeaf {
  uint64_t frame = 0;
  uint64_t root_frame = 0;
  uint64_t root_column = 0;
  bool has_ancestor = false;
};

}  // namespace

Result<std::vector<PathCandidate>> GrowPathsReference(
    const std::vector<std::vector<Neighbour>>& columns, const std::vector<uint64_t>& clip_starts,
    const GrowOptions& options, GrowStats* stats) {
  MOTIF_RETURN_IF_ERROR(ValidateGrowOptions(options));
  const uint64_t frame_count = columns.size();
  MOTIF_RETURN_IF_ERROR(ValidateClipStarts(clip_starts, frame_count));
  // The clip of every frame (a reference may spend O(N) freely).
  std::vector<uint64_t> clip_of(frame_count, 0);
  for (uint64_t frame = 0, clip = 0; frame < frame_count; ++frame) {
    while (clip + 1 < clip_starts.size() && clip_starts[clip + 1] <= frame) ++clip;
    clip_of[frame] = clip;
  }
  auto starts_clip = [&](uint64_t frame) {
    return frame == 0 || clip_of[frame] != clip_of[frame - 1];
  };
  for (uint64_t column = 0; column < frame_count; ++column) {
    const std::vector<Neighbour>& nodes = columns[column];
    for (size_t slot = 0; slot < nodes.size(); ++slot) {
      if (nodes[slot].frame >= frame_count ||
          (slot > 0 && nodes[slot].frame <= nodes[slot - 1].frame)) {
        return Status::InvalidArgument("column " + std::to_string(column) + ", node " +
                                       std::to_string(slot) + ": frames must increase strictly " +
                                       "and stay below " + std::to_string(frame_count));
      }
    }
  }

  GrowStats local_stats;
  std::vector<PathCandidate> candidates;
  auto die = [&](const ReferenceLeaf& leaf, uint64_t column) {
    ++local_stats.dead_paths;
    if (column + 1 - leaf.root_column < options.min_length ||
        leaf.frame + 1 - leaf.root_frame < options.min_length) {
      return;
    }
    candidates.push_back({leaf.root_column, column + 1, leaf.root_frame, leaf.frame + 1,
                          leaf.root_column, leaf.root_frame});
    ++local_stats.long_paths;
  };

  std::vector<ReferenceLeaf> leaves;
  std::vector<ReferenceLeaf> next;
  for (uint64_t column = 0; column < frame_count; ++column) {
    const std::vector<Neighbour>& nodes = columns[column];
    next.assign(nodes.size(), ReferenceLeaf{});
    for (size_t slot = 0; slot < nodes.size(); ++slot) next[slot].frame = nodes[slot].frame;
    if (starts_clip(column)) {
      for (const ReferenceLeaf& leaf : leaves) die(leaf, column - 1);
    } else {
      // Every pair (leaf of column - 1, node of column): O(K²) a step; the oldest paths claim
      // first (root column ascending, then frame), as in PathGrower.
      std::sort(leaves.begin(), leaves.end(), [](const ReferenceLeaf& a, const ReferenceLeaf& b) {
        return a.root_column != b.root_column ? a.root_column < b.root_column : a.frame < b.frame;
      });
      for (const ReferenceLeaf& leaf : leaves) {
        bool grew = false;
        for (ReferenceLeaf& node : next) {
          if (node.has_ancestor || node.frame < leaf.frame ||
              node.frame - leaf.frame >= options.branch ||
              clip_of[node.frame] != clip_of[leaf.frame]) {
            continue;
          }
          node.root_frame = leaf.root_frame;
          node.root_column = leaf.root_column;
          node.has_ancestor = true;
          grew = true;
        }
        if (!grew) die(leaf, column - 1);
      }
    }
    for (ReferenceLeaf& node : next) {
      if (node.has_ancestor) continue;
      node.root_frame = node.frame;
      node.root_column = column;
      ++local_stats.trees;
    }
    leaves.swap(next);
    local_stats.entries += nodes.size();
    local_stats.max_column_nodes = std::max<uint64_t>(local_stats.max_column_nodes, nodes.size());
  }
  for (const ReferenceLeaf& leaf : leaves) die(leaf, frame_count - 1);
  local_stats.columns = frame_count;
  SortCandidates(&candidates);
  if (!options.all_branches) {
    // The longest of each tree: sorted, a tree's paths are adjacent (same top_start and
    // match_start), the longest top row last, and among those the longest match last.
    std::vector<PathCandidate> longest;
    for (size_t idx = 0; idx < candidates.size(); ++idx) {
      const bool last_of_tree = idx + 1 == candidates.size() ||
                                candidates[idx + 1].root_column != candidates[idx].root_column ||
                                candidates[idx + 1].root_frame != candidates[idx].root_frame;
      if (last_of_tree) longest.push_back(candidates[idx]);
    }
    candidates.swap(longest);
  }
  local_stats.candidates = candidates.size();
  if (stats != nullptr) *stats = local_stats;
  return candidates;
}

Result<std::vector<PathCandidate>> GrowPathsReference(const TrellisFileReader& trellis,
                                                      const std::vector<uint64_t>& clip_starts,
                                                      const GrowOptions& options,
                                                      GrowStats* stats) {
  std::vector<std::vector<Neighbour>> columns;
  MOTIF_RETURN_IF_ERROR(trellis.ReadColumns(0, trellis.column_count(), &columns));
  Result<std::vector<PathCandidate>> candidates =
      GrowPathsReference(columns, clip_starts, options, stats);
  if (!candidates.ok()) return candidates.status().WithContext(trellis.path());
  return candidates;
}

}  // namespace motif
