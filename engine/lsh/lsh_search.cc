#include "engine/lsh/lsh_search.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/lsh/chain_sweep.h"
#include "engine/lsh/column_query.h"
#include "engine/lsh/lsh_tuning.h"
#include "engine/lsh/probe_sequence.h"
#include "engine/lsh/reverse_pass.h"

namespace motif {
namespace {

// InvalidArgument naming the search.
Status InvalidLshArgument(const std::string& what) {
  return Status::InvalidArgument("lsh search: " + what);
}

// Create's checks of the rules against the features (the rules' clip layout is filled in from
// the features when empty).
Status ValidateRules(const PoseFeatures& features, NeighbourRules* rules) {
  if (!(rules->eps > 0)) return InvalidLshArgument("eps must be > 0");
  if (rules->k_max == 0) return InvalidLshArgument("k_max must be > 0");
  // The features' clip layout is the one used (PoseFeatures::ClipOf); the rules may repeat it.
  if (rules->clip_first_frames.empty()) {
    rules->clip_first_frames = features.clip_first_frames();
  } else if (rules->clip_first_frames != features.clip_first_frames()) {
    return InvalidLshArgument("the rules' clip layout differs from the pose features' (" +
                              std::to_string(rules->clip_first_frames.size()) + " vs " +
                              std::to_string(features.clip_first_frames().size()) + " clips)");
  }
  return Status::Ok();
}

// Create's checks of the options against the features, in the order they are reported.
Status ValidateOptions(const PoseFeatures& features, const LshOptions& options) {
  auto invalid = InvalidLshArgument;
  const uint32_t dims = HashFamily::kDimsPerJoint * features.weighted_joint_count();
  if (dims == 0) return invalid("no weighted joint");
  if (options.tables == 0 || options.tables > 64) return invalid("tables must be in 1..64");
  if (options.hashes_per_table > HashFamily::kMaxHashesPerTable ||
      options.hashes_per_table + 1 > dims) {
    return invalid("hashes_per_table must be in 0.." +
                   std::to_string(std::min(HashFamily::kMaxHashesPerTable, dims - 1)));
  }
  if (options.probes_per_table == 0) return invalid("probes_per_table must be > 0");
  if (options.max_candidates == 0) return invalid("max_candidates must be > 0");
  if (options.max_entries == 0) return invalid("max_entries must be > 0");
  if (options.max_bucket_scan == 0) return invalid("max_bucket_scan must be > 0");
  if (options.bucket_width < 0 || !std::isfinite(options.bucket_width)) {
    return invalid("bucket_width must be >= 0");
  }
  if (features.frame_count() >= (uint64_t{1} << 32)) return invalid("2^32 frames or more");
  if (options.bucket_width == 0 && !(options.width_per_hash > 0)) {
    return invalid("width_per_hash must be > 0");
  }
  if (options.first_round_scan == 0) return invalid("first_round_scan must be > 0");
  if (options.shard_frames == 0) return invalid("shard_frames must be > 0");
  if (!(options.sparse_radius_factor > 0)) return invalid("sparse_radius_factor must be > 0");
  if (options.chain_advance > 16) return invalid("chain_advance must be in 0..16");
  if (options.chain_columns > 1 && options.chained_max_candidates == 0) {
    return invalid("chained_max_candidates must be > 0");
  }
  if (options.chain_probe_every == 0) return invalid("chain_probe_every must be > 0");
  return Status::Ok();
}

// How a search's columns [first_column, end_column) are cut into parallel tasks: one per aligned
// chain (or per 64 columns without chaining). A chain is computed whole whenever a range asks
// for one of its columns (only its columns inside the range are returned and counted; without
// sweeps, it stops at the range's end): a column is the same whichever range asked for it.
struct TaskLayout {
  uint64_t first_column = 0;
  uint64_t end_column = 0;
  bool chained = false;
  uint64_t grain = 64;       // columns per task
  uint32_t sweeps = 0;       // chain sweeps
  uint64_t compute_end = 0;  // no task computes a column at or after this
  uint64_t first_task = 0;
  uint64_t task_count = 0;

  static TaskLayout For(const LshOptions& options, uint64_t first_column, uint64_t count,
                        uint64_t frame_count) {
    TaskLayout layout;
    layout.first_column = first_column;
    layout.end_column = first_column + count;
    layout.chained = options.chain_columns > 1;
    layout.grain = layout.chained ? options.chain_columns : 64;
    layout.sweeps = layout.chained ? options.chain_sweeps : 0;
    layout.compute_end = layout.sweeps ? frame_count : layout.end_column;
    layout.first_task = first_column / layout.grain;
    layout.task_count = (layout.end_column + layout.grain - 1) / layout.grain - layout.first_task;
    return layout;
  }
  // The columns task `task` computes: [TaskBegin, TaskEnd).
  uint64_t TaskBegin(uint64_t task) const {
    const uint64_t task_first = (first_task + task) * grain;
    return chained ? task_first : std::max(task_first, first_column);
  }
  uint64_t TaskEnd(uint64_t task) const {
    return std::min((first_task + task + 1) * grain, compute_end);
  }
  bool InRange(uint64_t column) const { return column >= first_column && column < end_column; }
};

// What one task counts of the columns it returns (integers: the sums do not depend on how the
// tasks were split among threads).
struct TaskTotals {
  SearchStats search;
  LshQueryStats lsh;
};

// The scratch of one TBB range and the steps of a task over it: the columns of a chain in
// order (each seeded with its predecessor's), their reverse frames, the chain sweeps, and the
// columns in range handed out.
class ChainWorker {
 public:
  ChainWorker(const LshQueryContext& context, const TaskLayout& layout,
              const ReverseQuery* reverse_query, std::vector<std::vector<Neighbour>>* reverse)
      : context_(context),
        layout_(layout),
        reverse_query_(reverse_query),
        reverse_(reverse),
        query_(context),
        sweep_(context.features, context.rules, context.options.chain_advance) {
    if (reverse_ != nullptr) reverse_pass_.emplace(context);
  }

  void RunTask(uint64_t task, std::vector<std::vector<Neighbour>>* columns, TaskTotals* totals) {
    const uint64_t begin = layout_.TaskBegin(task);
    const size_t size = layout_.TaskEnd(task) - begin;
    chain_columns_.resize(std::max(chain_columns_.size(), size));
    work_.assign(size, ColumnWork{});
    for (size_t idx = 0; idx < size; ++idx) FindColumn(begin, idx);
    SweepChain(begin, size);
    HandOut(begin, size, columns, totals);
  }

 private:
  // Column begin + idx, and its reverse frames if the range asked for them.
  void FindColumn(uint64_t begin, size_t idx) {
    const uint64_t column = begin + idx;
    const bool seeded = layout_.chained && idx > 0;
    std::vector<Neighbour>* found = reverse_ != nullptr && layout_.InRange(column)
                                        ? &(*reverse_)[column - layout_.first_column]
                                        : nullptr;
    query_.Run(column, seeded ? &chain_columns_[idx - 1] : nullptr, &chain_columns_[idx],
               &work_[idx], reverse_query_, found);
    if (found != nullptr) FindReverse(column, seeded, found);
  }

  // The forward query's verified older frames (in *found), and the wider reverse scan's. A column
  // whose predecessor's reverse frames are known spends a chained column's probing budget on
  // average (every column scans in reverse).
  void FindReverse(uint64_t column, bool seeded, std::vector<Neighbour>* found) {
    const LshOptions& options = context_.options;
    const bool chained = seeded && column > layout_.first_column;
    const uint32_t chained_budget =
        std::max<uint32_t>(1, options.chained_max_candidates / options.chain_probe_every);
    reverse_pass_->Run(column, *reverse_query_, chained ? chained_budget : options.max_candidates,
                       chained ? &previous_reverse_ : nullptr, found);
    std::sort(found->begin(), found->end(),
              [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
    found->erase(
        std::unique(found->begin(), found->end(),
                    [](const Neighbour& a, const Neighbour& b) { return a.frame == b.frame; }),
        found->end());
    if (layout_.chained) previous_reverse_ = *found;
  }

  // The chain sweeps, alternately backward (from the successor) and forward.
  void SweepChain(uint64_t begin, size_t size) {
    for (uint32_t sweep = 0; sweep < layout_.sweeps && size > 1; ++sweep) {
      if (sweep % 2 == 0) {
        for (size_t idx = size - 1; idx-- > 0;) {
          sweep_.Sweep(begin + idx, chain_columns_[idx + 1], +1, &chain_columns_[idx], &work_[idx]);
        }
      } else {
        for (size_t idx = 1; idx < size; ++idx) {
          sweep_.Sweep(begin + idx, chain_columns_[idx - 1], -1, &chain_columns_[idx], &work_[idx]);
        }
      }
    }
  }

  // The task's columns inside the range, and their work.
  void HandOut(uint64_t begin, size_t size, std::vector<std::vector<Neighbour>>* columns,
               TaskTotals* totals) const {
    for (size_t idx = 0; idx < size; ++idx) {
      const uint64_t column = begin + idx;
      if (!layout_.InRange(column)) continue;
      std::vector<Neighbour>& out = (*columns)[column - layout_.first_column];
      out.assign(chain_columns_[idx].begin(), chain_columns_[idx].end());
      totals->search.columns += 1;
      totals->search.distance_evaluations += work_[idx].evaluations;
      totals->search.neighbours += out.size();
      totals->search.capped_columns += work_[idx].capped ? 1 : 0;
      totals->lsh.Add(work_[idx].lsh);
    }
  }

  const LshQueryContext& context_;
  const TaskLayout& layout_;
  const ReverseQuery* reverse_query_;
  std::vector<std::vector<Neighbour>>* reverse_;
  ColumnQuery query_;
  ChainSweep sweep_;
  std::optional<ReversePass> reverse_pass_;
  std::vector<std::vector<Neighbour>> chain_columns_;
  std::vector<ColumnWork> work_;
  std::vector<Neighbour> previous_reverse_;  // the chain's previous reverse frames
};

}  // namespace

LshSearch::LshSearch(const PoseFeatures& features, NeighbourRules rules, LshOptions options,
                     HashFamily family, LshIndex index, float extension_radius)
    : features_(features),
      rules_(std::move(rules)),
      options_(std::move(options)),
      family_(std::move(family)),
      index_(std::move(index)),
      extension_radius_(extension_radius) {}

Result<std::unique_ptr<LshSearch>> LshSearch::Create(const PoseFeatures& features,
                                                     NeighbourRules rules,
                                                     const LshOptions& options, RankGroup* ranks) {
  return Make(features, std::move(rules), options, nullptr, ranks);
}

Result<std::unique_ptr<LshSearch>> LshSearch::CreateWithIndex(const PoseFeatures& features,
                                                              NeighbourRules rules,
                                                              const LshOptions& options,
                                                              LshIndex index) {
  if (options.hashes_per_table == 0 || options.bucket_width == 0) {
    return Status::InvalidArgument("lsh search: a given index needs the hash family's sizes");
  }
  if (index.frame_count() != features.frame_count() || index.table_count() != options.tables) {
    return Status::InvalidArgument(
        "lsh search: the given index holds " + std::to_string(index.frame_count()) + " frames in " +
        std::to_string(index.table_count()) + " tables, not " +
        std::to_string(features.frame_count()) + " in " + std::to_string(options.tables));
  }
  return Make(features, std::move(rules), options, &index, nullptr);
}

Result<std::unique_ptr<LshSearch>> LshSearch::Make(const PoseFeatures& features,
                                                   NeighbourRules rules, const LshOptions& options,
                                                   LshIndex* given, RankGroup* ranks) {
  MOTIF_RETURN_IF_ERROR(ValidateRules(features, &rules));
  MOTIF_RETURN_IF_ERROR(ValidateOptions(features, options));
  MOTIF_ASSIGN_OR_RETURN(const SearchScale scale,
                         EstimateSearchScale(features, rules, options, ranks));
  LshOptions used =
      ResolveLshOptions(options, features.frame_count(), features.weighted_joint_count(), scale);
  HashFamily family = HashFamily::Draw(features.weights(), used.tables, used.hashes_per_table,
                                       used.bucket_width, used.seed);
  LshIndex index;
  if (given != nullptr) {
    index = std::move(*given);
  } else {
    MOTIF_ASSIGN_OR_RETURN(index,
                           LshIndex::Build(features, family, used.shard_frames, used.threads,
                                           used.ranking == LshRanking::kPositionCode, ranks));
  }
  const float extension_radius = options.sparse_radius_factor * scale.radius;
  return std::unique_ptr<LshSearch>(new LshSearch(features, std::move(rules), std::move(used),
                                                  std::move(family), std::move(index),
                                                  extension_radius));
}

Status LshSearch::SearchColumns(uint64_t first_column, uint64_t count,
                                std::vector<std::vector<Neighbour>>* columns,
                                SearchStats* stats) const {
  return SearchColumns(first_column, count, columns, stats, nullptr);
}

Status LshSearch::SearchColumns(uint64_t first_column, uint64_t count,
                                std::vector<std::vector<Neighbour>>* columns, SearchStats* stats,
                                LshQueryStats* lsh_stats) const {
  return Search(first_column, count, nullptr, columns, nullptr, stats, lsh_stats);
}

Status LshSearch::SearchColumnsAndReverse(uint64_t first_column, uint64_t count,
                                          const ReverseQuery& query,
                                          std::vector<std::vector<Neighbour>>* columns,
                                          std::vector<std::vector<Neighbour>>* reverse,
                                          SearchStats* stats) const {
  MOTIF_RETURN_IF_ERROR(CheckReverseQuery(query, features_.frame_count(), "lsh search"));
  if (reverse->size() < count) reverse->resize(count);
  return Search(first_column, count, &query, columns, reverse, stats, nullptr);
}

Status LshSearch::Search(uint64_t first_column, uint64_t count, const ReverseQuery* reverse_query,
                         std::vector<std::vector<Neighbour>>* columns,
                         std::vector<std::vector<Neighbour>>* reverse, SearchStats* stats,
                         LshQueryStats* lsh_stats) const {
  if (first_column + count > features_.frame_count()) {
    return Status::InvalidArgument("lsh search: columns [" + std::to_string(first_column) + ", " +
                                   std::to_string(first_column + count) + ") beyond " +
                                   std::to_string(features_.frame_count()) + " frames");
  }
  if (columns->size() < count) columns->resize(count);
  if (count == 0) return Status::Ok();
  const LshQueryContext context = this->context();
  const TaskLayout layout = TaskLayout::For(options_, first_column, count, features_.frame_count());
  std::vector<TaskTotals> totals(layout.task_count);  // each task writes its own slot
  tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, layout.task_count, 1),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        ChainWorker worker(context, layout, reverse_query, reverse);
                        for (uint64_t task = range.begin(); task != range.end(); ++task) {
                          worker.RunTask(task, columns, &totals[task]);
                        }
                      });
  });
  for (const TaskTotals& task_totals : totals) {
    if (stats) {
      stats->columns += task_totals.search.columns;
      stats->distance_evaluations += task_totals.search.distance_evaluations;
      stats->neighbours += task_totals.search.neighbours;
      stats->capped_columns += task_totals.search.capped_columns;
    }
    if (lsh_stats) lsh_stats->Add(task_totals.lsh);
  }
  return Status::Ok();
}

std::vector<LshSearch::ProbeInfo> LshSearch::ProbeSequence(uint64_t column) const {
  motif::ProbeSequence probes(family_, index_);
  probes.Prepare(features_.frame(column), options_.probes_per_table);
  std::vector<ProbeInfo> sequence;
  for (const BucketProbe& probe : probes.probes()) {
    sequence.push_back({probe.table_idx, probe.key, std::sqrt(probe.score)});
  }
  return sequence;
}

}  // namespace motif
