#include "engine/cluster/instance_builder.h"

#include <algorithm>
#include <numeric>
#include <optional>
#include <tuple>

namespace motif {

namespace {

// How far apart a path's two segments start (a periodic path's period).
uint64_t Shift(const PathCandidate& path) {
  return path.match_start > path.top_start ? path.match_start - path.top_start
                                           : path.top_start - path.match_start;
}

// Union-find with path halving; the smaller index becomes the root, so results do not depend on
// the order of unions.
class DisjointSets {
 public:
  explicit DisjointSets(size_t count) : parent_(count) {
    std::iota(parent_.begin(), parent_.end(), size_t{0});
  }
  size_t Find(size_t node) {
    while (parent_[node] != node) {
      parent_[node] = parent_[parent_[node]];
      node = parent_[node];
    }
    return node;
  }
  void Union(size_t a, size_t b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (a < b) {
      parent_[b] = a;
    } else {
      parent_[a] = b;
    }
  }

 private:
  std::vector<size_t> parent_;
};

// Longer first; ties broken by every field so the choice never depends on input order.
bool IsLongerPath(const PathCandidate& a, const PathCandidate& b) {
  return std::make_tuple(a.top_length(), a.match_length(), b.top_start, b.match_start, b.top_end,
                         b.match_end) > std::make_tuple(b.top_length(), b.match_length(),
                                                        a.top_start, a.match_start, a.top_end,
                                                        a.match_end);
}

// Trims the raw instances to their movement (MovingSpan) and carries the links: an instance
// with no movement left is dropped with its links (BuildInstances, step 2).
void TrimToMovement(const std::vector<MotifInstance>& pauses, uint64_t min_length,
                    std::vector<MotifInstance>* raw, std::vector<std::pair<size_t, size_t>>* links,
                    uint64_t* trimmed, uint64_t* still) {
  constexpr size_t kDropped = static_cast<size_t>(-1);
  std::vector<size_t> new_index(raw->size(), kDropped);
  std::vector<MotifInstance> kept;
  for (size_t idx = 0; idx < raw->size(); ++idx) {
    const std::optional<MotifInstance> span = MovingSpan((*raw)[idx], pauses, min_length);
    if (!span) {
      ++*still;
      continue;
    }
    if (*span != (*raw)[idx]) ++*trimmed;
    new_index[idx] = kept.size();
    kept.push_back(*span);
  }
  std::vector<std::pair<size_t, size_t>> kept_links;
  for (const auto& [a, b] : *links) {
    if (new_index[a] != kDropped && new_index[b] != kDropped) {
      kept_links.emplace_back(new_index[a], new_index[b]);
    }
  }
  *raw = std::move(kept);
  *links = std::move(kept_links);
}

}  // namespace

std::optional<MotifInstance> MovingSpan(const MotifInstance& range,
                                        const std::vector<MotifInstance>& pauses,
                                        uint64_t min_length) {
  auto pause =
      std::lower_bound(pauses.begin(), pauses.end(), range.start,
                       [](const MotifInstance& p, uint64_t frame) { return p.end <= frame; });
  if (pause == pauses.end() || pause->start >= range.end) return range;
  // The moving stretches between the pauses, the first and last of at least min_length kept.
  const uint64_t least = std::max<uint64_t>(min_length, 1);
  std::optional<MotifInstance> span;
  uint64_t from = range.start;
  auto moving = [&](uint64_t end) {
    if (end <= from || end - from < least) return;
    if (!span) span = MotifInstance{from, end};
    span->end = end;
  };
  for (; pause != pauses.end() && pause->start < range.end; ++pause) {
    moving(std::max(from, pause->start));
    from = std::max(from, pause->end);
  }
  moving(range.end);
  return span;
}

std::vector<PathCandidate> KeepLongestPathPerRoot(std::vector<PathCandidate> candidates) {
  std::sort(candidates.begin(), candidates.end(),
            [](const PathCandidate& a, const PathCandidate& b) {
              if (a.root_column != b.root_column) return a.root_column < b.root_column;
              if (a.root_frame != b.root_frame) return a.root_frame < b.root_frame;
              return IsLongerPath(a, b);
            });
  std::vector<PathCandidate> kept;
  for (const PathCandidate& candidate : candidates) {
    if (!kept.empty() && kept.back().root_column == candidate.root_column &&
        kept.back().root_frame == candidate.root_frame) {
      continue;  // a shorter branch of the same tree
    }
    kept.push_back(candidate);
  }
  return kept;
}

bool OverlapsEnough(const MotifInstance& a, const MotifInstance& b, double fraction) {
  const uint64_t longer = std::max(a.length(), b.length());
  if (std::min(a.length(), b.length()) == 0) return false;
  return static_cast<double>(OverlapFrames(a, b)) >= fraction * static_cast<double>(longer);
}

std::vector<MotifInstance> PeriodicPieces(const PathCandidate& path, uint64_t min_length) {
  const MotifInstance top{path.top_start, path.top_end};
  const MotifInstance match{path.match_start, path.match_end};
  if (OverlapFrames(top, match) == 0) return {};
  const uint64_t period = Shift(path);
  if (period == 0) return {};
  const uint64_t periods = std::max<uint64_t>(1, (min_length + period - 1) / period);
  const uint64_t piece = periods * period;
  const uint64_t start = std::min(top.start, match.start);
  const uint64_t end = std::max(top.end, match.end);
  std::vector<MotifInstance> pieces;
  for (uint64_t from = start; from + piece <= end; from += piece) {
    pieces.push_back({from, from + piece});
  }
  return pieces;
}

namespace {

// The pieces a periodic path cuts its span into: [start + j * piece, + piece), j < count.
struct PeriodGrid {
  uint64_t start = 0;
  uint64_t period = 0;
  uint64_t piece = 0;
  uint64_t count = 0;
  uint64_t end = 0;  // of the path's span (the last piece may end before it)
  MotifInstance Piece(uint64_t j) const { return {start + j * piece, start + (j + 1) * piece}; }
  MotifInstance Span() const { return {start, end}; }
};

std::optional<PeriodGrid> GridOf(const PathCandidate& path, uint64_t min_length) {
  const std::vector<MotifInstance> pieces = PeriodicPieces(path, min_length);
  if (pieces.empty()) return std::nullopt;
  const uint64_t piece = pieces[0].length();
  const uint64_t period = Shift(path);
  return PeriodGrid{pieces[0].start, period, piece, pieces.size(),
                    std::max(path.top_end, path.match_end)};
}

// The grid of the shortest period that `path` repeats a whole number k >= 2 of (its shift within
// a quarter period of k periods), among the grids covering 3/4 of both its segments: the path
// is that periodic motion matched with itself k periods later (a harmonic). Null if none.
const PeriodGrid* FundamentalOf(const PathCandidate& path, const std::vector<PeriodGrid>& grids) {
  const uint64_t shift = Shift(path);
  const MotifInstance top{path.top_start, path.top_end};
  const MotifInstance match{path.match_start, path.match_end};
  const PeriodGrid* best = nullptr;
  for (const PeriodGrid& grid : grids) {
    const MotifInstance span = grid.Span();
    if (4 * OverlapFrames(top, span) < 3 * top.length() ||
        4 * OverlapFrames(match, span) < 3 * match.length()) {
      continue;
    }
    if (grid.piece != grid.period) continue;  // a period shorter than lambda is no fundamental
    const uint64_t k = (shift + grid.period / 2) / grid.period;
    const uint64_t off =
        k * grid.period > shift ? k * grid.period - shift : shift - k * grid.period;
    if (k < 2 || 4 * off > grid.period) continue;
    if (!best || grid.period < best->period ||
        (grid.period == best->period && grid.count * grid.piece > best->count * best->piece)) {
      best = &grid;
    }
  }
  return best;
}

// A harmonic's links on its fundamental's pieces: each piece half inside its earlier segment to
// the piece as many pieces later as the shift spans. Empty when the shift is under a piece.
std::vector<std::pair<MotifInstance, MotifInstance>> HarmonicLinks(const PathCandidate& path,
                                                                   const PeriodGrid& grid) {
  const uint64_t step = (Shift(path) + grid.piece / 2) / grid.piece;
  const MotifInstance earlier = path.top_start <= path.match_start
                                    ? MotifInstance{path.top_start, path.top_end}
                                    : MotifInstance{path.match_start, path.match_end};
  std::vector<std::pair<MotifInstance, MotifInstance>> links;
  for (uint64_t j = 0; step > 0 && j + step < grid.count; ++j) {
    if (2 * OverlapFrames(grid.Piece(j), earlier) >= grid.piece) {
      links.emplace_back(grid.Piece(j), grid.Piece(j + step));
    }
  }
  return links;
}

}  // namespace

RawInstanceSet RawInstances(const std::vector<PathCandidate>& paths, uint64_t min_length) {
  RawInstanceSet set;
  std::vector<PeriodGrid> grids;
  for (const PathCandidate& path : paths) {
    if (std::optional<PeriodGrid> grid = GridOf(path, min_length)) grids.push_back(*grid);
  }
  auto add_link = [&](const MotifInstance& a, const MotifInstance& b) {
    set.links.emplace_back(set.instances.size(), set.instances.size() + 1);
    set.instances.push_back(a);
    set.instances.push_back(b);
  };
  for (const PathCandidate& path : paths) {
    if (const PeriodGrid* fundamental = FundamentalOf(path, grids)) {
      const auto links = HarmonicLinks(path, *fundamental);
      if (!links.empty()) {
        ++set.harmonic_paths;
        for (const auto& [a, b] : links) add_link(a, b);
        continue;
      }
    }
    const std::vector<MotifInstance> pieces = PeriodicPieces(path, min_length);
    if (pieces.empty()) {
      add_link({path.top_start, path.top_end}, {path.match_start, path.match_end});
      continue;
    }
    ++set.periodic_paths;
    for (size_t piece_idx = 0; piece_idx < pieces.size(); ++piece_idx) {
      if (piece_idx > 0) set.links.emplace_back(set.instances.size() - 1, set.instances.size());
      set.instances.push_back(pieces[piece_idx]);
    }
  }
  return set;
}

namespace {

bool RangeBefore(const MotifInstance& a, const MotifInstance& b) {
  return std::tie(a.start, a.end) < std::tie(b.start, b.end);
}

// The sweep in start order: `reaching` holds the earlier instances whose end is past the current
// start; only they can overlap it. Instances overlapping by `merge_overlap` join one set.
void UnionOverlapping(const std::vector<MotifInstance>& raw, double merge_overlap,
                      DisjointSets* sets) {
  std::vector<size_t> by_start(raw.size());
  std::iota(by_start.begin(), by_start.end(), size_t{0});
  std::sort(by_start.begin(), by_start.end(), [&](size_t a, size_t b) {
    return std::tie(raw[a].start, raw[a].end, a) < std::tie(raw[b].start, raw[b].end, b);
  });
  std::vector<size_t> reaching;
  for (size_t idx : by_start) {
    const MotifInstance& current = raw[idx];
    size_t kept = 0;
    for (size_t other : reaching) {
      if (raw[other].end <= current.start) continue;
      reaching[kept++] = other;
      if (OverlapsEnough(raw[other], current, merge_overlap)) sets->Union(other, idx);
    }
    reaching.resize(kept);
    reaching.push_back(idx);
  }
}

// Each set becomes the union of its ranges (*merged_of_root, by root); sets with equal unions
// become one instance. Sorted by (start, end).
std::vector<MotifInstance> MergeInstanceSets(const std::vector<MotifInstance>& raw,
                                             DisjointSets* sets,
                                             std::vector<MotifInstance>* merged_of_root) {
  merged_of_root->assign(raw.size(), MotifInstance());
  std::vector<size_t> roots;
  for (size_t idx = 0; idx < raw.size(); ++idx) {
    const size_t root = sets->Find(idx);
    MotifInstance& merged = (*merged_of_root)[root];
    if (root == idx) {
      merged = raw[idx];
      roots.push_back(root);
    } else {
      merged.start = std::min(merged.start, raw[idx].start);
      merged.end = std::max(merged.end, raw[idx].end);
    }
  }
  std::vector<MotifInstance> instances;
  for (size_t root : roots) instances.push_back((*merged_of_root)[root]);
  std::sort(instances.begin(), instances.end(), RangeBefore);
  instances.erase(std::unique(instances.begin(), instances.end()), instances.end());
  return instances;
}

// The raw links as distinct, sorted links between the merged instances; a link whose two ends
// merged into one instance is counted in stats.self_links.
void LinkMergedInstances(const std::vector<std::pair<size_t, size_t>>& raw_links,
                         const std::vector<MotifInstance>& merged_of_root, DisjointSets* sets,
                         InstanceSet* set) {
  auto id_of = [&](size_t raw_idx) {
    const MotifInstance& range = merged_of_root[sets->Find(raw_idx)];
    auto it = std::lower_bound(set->instances.begin(), set->instances.end(), range, RangeBefore);
    return static_cast<uint32_t>(it - set->instances.begin());
  };
  for (const auto& [from, to] : raw_links) {
    const uint32_t a = id_of(from);
    const uint32_t b = id_of(to);
    if (a == b) {
      ++set->stats.self_links;
      continue;
    }
    set->links.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(set->links.begin(), set->links.end());
  set->links.erase(std::unique(set->links.begin(), set->links.end()), set->links.end());
}

}  // namespace

InstanceSet BuildInstances(const std::vector<PathCandidate>& candidates,
                           const InstanceOptions& options) {
  InstanceSet set;
  set.stats.candidates = candidates.size();
  std::vector<PathCandidate> paths;
  paths.reserve(candidates.size());
  for (const PathCandidate& candidate : candidates) {
    if (candidate.top_end > candidate.top_start && candidate.match_end > candidate.match_start) {
      paths.push_back(candidate);
    }
  }
  paths = KeepLongestPathPerRoot(std::move(paths));
  set.stats.kept_paths = paths.size();

  RawInstanceSet raw_set = RawInstances(paths, options.min_length);
  std::vector<MotifInstance>& raw = raw_set.instances;
  set.stats.periodic_paths = raw_set.periodic_paths;
  set.stats.harmonic_paths = raw_set.harmonic_paths;
  if (!options.pauses.empty()) {
    TrimToMovement(options.pauses, options.min_length, &raw, &raw_set.links,
                   &set.stats.trimmed_instances, &set.stats.still_instances);
  }
  set.stats.raw_instances = raw.size();

  DisjointSets sets(raw.size());
  UnionOverlapping(raw, options.merge_overlap, &sets);
  std::vector<MotifInstance> merged_of_root;
  set.instances = MergeInstanceSets(raw, &sets, &merged_of_root);
  set.stats.instances = set.instances.size();
  LinkMergedInstances(raw_set.links, merged_of_root, &sets, &set);
  set.stats.links = set.links.size();
  return set;
}

}  // namespace motif
