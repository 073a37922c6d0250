#include "engine/distance/exact_search.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/distance/distance_kernel.h"

namespace motif {
namespace {

constexpr uint32_t kScanChunk = 32;

// Keeps the k_max nearest of `column` (FinishColumn's order: distance, then frame). The k_max
// nearest of the whole column are among the k_max nearest of any prefix joined with the rest,
// so pruning as the column grows changes nothing but the memory it takes.
void KeepNearest(uint32_t k_max, std::vector<Neighbour>* column) {
  auto nearer = [](const Neighbour& a, const Neighbour& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
  };
  std::nth_element(column->begin(), column->begin() + k_max, column->end(), nearer);
  column->resize(k_max);
}

// One task's share: columns [first, first + count) of the archive, written to `columns`
// (the caller's vector, from index first - first_column).
// With `reverse`, also the frames below reverse_query->frame_limit within their thresholds,
// into reverse[query_idx].
void SearchQueryBlock(const PoseFeatures& features, const NeighbourRules& rules,
                      const ExactSearchOptions& options, const DistanceKernel& kernel,
                      uint64_t first, uint32_t count, std::vector<Neighbour>* columns,
                      const ReverseQuery* reverse_query, std::vector<Neighbour>* reverse,
                      SearchStats* stats) {
  const uint64_t frame_count = features.frame_count();
  FrameBlock queries;
  queries.LoadRange(features, first, count);
  FrameBlock candidates;
  const uint32_t block_frames = options.candidate_block_frames;
  std::vector<float> tile(static_cast<size_t>(count) * block_frames);
  std::vector<ExclusionRange> excluded(count);
  std::vector<uint64_t> within(count, 0);  // frames within eps, before the k_max cap
  const size_t prune_size = std::max<size_t>(2 * static_cast<size_t>(rules.k_max), 1024);
  for (uint32_t query_idx = 0; query_idx < count; ++query_idx) {
    excluded[query_idx] = ExclusionRangeOf(rules, first + query_idx, frame_count);
    columns[query_idx].clear();
    if (reverse != nullptr) reverse[query_idx].clear();
  }
  const float eps = rules.eps;
  for (uint64_t block_first = 0; block_first < frame_count; block_first += block_frames) {
    const uint32_t block_count =
        static_cast<uint32_t>(std::min<uint64_t>(block_frames, frame_count - block_first));
    candidates.LoadRange(features, block_first, block_count);
    kernel.Compute(queries, candidates, tile.data(), block_frames);
    for (uint32_t query_idx = 0; query_idx < count; ++query_idx) {
      const float* row = &tile[static_cast<size_t>(query_idx) * block_frames];
      std::vector<Neighbour>& column = columns[query_idx];
      const ExclusionRange& skip = excluded[query_idx];
      const size_t size_before = column.size();
      for (uint32_t chunk_first = 0; chunk_first < block_count; chunk_first += kScanChunk) {
        const uint32_t chunk_end = std::min(chunk_first + kScanChunk, block_count);
        // Most chunks hold no frame within eps (K is ~1 % of N): test a chunk at once first,
        // which the compiler vectorises, and walk it only on a hit.
        bool any_within = false;
        for (uint32_t candidate_idx = chunk_first; candidate_idx < chunk_end; ++candidate_idx) {
          any_within |= row[candidate_idx] <= eps;
        }
        if (!any_within) continue;
        for (uint32_t candidate_idx = chunk_first; candidate_idx < chunk_end; ++candidate_idx) {
          if (row[candidate_idx] <= eps) {
            const uint64_t frame = block_first + candidate_idx;
            if (!skip.Contains(frame)) {
              const Neighbour found{static_cast<uint32_t>(frame), row[candidate_idx]};
              column.push_back(found);
              if (reverse != nullptr && frame < reverse_query->frame_limit &&
                  (reverse_query->thresholds == nullptr ||
                   found.distance <= reverse_query->thresholds[frame])) {
                reverse[query_idx].push_back(found);
              }
            }
          }
        }
      }
      within[query_idx] += column.size() - size_before;
      // Bounded memory however large eps is: at most prune_size + a block per column.
      if (column.size() > prune_size) KeepNearest(rules.k_max, &column);
    }
  }
  for (uint32_t query_idx = 0; query_idx < count; ++query_idx) {
    std::vector<Neighbour>& column = columns[query_idx];
    if (within[query_idx] > rules.k_max) ++stats->capped_columns;
    FinishColumn(rules.k_max, &column);
    stats->neighbours += column.size();
  }
  stats->columns += count;
  stats->distance_evaluations += static_cast<uint64_t>(count) * frame_count;
}

}  // namespace

Status ValidateClipStarts(const std::vector<uint64_t>& clip_first_frames) {
  if (clip_first_frames.empty() || clip_first_frames[0] != 0) {
    return Status::InvalidArgument("neighbour rules: the clip list must start with frame 0");
  }
  if (!std::is_sorted(clip_first_frames.begin(), clip_first_frames.end())) {
    return Status::InvalidArgument("neighbour rules: the clip list is not ascending");
  }
  return Status::Ok();
}

ExclusionRange ExclusionRangeOf(const NeighbourRules& rules, uint64_t frame, uint64_t frame_count) {
  const std::vector<uint64_t>& starts = rules.clip_first_frames;
  const auto after = std::upper_bound(starts.begin(), starts.end(), frame);
  const uint64_t clip_begin = after == starts.begin() ? 0 : *(after - 1);
  const uint64_t clip_end = after == starts.end() ? frame_count : *after;
  // Excluded: j == t, or the same clip and |t - j| < exclusion_frames.
  const uint64_t reach = std::max<uint64_t>(rules.exclusion_frames, 1) - 1;
  ExclusionRange range;
  range.begin = frame - std::min(frame - clip_begin, reach);
  range.end = std::min(clip_end, frame + reach + 1);
  return range;
}

ExactSearch::ExactSearch(const PoseFeatures& features, NeighbourRules rules,
                         ExactSearchOptions options)
    : features_(features), rules_(std::move(rules)), options_(options) {
  if (rules_.clip_first_frames.empty()) rules_.clip_first_frames = features.clip_first_frames();
  options_.query_block_frames = std::max<uint32_t>(options_.query_block_frames, 1);
  options_.candidate_block_frames = std::max<uint32_t>(options_.candidate_block_frames, 1);
}

Status ExactSearch::SearchColumns(uint64_t first_column, uint64_t count,
                                  std::vector<std::vector<Neighbour>>* columns,
                                  SearchStats* stats) const {
  return Search(first_column, count, nullptr, columns, nullptr, stats);
}

Status ExactSearch::SearchColumnsAndReverse(uint64_t first_column, uint64_t count,
                                            const ReverseQuery& query,
                                            std::vector<std::vector<Neighbour>>* columns,
                                            std::vector<std::vector<Neighbour>>* reverse,
                                            SearchStats* stats) const {
  MOTIF_RETURN_IF_ERROR(CheckReverseQuery(query, features_.frame_count(), "exact search"));
  if (reverse->size() < count) reverse->resize(count);
  return Search(first_column, count, &query, columns, reverse, stats);
}

Status ExactSearch::Search(uint64_t first_column, uint64_t count, const ReverseQuery* query,
                           std::vector<std::vector<Neighbour>>* columns,
                           std::vector<std::vector<Neighbour>>* reverse, SearchStats* stats) const {
  const uint64_t frame_count = features_.frame_count();
  if (first_column > frame_count || count > frame_count - first_column) {
    return Status::InvalidArgument("exact search: columns [" + std::to_string(first_column) + ", " +
                                   std::to_string(first_column + count) +
                                   ") outside an archive of " + std::to_string(frame_count) +
                                   " frames");
  }
  if (frame_count > UINT32_MAX) {
    return Status::InvalidArgument("exact search: " + std::to_string(frame_count) +
                                   " frames: trellis frame indices are 32-bit");
  }
  if (!std::isfinite(rules_.eps) || rules_.eps < 0) {
    return Status::InvalidArgument("exact search: eps must be a non-negative number, not " +
                                   std::to_string(rules_.eps));
  }
  MOTIF_RETURN_IF_ERROR(ValidateClipStarts(rules_.clip_first_frames));
  if (columns->size() < count) columns->resize(count);
  if (count == 0) return Status::Ok();

  const DistanceKernel kernel(features_);
  const uint32_t block_frames = options_.query_block_frames;
  const uint64_t task_count = (count + block_frames - 1) / block_frames;
  std::vector<SearchStats> task_stats(task_count);
  std::vector<Status> task_status(task_count);
  tbb::task_arena arena(options_.threads > 0 ? static_cast<int>(options_.threads)
                                             : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, task_count, /*grainsize=*/1),
        [&](const tbb::blocked_range<uint64_t>& range) {
          for (uint64_t task_idx = range.begin(); task_idx != range.end(); ++task_idx) {
            const uint64_t offset = task_idx * block_frames;
            const uint32_t block_count =
                static_cast<uint32_t>(std::min<uint64_t>(block_frames, count - offset));
            try {
              SearchQueryBlock(features_, rules_, options_, kernel, first_column + offset,
                               block_count, columns->data() + offset, query,
                               reverse != nullptr ? reverse->data() + offset : nullptr,
                               &task_stats[task_idx]);
            } catch (const std::bad_alloc&) {
              task_status[task_idx] =
                  Status::ResourceExhausted("exact search: out of memory in columns from " +
                                            std::to_string(first_column + offset));
            }
          }
        });
  });
  for (const Status& status : task_status) MOTIF_RETURN_IF_ERROR(status);  // lowest task wins
  // Merged in task order (integer sums: the order does not matter, but it is fixed anyway).
  for (const SearchStats& task : task_stats) {
    stats->columns += task.columns;
    stats->distance_evaluations += task.distance_evaluations;
    stats->neighbours += task.neighbours;
    stats->capped_columns += task.capped_columns;
  }
  return Status::Ok();
}

}  // namespace motif
