#include "engine/cluster/instance_similarity.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/cluster/instance_interval_index.h"

namespace motif {

namespace {

struct DirectedCount {
  uint32_t from = 0;
  uint32_t to = 0;
  uint64_t shared = 0;
};

// What one instance has counted so far: (other instance, frames of this one that hit it), one
// entry per other instance and block span, summed when the instance is complete.
struct OpenInstance {
  std::vector<std::pair<uint32_t, uint64_t>> spans;
};

// Per-thread dense counters over all instances (O(instances) memory a thread): the hot loop
// touches an array, not a hash map. `touched` lists the entries to report and clear.
struct CountScratch {
  explicit CountScratch(size_t instances)
      : shared(instances, 0), last_column(instances, UINT64_MAX) {}
  std::vector<uint32_t> shared;
  std::vector<uint64_t> last_column;
  std::vector<uint32_t> touched;
};

// Adds columns [first, end) of `block` to instance `self`'s counts.
void CountColumns(const TrellisBlock& block, uint64_t first, uint64_t end, uint32_t self,
                  const InstanceIntervalIndex& index, CountScratch* scratch, OpenInstance* open,
                  uint64_t* scanned) {
  InstanceIntervalIndex::Cursor cursor(index);
  for (uint64_t column = first; column < end; ++column) {
    const uint64_t local = column - block.first_column;
    cursor.Reset();
    for (uint32_t entry = block.offsets[local]; entry < block.offsets[local + 1]; ++entry) {
      for (uint32_t other : cursor.Containing(block.neighbours[entry].frame)) {
        if (other == self || scratch->last_column[other] == column) continue;
        scratch->last_column[other] = column;  // a column counts once per other instance
        if (scratch->shared[other]++ == 0) scratch->touched.push_back(other);
      }
    }
    *scanned += block.offsets[local + 1] - block.offsets[local];
  }
  for (uint32_t other : scratch->touched) {
    open->spans.emplace_back(other, scratch->shared[other]);
    scratch->shared[other] = 0;
    scratch->last_column[other] = UINT64_MAX;
  }
  scratch->touched.clear();
}

// InvalidArgument unless the instances are non-empty ranges of the trellis's columns sorted by
// start, and every link joins two of them. *total_columns: the instances' columns.
Status CheckSimilarityInputs(const TrellisFileReader& trellis,
                             const std::vector<MotifInstance>& instances,
                             const std::vector<InstanceLink>& links, uint64_t* total_columns) {
  if (instances.size() >= UINT32_MAX) {
    return Status::InvalidArgument("too many instances: " + std::to_string(instances.size()));
  }
  *total_columns = 0;
  for (size_t id = 0; id < instances.size(); ++id) {
    const MotifInstance& instance = instances[id];
    if (instance.end <= instance.start || instance.end > trellis.column_count()) {
      return Status::InvalidArgument(
          "instance " + std::to_string(id) + " [" + std::to_string(instance.start) + ", " +
          std::to_string(instance.end) + ") is empty or outside the trellis's " +
          std::to_string(trellis.column_count()) + " columns");
    }
    if (id > 0 && instance.start < instances[id - 1].start) {
      return Status::InvalidArgument("instances are not sorted by start");
    }
    *total_columns += instance.length();
  }
  for (const InstanceLink& link : links) {
    if (link.a >= instances.size() || link.b >= instances.size() || link.a == link.b) {
      return Status::InvalidArgument("link (" + std::to_string(link.a) + ", " +
                                     std::to_string(link.b) + ") does not join two instances");
    }
  }
  return Status::Ok();
}

// Streams the trellis block by block (blocks no instance touches are not decoded), counting in
// parallel the frames each instance intersecting a block shares with the others; an instance's
// directions strong enough to keep are taken as soon as its last column has been read.
class SharedFrameCounter {
 public:
  SharedFrameCounter(const TrellisFileReader& trellis, const std::vector<MotifInstance>& instances,
                     const SimilarityOptions& options, SimilarityStats* stats)
      : trellis_(trellis),
        instances_(instances),
        options_(options),
        stats_(stats),
        index_(instances),
        instance_count_(static_cast<uint32_t>(instances.size())),
        arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic),
        open_(instance_count_),
        scratches_([count = instance_count_] { return CountScratch(count); }) {}

  // Every block; progress after each decoded one, out of `total_columns`.
  Status CountAll(uint64_t total_columns) {
    const uint64_t block_columns = trellis_.block_columns();
    for (uint64_t block_idx = 0; block_idx < trellis_.block_count(); ++block_idx) {
      const uint64_t block_first = block_idx * block_columns;
      const uint64_t block_end = std::min(block_first + block_columns, trellis_.column_count());
      UpdateActive(block_first, block_end);
      if (active_.empty()) continue;
      MOTIF_RETURN_IF_ERROR(trellis_.ReadBlock(block_idx, &block_, /*decode_distances=*/false));
      // The block is decoded: give its mapped pages back, or the whole file (about 500 bytes a
      // frame) would stay resident when the instances cover the archive (as the grower does).
      MOTIF_RETURN_IF_ERROR(trellis_.ReleaseBlocks(block_idx, block_idx + 1));
      ++stats_->blocks_decoded;
      CountActive(block_first, block_end);
      FinishBlock(block_first, block_end);
      if (options_.progress) options_.progress(columns_done_, total_columns);
    }
    return Status::Ok();
  }

  // The kept directions, (min id, max id, shared) each.
  std::vector<DirectedCount>& directed() { return directed_; }

 private:
  // The instances intersecting [block_first, block_end), ascending.
  void UpdateActive(uint64_t block_first, uint64_t block_end) {
    std::erase_if(active_, [&](uint32_t id) { return instances_[id].end <= block_first; });
    while (next_instance_ < instance_count_ && instances_[next_instance_].start < block_end) {
      active_.push_back(next_instance_++);
    }
  }

  void CountActive(uint64_t block_first, uint64_t block_end) {
    scanned_.assign(active_.size(), 0);
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, active_.size(), 1),
                        [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t slot = range.begin(); slot < range.end(); ++slot) {
                            const uint32_t id = active_[slot];
                            if (!open_[id]) open_[id] = std::make_unique<OpenInstance>();
                            const uint64_t first = std::max(instances_[id].start, block_first);
                            const uint64_t end = std::min(instances_[id].end, block_end);
                            CountColumns(block_, first, end, id, index_, &scratches_.local(),
                                         open_[id].get(), &scanned_[slot]);
                          }
                        });
    });
  }

  // The block's counts into the stats; instances whose last column was in this block are
  // complete: keep their strong directions.
  void FinishBlock(uint64_t block_first, uint64_t block_end) {
    for (size_t slot = 0; slot < active_.size(); ++slot) {
      const uint32_t id = active_[slot];
      stats_->neighbours_scanned += scanned_[slot];
      const uint64_t columns =
          std::min(instances_[id].end, block_end) - std::max(instances_[id].start, block_first);
      stats_->columns_read += columns;
      columns_done_ += columns;
      if (instances_[id].end > block_end) continue;
      KeepStrongDirections(id);
      open_[id].reset();
    }
  }

  // Sums instance `id`'s spans per other instance, in id order (deterministic whatever the
  // threads did), and keeps each direction with shared >= min_similarity of the shorter.
  void KeepStrongDirections(uint32_t id) {
    std::vector<std::pair<uint32_t, uint64_t>>& spans = open_[id]->spans;
    std::sort(spans.begin(), spans.end());
    for (size_t idx = 0; idx < spans.size();) {
      const uint32_t other = spans[idx].first;
      uint64_t shared = 0;
      for (; idx < spans.size() && spans[idx].first == other; ++idx) shared += spans[idx].second;
      const uint64_t shorter = std::min(instances_[id].length(), instances_[other].length());
      if (static_cast<double>(shared) >= options_.min_similarity * static_cast<double>(shorter)) {
        directed_.push_back({std::min(id, other), std::max(id, other), shared});
      }
    }
  }

  const TrellisFileReader& trellis_;
  const std::vector<MotifInstance>& instances_;
  const SimilarityOptions& options_;
  SimilarityStats* stats_;
  const InstanceIntervalIndex index_;
  const uint32_t instance_count_;
  tbb::task_arena arena_;
  std::vector<std::unique_ptr<OpenInstance>> open_;
  tbb::enumerable_thread_specific<CountScratch> scratches_;
  std::vector<uint32_t> active_;   // instances intersecting the current block, ascending
  std::vector<uint64_t> scanned_;  // per active slot
  std::vector<DirectedCount> directed_;
  uint32_t next_instance_ = 0;
  uint64_t columns_done_ = 0;
  TrellisBlock block_;
};

// Both directions of a pair become one similarity: the larger count over the shorter length.
std::vector<WeightedEdge> PairSimilarities(const std::vector<MotifInstance>& instances,
                                           std::vector<DirectedCount>* directed) {
  std::sort(directed->begin(), directed->end(), [](const DirectedCount& x, const DirectedCount& y) {
    if (x.from != y.from) return x.from < y.from;
    if (x.to != y.to) return x.to < y.to;
    return x.shared > y.shared;
  });
  std::vector<WeightedEdge> edges;
  for (size_t idx = 0; idx < directed->size(); ++idx) {
    if (idx > 0 && (*directed)[idx].from == (*directed)[idx - 1].from &&
        (*directed)[idx].to == (*directed)[idx - 1].to) {
      continue;  // the smaller direction of a pair already taken
    }
    const DirectedCount& pair = (*directed)[idx];
    const uint64_t shorter = std::min(instances[pair.from].length(), instances[pair.to].length());
    const double similarity =
        std::min(1.0, static_cast<double>(pair.shared) / static_cast<double>(shorter));
    edges.push_back({pair.from, pair.to, similarity});
  }
  directed->clear();
  directed->shrink_to_fit();
  return edges;
}

}  // namespace

Result<SimilarityGraph> BuildSimilarityGraph(const TrellisFileReader& trellis,
                                             const std::vector<MotifInstance>& instances,
                                             const std::vector<InstanceLink>& links,
                                             const SimilarityOptions& options,
                                             SimilarityStats* stats) {
  const auto started = std::chrono::steady_clock::now();
  SimilarityStats local_stats;
  if (stats == nullptr) stats = &local_stats;
  *stats = SimilarityStats();
  uint64_t total_columns = 0;
  MOTIF_RETURN_IF_ERROR(CheckSimilarityInputs(trellis, instances, links, &total_columns));

  std::vector<WeightedEdge> edges;
  {
    SharedFrameCounter counter(trellis, instances, options, stats);
    MOTIF_RETURN_IF_ERROR(counter.CountAll(total_columns));
    stats->directed_pairs = counter.directed().size();
    edges = PairSimilarities(instances, &counter.directed());
  }
  stats->similar_pairs = edges.size();
  if (options.link_weight > 0) {
    for (const InstanceLink& link : links) {
      edges.push_back({std::min(link.a, link.b), std::max(link.a, link.b), options.link_weight});
    }
  }
  stats->linked_pairs = links.size();
  const uint32_t instance_count = static_cast<uint32_t>(instances.size());
  SimilarityGraph graph = SimilarityGraph::FromEdges(instance_count, std::move(edges));
  stats->edges = graph.edge_count();
  stats->seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return graph;
}

}  // namespace motif
