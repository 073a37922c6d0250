#include "engine/grow/path_grower.h"

#include <algorithm>
#include <string>
#include <tuple>

#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

namespace {

// A cell of the auxiliary array: the top bit flags a frame that starts a clip (permanent); the
// low 31 bits hold 1 + the slot of the node of column t+1 at that frame, or 0 (not marked).
constexpr uint32_t kClipStartBit = 0x80000000u;
constexpr uint32_t kSlotMask = 0x7FFFFFFFu;

constexpr uint64_t kMaxFrameCount = uint64_t{1} << 32;  // frame ids are u32

// The live leaf of one path: its node's frame, its tree's root and the tree's slot in the pool.
// Its depth is the current column minus root_column.
struct Leaf {
  uint32_t frame;
  uint32_t root_frame;
  uint32_t root_column;
  uint32_t tree;
};

// A tree with live leaves: how many, and its longest dead path so far (if any reached lambda).
struct Tree {
  uint32_t live_leaves = 0;
  bool has_best = false;
  uint64_t best_top_end = 0;
  uint64_t best_match_end = 0;
};

}  // namespace

Status ValidateGrowOptions(const GrowOptions& options) {
  if (options.branch < 1 || options.branch > kMaxBranch) {
    return Status::InvalidOption("branch", "must be in [1, " + std::to_string(kMaxBranch) +
                                               "], not " + std::to_string(options.branch));
  }
  if (options.min_length < 1) {
    return Status::InvalidOption("min-length", "must be at least 1 frame");
  }
  return Status::Ok();
}

Status ValidateClipStarts(const std::vector<uint64_t>& clip_starts, uint64_t frame_count) {
  if (clip_starts.empty()) return Status::Ok();
  if (clip_starts[0] != 0) {
    return Status::InvalidArgument("the first clip starts at frame " +
                                   std::to_string(clip_starts[0]) + ", not 0");
  }
  for (size_t clip_idx = 0; clip_idx < clip_starts.size(); ++clip_idx) {
    if (clip_starts[clip_idx] >= frame_count ||
        (clip_idx > 0 && clip_starts[clip_idx] <= clip_starts[clip_idx - 1])) {
      return Status::InvalidArgument("clip " + std::to_string(clip_idx) + " starts at frame " +
                                     std::to_string(clip_starts[clip_idx]) +
                                     ": clip starts must increase and stay below " +
                                     std::to_string(frame_count));
    }
  }
  return Status::Ok();
}

void SortCandidates(std::vector<PathCandidate>* candidates) {
  std::sort(candidates->begin(), candidates->end(),
            [](const PathCandidate& a, const PathCandidate& b) {
              return std::tie(a.top_start, a.match_start, a.top_end, a.match_end, a.root_column,
                              a.root_frame) < std::tie(b.top_start, b.match_start, b.top_end,
                                                       b.match_end, b.root_column, b.root_frame);
            });
}

class PathGrower::Impl {
 public:
  uint64_t frame_count = 0;
  GrowOptions options;
  std::vector<uint32_t> cells;  // the auxiliary array, N cells
  // LeavesInClaimOrder: the leaves of a column are appended in the order the oldest path
  // claims first needs (root column ascending, then frame), without a sort. Leaves are taken
  // in that order, and each appends its children in frame order; a leaf's children all lie
  // above its predecessor's in the same tree age, since that predecessor claimed every marked
  // cell of its own window (of B cells from a lower frame). Children inherit their root column;
  // the new trees, rooted in this column (the youngest), follow in frame order.
  std::vector<Leaf> leaves;     // column next_column - 1, in claim order
  std::vector<Leaf> next;       // column next_column, being filled in claim order
  std::vector<Tree> trees;      // slots of trees with live leaves (at most two columns' worth)
  std::vector<uint32_t> free_trees;
  uint64_t next_column = 0;
  std::vector<PathCandidate> candidates;
  GrowStats stats;

  uint32_t NewTree() {
    ++stats.trees;
    if (free_trees.empty()) {
      trees.push_back(Tree{1, false, 0, 0});
      return static_cast<uint32_t>(trees.size() - 1);
    }
    const uint32_t tree = free_trees.back();
    free_trees.pop_back();
    trees[tree] = Tree{1, false, 0, 0};
    return tree;
  }

  static PathCandidate MakeCandidate(const Leaf& leaf, uint64_t top_end, uint64_t match_end) {
    return {leaf.root_column, top_end,          leaf.root_frame,
            match_end,        leaf.root_column, leaf.root_frame};
  }

  // The leaf of column `column` could not grow: its path is a candidate if it is long enough
  // on both sides; with all_branches it is kept, otherwise only its tree's longest one
  // (by top length, then match length) is, once the tree's last leaf is gone.
  void Die(const Leaf& leaf, uint64_t column) {
    ++stats.dead_paths;
    Tree& tree = trees[leaf.tree];
    const uint64_t top_end = column + 1;
    const uint64_t match_end = uint64_t{leaf.frame} + 1;
    if (top_end - leaf.root_column >= options.min_length &&
        match_end - leaf.root_frame >= options.min_length) {
      ++stats.long_paths;
      if (options.all_branches) {
        candidates.push_back(MakeCandidate(leaf, top_end, match_end));
      } else if (!tree.has_best || top_end > tree.best_top_end ||
                 (top_end == tree.best_top_end && match_end > tree.best_match_end)) {
        tree.has_best = true;
        tree.best_top_end = top_end;
        tree.best_match_end = match_end;
      }
    }
    if (--tree.live_leaves == 0) {
      if (tree.has_best)
        candidates.push_back(MakeCandidate(leaf, tree.best_top_end, tree.best_match_end));
      free_trees.push_back(leaf.tree);
    }
  }

  void Step(const Neighbour* nodes, size_t count) {
    const uint64_t column = next_column;
    next.clear();
    next.reserve(count);
    // Column `column` starts a clip (or the trellis): no path crosses into it.
    if (column == 0 || (cells[column] & kClipStartBit) != 0) {
      for (const Leaf& leaf : leaves) Die(leaf, column - 1);
      for (size_t slot = 0; slot < count; ++slot) {
        next.push_back({nodes[slot].frame, nodes[slot].frame, static_cast<uint32_t>(column),
                        NewTree()});
      }
      return;
    }
    for (size_t slot = 0; slot < count; ++slot) {
      cells[nodes[slot].frame] |= static_cast<uint32_t>(slot + 1);
    }
    const uint64_t branch = options.branch;
    // The oldest paths claim first (root column ascending, then frame): a long match keeps its
    // continuation instead of losing it to a tree that started a few frames above it. The
    // leaves are in that order already (LeavesInClaimOrder), so no sort is needed.
    for (const Leaf& leaf : leaves) {
      const uint64_t first = leaf.frame;
      const uint64_t end = std::min<uint64_t>(first + branch, frame_count);
      // Most windows of noise nodes are empty: one test for the whole window instead of a
      // mispredicted branch per cell (the clip check below may still leave it empty).
      uint32_t any_marked = 0;
      for (uint64_t frame = first; frame < end; ++frame) any_marked |= cells[frame];
      uint32_t children = 0;
      if ((any_marked & kSlotMask) != 0) {
        for (uint64_t frame = first; frame < end; ++frame) {
          const uint32_t cell = cells[frame];
          // The window stops at the next clip: a matched segment never spans two clips.
          if (frame != first && (cell & kClipStartBit) != 0) break;
          const uint32_t slot = cell & kSlotMask;
          if (slot == 0) continue;
          next.push_back({static_cast<uint32_t>(frame), leaf.root_frame, leaf.root_column,
                          leaf.tree});
          cells[frame] = cell & kClipStartBit;  // claimed: one ancestor per node
          ++children;
        }
      }
      if (children == 0) {
        Die(leaf, column - 1);
      } else {
        trees[leaf.tree].live_leaves += children - 1;  // the leaf is replaced by its children
      }
    }
    // Unclaimed nodes start new trees; every mark is gone afterwards.
    for (size_t slot = 0; slot < count; ++slot) {
      uint32_t& cell = cells[nodes[slot].frame];
      if ((cell & kSlotMask) != 0) {
        next.push_back({nodes[slot].frame, nodes[slot].frame, static_cast<uint32_t>(column),
                        NewTree()});
      }
      cell &= kClipStartBit;
    }
  }
};

Result<std::unique_ptr<PathGrower>> PathGrower::Create(uint64_t frame_count,
                                                       const std::vector<uint64_t>& clip_starts,
                                                       const GrowOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateGrowOptions(options));
  if (frame_count > kMaxFrameCount) {
    return Status::InvalidArgument("a trellis of " + std::to_string(frame_count) +
                                   " columns: at most 2^32 are supported");
  }
  MOTIF_RETURN_IF_ERROR(ValidateClipStarts(clip_starts, frame_count));
  auto impl = std::make_unique<Impl>();
  impl->frame_count = frame_count;
  impl->options = options;
  impl->cells.assign(frame_count, 0);
  for (uint64_t start : clip_starts) impl->cells[start] = kClipStartBit;
  return std::unique_ptr<PathGrower>(new PathGrower(std::move(impl)));
}

PathGrower::PathGrower(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PathGrower::~PathGrower() = default;

uint64_t PathGrower::next_column() const { return impl_->next_column; }
const GrowStats& PathGrower::stats() const { return impl_->stats; }

uint64_t PathGrower::memory_bytes() const {
  return impl_->cells.capacity() * sizeof(uint32_t) +
         (impl_->leaves.capacity() + impl_->next.capacity()) * sizeof(Leaf) +
         impl_->trees.capacity() * sizeof(Tree) + impl_->free_trees.capacity() * sizeof(uint32_t) +
         impl_->candidates.capacity() * sizeof(PathCandidate);
}

Status PathGrower::AddColumn(const Neighbour* nodes, size_t count) {
  Impl& impl = *impl_;
  const uint64_t column = impl.next_column;
  if (column >= impl.frame_count) {
    return Status::InvalidArgument("all " + std::to_string(impl.frame_count) +
                                   " columns were added already");
  }
  if (count > kSlotMask - 1) {
    return Status::InvalidArgument("column " + std::to_string(column) + " has " +
                                   std::to_string(count) + " nodes");
  }
  for (size_t slot = 0; slot < count; ++slot) {
    if (nodes[slot].frame >= impl.frame_count ||
        (slot > 0 && nodes[slot].frame <= nodes[slot - 1].frame)) {
      return Status::InvalidArgument(
          "column " + std::to_string(column) + ", node " + std::to_string(slot) + ": frame " +
          std::to_string(nodes[slot].frame) + " (frames must increase strictly and stay below " +
          std::to_string(impl.frame_count) + ")");
    }
  }
  impl.Step(nodes, count);
  impl.leaves.swap(impl.next);
  impl.next_column = column + 1;
  impl.stats.columns = impl.next_column;
  impl.stats.entries += count;
  impl.stats.max_column_nodes = std::max<uint64_t>(impl.stats.max_column_nodes, count);
  return Status::Ok();
}

Result<std::vector<PathCandidate>> PathGrower::Finish() {
  Impl& impl = *impl_;
  if (impl.next_column != impl.frame_count) {
    return Status::InvalidArgument("Finish after " + std::to_string(impl.next_column) + " of " +
                                   std::to_string(impl.frame_count) + " columns");
  }
  if (impl.frame_count > 0) {
    for (const Leaf& leaf : impl.leaves) impl.Die(leaf, impl.frame_count - 1);
  }
  impl.leaves.clear();
  impl.stats.candidates = impl.candidates.size();
  std::vector<PathCandidate> candidates = std::move(impl.candidates);
  impl.candidates.clear();
  SortCandidates(&candidates);
  return candidates;
}

Result<std::vector<PathCandidate>> GrowPaths(
    const TrellisFileReader& trellis, const std::vector<uint64_t>& clip_starts,
    const GrowOptions& options, const std::function<void(uint64_t, uint64_t)>& progress,
    GrowStats* stats) {
  const uint64_t total = trellis.column_count();
  Result<std::unique_ptr<PathGrower>> created = PathGrower::Create(total, clip_starts, options);
  if (!created.ok()) return created.status().WithContext(trellis.path());
  PathGrower& grower = **created;
  if (progress) progress(0, total);
  TrellisBlock block;
  for (uint64_t block_idx = 0; block_idx < trellis.block_count(); ++block_idx) {
    MOTIF_RETURN_IF_ERROR(trellis.ReadBlock(block_idx, &block, /*decode_distances=*/false));
    for (uint32_t in_block = 0; in_block < block.column_count; ++in_block) {
      const uint32_t begin = block.offsets[in_block];
      const uint32_t end = block.offsets[in_block + 1];
      Status status = grower.AddColumn(block.neighbours.data() + begin, end - begin);
      if (!status.ok()) return status.WithContext(trellis.path());
    }
    // The block is consumed: without this its mapped pages stay in the process's resident set
    // until the reader closes (the whole file by the end: gigabytes at 10^7 frames), dwarfing
    // the grower's O(N) memory. The page cache keeps them; the reader maps them again if asked.
    MOTIF_RETURN_IF_ERROR(trellis.ReleaseBlocks(block_idx, block_idx + 1));
    if (progress) progress(grower.next_column(), total);
  }
  const uint64_t memory_bytes = grower.memory_bytes();
  Result<std::vector<PathCandidate>> candidates = grower.Finish();
  if (!candidates.ok()) return candidates.status().WithContext(trellis.path());
  if (stats != nullptr) {
    *stats = grower.stats();
    stats->memory_bytes = memory_bytes;
  }
  return candidates;
}

}  // namespace motif
