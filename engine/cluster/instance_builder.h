// Instance building, the first half of the paper's clustering step (Meng et al. 2008, step 3):
// from the grower's path candidates to the motif instances that get clustered.
//
//  1. Keep the longest path per root. Candidates of one tree (same root node) are branches of
//     one match: only the longest (top-row length, then matched length, then earliest) stays.
//  2. Each kept path gives two instances, its top-row segment and its matched segment, linked.
//     A path whose two segments overlap is a periodic motion matching itself one period d later
//     (d = |match_start - top_start|): its span is cut into consecutive pieces of whole periods,
//     each at least min_length frames (one period, or the fewest that reach min_length), and
//     each piece is linked to the next. So a walk gives one instance per gait cycle rather than
//     one per take, and ten jumps in a row ten instances.
//     A path that matches such a periodic motion with itself k >= 2 periods later (a harmonic:
//     both its segments 3/4 inside the periodic path's span, its shift within a quarter period
//     of k periods, the period at least min_length) links the periodic path's own pieces k
//     pieces apart instead of giving two instances of its own: they would be a cycle and a
//     third, or two cycles, at a phase of their own, and merge with the pieces into longer
//     instances. Of several such periodic paths the shortest period is taken.
//     Each raw instance is then trimmed to its movement (options.pauses): its still head and
//     tail go, and with them a stretch shorter than lambda cut off by a pause (the end of the
//     movement before). An instance that is all pauses and short stretches is dropped.
//  3. Instances that overlap by at least 3/4 of the LONGER one (so each covers 3/4 of the
//     other) are merged: a union-find over an interval sweep (instances by start; each is
//     compared only with the earlier instances that still reach it), so the cost is
//     O(n log n + n·d), d the overlap depth, never all pairs. A merged instance is the union of
//     its members' ranges; members overlap pairwise along a chain, so the union is one
//     contiguous range inside one clip. The paper merges at 3/4 of the SHORTER: on repeated
//     movement that joins a one-repetition instance to a several-repetition one that contains
//     it, and the chain of such merges grows into whole takes (docs/design/motif_quality.md).
//  4. Links are carried to the merged instances; a path whose two segments merged into one
//     instance leaves no link and is counted.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "engine/cluster/motif_instance.h"
#include "formats/paths_file/path_candidate.h"

namespace motif {

struct InstanceOptions {
  double merge_overlap = 0.75;  // merge when the overlap is at least this fraction of the longer
  uint64_t min_length = 0;      // the least piece of a periodic path, frames (the grower's lambda)
  // Still stretches of the archive (pauses.h), ascending global ranges: each raw instance is
  // trimmed to its movement (MovingSpan). Empty: nothing is trimmed.
  std::vector<MotifInstance> pauses;
};

struct InstanceSetStats {
  uint64_t candidates = 0;         // paths given
  uint64_t kept_paths = 0;         // after keeping the longest per root
  uint64_t raw_instances = 0;      // 2 per kept path
  uint64_t instances = 0;          // after merging
  uint64_t links = 0;              // distinct links between merged instances
  uint64_t self_links = 0;         // kept paths whose two segments merged into one instance
  uint64_t periodic_paths = 0;     // kept paths cut into periods (their segments overlapped)
  uint64_t harmonic_paths = 0;     // kept paths that repeat a periodic path k >= 2 periods later
  uint64_t trimmed_instances = 0;  // raw instances trimmed to their movement
  uint64_t still_instances = 0;    // raw instances with no movement of min_length, dropped
};

struct InstanceSet {
  std::vector<MotifInstance> instances;  // sorted by (start, end); an instance's id is its index
  std::vector<InstanceLink> links;       // distinct, a < b, sorted
  InstanceSetStats stats;
};

// The longest candidate of each root (root_column, root_frame), sorted by root.
std::vector<PathCandidate> KeepLongestPathPerRoot(std::vector<PathCandidate> candidates);

// True if a and b share at least `fraction` of the longer one's frames.
bool OverlapsEnough(const MotifInstance& a, const MotifInstance& b, double fraction);

// The pieces of a periodic path (its segments overlap; step 2 above), in order; empty when its
// segments do not overlap.
std::vector<MotifInstance> PeriodicPieces(const PathCandidate& path, uint64_t min_length);

// Step 2 before the trimming: the raw instances of the kept paths (periodic ones cut into
// pieces, harmonics linked on their periodic path's pieces) and the links between them, as
// pairs of indices into `instances`. O(paths x periodic paths).
struct RawInstanceSet {
  std::vector<MotifInstance> instances;
  std::vector<std::pair<size_t, size_t>> links;
  uint64_t periodic_paths = 0;
  uint64_t harmonic_paths = 0;
};
RawInstanceSet RawInstances(const std::vector<PathCandidate>& kept_paths, uint64_t min_length);

// `range` trimmed to its movement: from the start of its first moving stretch (a stretch between
// `pauses`, ascending and disjoint) of at least min_length frames to the end of its last one;
// `range` itself when no pause overlaps it, nullopt when no stretch is long enough.
std::optional<MotifInstance> MovingSpan(const MotifInstance& range,
                                        const std::vector<MotifInstance>& pauses,
                                        uint64_t min_length);

// Steps 1 to 4 above. Candidates with an empty segment are skipped (the grower never makes them).
InstanceSet BuildInstances(const std::vector<PathCandidate>& candidates,
                           const InstanceOptions& options = {});

}  // namespace motif
