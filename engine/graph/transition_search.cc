#include "engine/graph/transition_search.h"

#include <algorithm>
#include <atomic>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace motif {
namespace {

constexpr uint64_t kColumnsPerTask = 4096;

// The distance of entry `frame` in a column sorted by frame, or -1 when it is not there.
float EntryDistance(const std::vector<Neighbour>& column, uint64_t frame) {
  const auto found =
      std::lower_bound(column.begin(), column.end(), frame,
                       [](const Neighbour& entry, uint64_t value) { return entry.frame < value; });
  return found != column.end() && found->frame == frame ? found->distance : -1.0f;
}

// The window cost of (s, g), or -1 when a checked pair is not within eps. `columns[k]` is column
// first + k.
float WindowCost(const std::vector<std::vector<Neighbour>>& columns, uint64_t first, uint64_t s,
                 uint64_t g, float distance, const TransitionOptions& options) {
  double sum = distance;
  uint32_t pairs = 1;
  const uint32_t last = options.window_frames - 1;
  for (uint32_t o = options.check_step;; o += options.check_step) {
    if (o > last) o = last;
    const float d = EntryDistance(columns[s + o - first], g + o);
    if (d < 0) return -1.0f;
    sum += d;
    ++pairs;
    if (o == last) break;
  }
  return static_cast<float>(sum / pairs);
}

// Whether (s, g, cost) is at least as good as every other entry of `others` (sorted by target)
// within `radius` frames of g; ties go to the lower (source, target).
bool BestNear(const Transition& t, std::span<const Transition> others, uint64_t radius) {
  const uint64_t low = t.target > radius ? t.target - radius : 0;
  auto it = std::lower_bound(others.begin(), others.end(), low,
                             [](const Transition& x, uint64_t v) { return x.target < v; });
  for (; it != others.end() && it->target <= t.target + radius; ++it) {
    if (it->source == t.source && it->target == t.target) continue;
    if (it->cost < t.cost) return false;
    if (it->cost == t.cost &&
        (it->source < t.source || (it->source == t.source && it->target < t.target))) {
      return false;
    }
  }
  return true;
}

// The minima of the `index`-th distinct source.
std::span<const Transition> Row(const std::vector<Transition>& minima,
                                const std::vector<size_t>& column_start, size_t index) {
  return {minima.data() + column_start[index], column_start[index + 1] - column_start[index]};
}

struct ChunkResult {
  std::vector<Transition> minima;  // local minima along g within each column
  uint64_t candidates = 0;
  Status status;
};

void SearchChunk(const TrellisFileReader& trellis, const ClipBounds& clips, uint64_t first,
                 uint64_t end, const TransitionOptions& options, ChunkResult* out) {
  const uint64_t n = trellis.column_count();
  const uint64_t read_end = std::min(n, end + options.window_frames);
  std::vector<std::vector<Neighbour>> columns;
  out->status = trellis.ReadColumns(first, read_end - first, &columns);
  if (!out->status.ok()) return;
  const uint64_t radius = options.window_frames / 2;
  std::vector<Transition> column_candidates;
  for (uint64_t s = first; s < end; ++s) {
    const uint32_t s_clip = clips.ClipOf(s);
    if (s + options.window_frames > clips.starts[s_clip + 1]) continue;
    column_candidates.clear();
    for (const Neighbour& entry : columns[s - first]) {
      const uint64_t g = entry.frame;
      const uint32_t g_clip = clips.ClipOf(g);
      // The walk goes on in g's clip after the window: at least one frame must be left.
      if (g + options.window_frames >= clips.starts[g_clip + 1]) continue;
      if (g_clip == s_clip && (g > s ? g - s : s - g) < options.window_frames) continue;
      const float cost = WindowCost(columns, first, s, g, entry.distance, options);
      if (cost >= 0) column_candidates.push_back({s, g, cost});
    }
    out->candidates += column_candidates.size();
    for (const Transition& t : column_candidates) {
      if (BestNear(t, column_candidates, radius)) out->minima.push_back(t);
    }
  }
  // Give this chunk's pages of the mapped trellis back, as the path grower does, so that a
  // trellis larger than memory does not stay resident (a neighbour still reading them faults
  // them back in).
  const uint64_t block_columns = trellis.block_columns();
  out->status = trellis.ReleaseBlocks(first / block_columns, (end - 1) / block_columns + 1);
}

}  // namespace

uint32_t ClipBounds::ClipOf(uint64_t frame) const {
  return static_cast<uint32_t>(std::upper_bound(starts.begin(), starts.end(), frame) -
                               starts.begin() - 1);
}

ClipBounds ClipBoundsOf(const FrameFileReader& reader) {
  ClipBounds bounds;
  for (const ClipInfo& clip : reader.clips()) bounds.starts.push_back(clip.first_frame);
  bounds.starts.push_back(reader.frame_count());
  return bounds;
}

Result<TransitionSearch> FindTransitions(const TrellisFileReader& trellis, const ClipBounds& clips,
                                         const TransitionOptions& options) {
  if (options.window_frames < 2 || options.check_step == 0) {
    return Status::InvalidArgument("transitions: the window needs at least 2 frames and a step");
  }
  const uint64_t n = trellis.column_count();
  if (clips.starts.empty() || clips.starts.back() != n) {
    return Status::InvalidArgument("transitions: the trellis has " + std::to_string(n) +
                                   " columns, not the archive's frame count");
  }
  const uint64_t chunks = (n + kColumnsPerTask - 1) / kColumnsPerTask;
  std::vector<ChunkResult> results(chunks);
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        for (uint64_t chunk = range.begin(); chunk != range.end(); ++chunk) {
                          const uint64_t first = chunk * kColumnsPerTask;
                          const uint64_t end = std::min(n, first + kColumnsPerTask);
                          SearchChunk(trellis, clips, first, end, options, &results[chunk]);
                          const uint64_t now = done.fetch_add(end - first) + (end - first);
                          if (options.progress) options.progress(now, n);
                        }
                      });
  });
  TransitionSearch search;
  std::vector<Transition> minima;
  for (ChunkResult& result : results) {
    MOTIF_RETURN_IF_ERROR(result.status);
    search.candidates += result.candidates;
    minima.insert(minima.end(), result.minima.begin(), result.minima.end());
    std::vector<Transition>().swap(result.minima);
  }
  // Local minima in (s, g): also against the neighbouring columns' minima along g.
  const uint64_t radius = options.window_frames / 2;
  std::vector<size_t> column_start;  // index of the first minimum of each distinct source
  for (size_t idx = 0; idx < minima.size(); ++idx) {
    if (idx == 0 || minima[idx].source != minima[idx - 1].source) column_start.push_back(idx);
  }
  column_start.push_back(minima.size());
  for (size_t col = 0; col + 1 < column_start.size(); ++col) {
    for (size_t idx = column_start[col]; idx < column_start[col + 1]; ++idx) {
      const Transition& t = minima[idx];
      bool best = true;
      for (size_t other = col; best && other > 0;) {
        --other;
        if (minima[column_start[other]].source + radius < t.source) break;
        best = BestNear(t, Row(minima, column_start, other), radius);
      }
      for (size_t other = col + 1; best && other + 1 < column_start.size(); ++other) {
        if (minima[column_start[other]].source > t.source + radius) break;
        best = BestNear(t, Row(minima, column_start, other), radius);
      }
      if (best) search.transitions.push_back(t);
    }
  }
  return search;
}

}  // namespace motif
