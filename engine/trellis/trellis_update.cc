#include "engine/trellis/trellis_update.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "common/seconds_since.h"
#include "formats/trellis_file/trellis_block_codec.h"

namespace motif {
namespace {

using Clock = std::chrono::steady_clock;

// The zstd level of every trellis this engine writes (TrellisFileWriterOptions' default): a
// rewritten block must encode to the bytes a full build would write.
const int kZstdLevel = TrellisFileWriterOptions{}.zstd_level;

// A new frame found within an old column's threshold by the new frame's own query.
struct ReversePair {
  uint32_t old_frame;
  uint32_t new_frame;
  float distance;  // exact (the search's)
};

// The thresholds of the old columns from `first_block`'s first column on (ColumnThreshold);
// columns before first_block (already written by an interrupted update) get -1: nothing is
// wanted there.
Status ComputeThresholds(const TrellisFileReader& previous, uint64_t first_block,
                         tbb::task_arena& arena,
                         const std::function<void(uint64_t, uint64_t)>& progress,
                         std::vector<float>* thresholds) {
  const TrellisParams& params = previous.params();
  const uint64_t block_count = previous.block_count();
  thresholds->assign(params.frame_count, -1.0f);
  if (first_block >= block_count) return Status::Ok();
  std::vector<Status> block_status(block_count - first_block);
  std::atomic<uint64_t> done{0};
  tbb::enumerable_thread_specific<TrellisBlock> scratch;
  arena.execute([&] {
    tbb::parallel_for(first_block, block_count, [&](uint64_t block_idx) {
      TrellisBlock& block = scratch.local();
      Status status = previous.ReadBlock(block_idx, &block, /*decode_distances=*/true);
      if (!status.ok()) {
        block_status[block_idx - first_block] = status;
        return;
      }
      for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
        const uint32_t begin = block.offsets[column_idx];
        (*thresholds)[block.first_column + column_idx] =
            ColumnThreshold(block.neighbours.data() + begin, block.offsets[column_idx + 1] - begin,
                            params.eps, params.k_max);
      }
      // A memory hint; it fails only for a block out of range, and block_idx is in range.
      (void)previous.ReleaseBlocks(block_idx, block_idx + 1);
      if (progress) progress(done.fetch_add(1) + 1, block_count - first_block);
    });
  });
  for (const Status& status : block_status) MOTIF_RETURN_IF_ERROR(status);  // the lowest block
  return Status::Ok();
}

// Buffers reused across blocks (a block's columns and its encoded bytes are megabytes: fresh
// ones would be mapped and faulted in again for every block).
template <typename T>
class BufferPool {
 public:
  std::unique_ptr<T> Take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return std::make_unique<T>();
    std::unique_ptr<T> buffer = std::move(free_.back());
    free_.pop_back();
    return buffer;
  }
  void Give(std::unique_ptr<T> buffer) {
    if (!buffer) return;
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(buffer));
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<T>> free_;
};

using Columns = std::vector<std::vector<Neighbour>>;

// Per-thread scratch of MergeColumn.
struct MergeScratch {
  std::vector<uint16_t> codes;  // old entries' codes, then the candidates'
  std::vector<uint16_t> order;  // a copy for nth_element
  std::vector<uint8_t> keep;    // per entry, in the order of `codes`
  struct Tied {
    float distance;
    uint32_t frame;
    uint32_t entry;
  };
  std::vector<Tied> tied;
};

// Column `column`'s k_max nearest among its old entries (sorted by frame, stored distances) and
// its candidates (new frames, all after the old entries, sorted by frame, exact distances), in
// FinishColumn's order (distance, then frame), into *out sorted by frame. True if a candidate
// entered. Only the stored codes are known of the old entries; the code is monotone in the
// distance, so entries are ordered by code, and only those sharing the code at the cut get
// their exact distance computed again (PoseDistance: the bits the search computed). The old
// entries keep their order and every candidate's frame is above them, so the result needs no
// sort.
bool MergeColumn(const PoseFeatures& features, uint64_t column, float eps, uint32_t k_max,
                 const Neighbour* old_entries, size_t old_count, const ReversePair* candidates,
                 size_t candidate_count, std::vector<Neighbour>* out, uint64_t* recomputed,
                 MergeScratch* scratch) {
  out->assign(old_entries, old_entries + old_count);
  if (candidate_count == 0) return false;
  if (old_count + candidate_count <= k_max) {
    for (size_t idx = 0; idx < candidate_count; ++idx) {
      out->push_back({candidates[idx].new_frame, candidates[idx].distance});
    }
    return true;
  }
  const size_t total = old_count + candidate_count;
  std::vector<uint16_t>& codes = scratch->codes;
  codes.resize(total);
  for (size_t idx = 0; idx < old_count; ++idx) {
    codes[idx] = trellis_file::QuantizeDistance(old_entries[idx].distance, eps);
  }
  for (size_t idx = 0; idx < candidate_count; ++idx) {
    codes[old_count + idx] = trellis_file::QuantizeDistance(candidates[idx].distance, eps);
  }
  scratch->order.assign(codes.begin(), codes.end());
  std::nth_element(scratch->order.begin(), scratch->order.begin() + (k_max - 1),
                   scratch->order.end());
  const uint16_t cut_code = scratch->order[k_max - 1];
  // Kept for sure: codes below the cut. Out: codes above. The cut's code: as many as fit,
  // nearest first by exact distance (then frame).
  std::vector<uint8_t>& keep = scratch->keep;
  keep.assign(total, 0);
  size_t below = 0;
  size_t at_cut = 0;
  for (size_t idx = 0; idx < total; ++idx) {
    if (codes[idx] < cut_code) {
      keep[idx] = 1;
      ++below;
    } else if (codes[idx] == cut_code) {
      ++at_cut;
    }
  }
  const size_t room = k_max - below;
  if (at_cut <= room) {
    for (size_t idx = 0; idx < total; ++idx) keep[idx] |= codes[idx] == cut_code;
  } else {
    std::vector<MergeScratch::Tied>& tied = scratch->tied;
    tied.clear();
    for (size_t idx = 0; idx < total; ++idx) {
      if (codes[idx] != cut_code) continue;
      if (idx < old_count) {
        ++*recomputed;
        tied.push_back({PoseDistance(features, column, old_entries[idx].frame),
                        old_entries[idx].frame, static_cast<uint32_t>(idx)});
      } else {
        const ReversePair& candidate = candidates[idx - old_count];
        tied.push_back({candidate.distance, candidate.new_frame, static_cast<uint32_t>(idx)});
      }
    }
    std::sort(tied.begin(), tied.end(),
              [](const MergeScratch::Tied& a, const MergeScratch::Tied& b) {
                return a.distance != b.distance ? a.distance < b.distance : a.frame < b.frame;
              });
    for (size_t idx = 0; idx < room; ++idx) keep[tied[idx].entry] = 1;
  }
  out->clear();
  bool entered = false;
  for (size_t idx = 0; idx < old_count; ++idx) {
    if (keep[idx]) out->push_back(old_entries[idx]);
  }
  for (size_t idx = 0; idx < candidate_count; ++idx) {
    if (keep[old_count + idx]) {
      out->push_back({candidates[idx].new_frame, candidates[idx].distance});
      entered = true;
    }
  }
  return entered;
}

// One output block on its way through the merge pipeline.
struct OutputBlock {
  uint64_t block_idx = 0;
  Status status;
  const uint8_t* bytes = nullptr;  // the block to append: into `owned` or the old file
  uint64_t size = 0;
  std::unique_ptr<std::string> owned;
  std::unique_ptr<Columns> columns;  // the block's columns, when they were at hand or needed
  bool copied = false;               // an old block copied unchanged
  bool rewritten = false;            // an old block with changed columns (or the mixed block)
  uint64_t changed_columns = 0;
  uint64_t recomputed = 0;
};

}  // namespace

float ColumnThreshold(const Neighbour* entries, size_t count, float eps, uint32_t k_max) {
  if (count < k_max) return eps;
  float farthest = 0;
  for (size_t idx = 0; idx < count; ++idx) farthest = std::max(farthest, entries[idx].distance);
  // As stored: a distance decoded from its code is the same whatever it was before.
  farthest = trellis_file::DequantizeDistance(trellis_file::QuantizeDistance(farthest, eps), eps);
  return std::min(eps, farthest + static_cast<float>(2 * trellis_file::QuantizationBound(eps)));
}

Result<TrellisUpdateReport> UpdateTrellis(const TrellisFileReader& previous,
                                          const PoseFeatures& features, const NeighbourRules& rules,
                                          const NeighbourSearch& search,
                                          const TrellisParams& params, const std::string& out_path,
                                          const TrellisUpdateOptions& options) {
  const TrellisParams& old_params = previous.params();
  const uint64_t old_columns = previous.column_count();
  const uint64_t frame_count = features.frame_count();
  auto invalid = [&](const std::string& what) {
    return Status::InvalidArgument("trellis update of " + previous.path() + ": " + what);
  };
  if (old_params.eps != params.eps || old_params.k_max != params.k_max ||
      old_params.exclusion_frames != params.exclusion_frames ||
      old_params.weights_hash != params.weights_hash) {
    return invalid("eps, k_max, exclusion or joint weights differ from the new trellis's");
  }
  if (params.eps != rules.eps || params.k_max != rules.k_max ||
      params.exclusion_frames != rules.exclusion_frames) {
    return invalid("the search's rules differ from the new trellis's parameters");
  }
  if (params.frame_count != frame_count || old_columns > frame_count) {
    return invalid("the old trellis has " + std::to_string(old_columns) + " columns, the archive " +
                   std::to_string(frame_count) + " frames, the new parameters " +
                   std::to_string(params.frame_count));
  }
  auto progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (options.progress) options.progress(stage, done, total);
  };

  TrellisUpdateReport report;
  report.old_columns = old_columns;
  report.new_columns = frame_count - old_columns;
  TrellisFileWriterOptions writer_options;
  writer_options.block_columns = previous.block_columns();
  writer_options.zstd_level = kZstdLevel;
  writer_options.file_system = options.file_system;
  // Blocks come faster than a disk syncs them; Finish syncs the file before its rename.
  writer_options.sync_each_block = false;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileWriter> writer,
                         TrellisFileWriter::OpenOrResume(out_path, params, writer_options));
  const uint64_t block_columns = writer->block_columns();
  // next_column is a multiple of B, or N when every block was written (an update interrupted
  // while finishing).
  const uint64_t first_out_block = (writer->next_column() + block_columns - 1) / block_columns;
  const uint64_t out_blocks = (frame_count + block_columns - 1) / block_columns;
  report.resumed_from_column = writer->next_column();
  // Blocks [0, mixed_block) hold old columns only; from mixed_block on they hold new columns
  // (mixed_block itself also the last old ones when old_columns is not a multiple of B).
  const uint64_t mixed_block = old_columns / block_columns;
  const bool old_blocks_left = first_out_block * block_columns < old_columns;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);

  // 1. Thresholds of the old columns still to write: saved by the previous update, or decoded.
  Clock::time_point start = Clock::now();
  std::vector<float> computed_thresholds;
  const std::vector<float>* thresholds = nullptr;
  if (old_blocks_left) {
    if (options.thresholds != nullptr && options.thresholds->size() == old_columns) {
      thresholds = options.thresholds;
    } else {
      progress("thresholds", 0, previous.block_count() - first_out_block);
      MOTIF_RETURN_IF_ERROR(ComputeThresholds(
          previous, first_out_block, arena,
          [&](uint64_t done, uint64_t total) { progress("thresholds", done, total); },
          &computed_thresholds));
      thresholds = &computed_thresholds;
    }
  }
  // The new trellis's thresholds, when every block goes through this update.
  std::vector<float>* next_thresholds =
      report.resumed_from_column == 0 ? options.next_thresholds : nullptr;
  if (options.next_thresholds) options.next_thresholds->clear();
  if (next_thresholds) next_thresholds->assign(frame_count, params.eps);
  auto set_thresholds = [&](uint64_t first_column, const Columns& columns) {
    if (next_thresholds == nullptr) return;
    for (size_t idx = 0; idx < columns.size(); ++idx) {
      (*next_thresholds)[first_column + idx] =
          ColumnThreshold(columns[idx].data(), columns[idx].size(), params.eps, params.k_max);
    }
  };
  report.thresholds_seconds = SecondsSince(start);

  // 2. The new columns, block by block of the output: whole new blocks are encoded at once
  // (and kept for the block sink), the new columns of the mixed block are kept for the merge.
  // With old blocks still to write, the queries also report the old columns they enter.
  start = Clock::now();
  const uint64_t search_first =
      old_blocks_left ? old_columns : std::max(old_columns, writer->next_column());
  std::vector<ReversePair> pairs;
  Columns mixed_new_columns;  // [old_columns, the mixed end)
  std::vector<std::unique_ptr<std::string>> new_block_bytes(out_blocks);
  std::vector<std::unique_ptr<Columns>> new_block_columns(out_blocks);
  {
    trellis_file::BlockEncoder encoder(kZstdLevel);
    ReverseQuery query;
    query.frame_limit = old_columns;
    query.thresholds = thresholds ? thresholds->data() : nullptr;
    Columns columns;
    Columns reverse;
    progress("new columns", 0, frame_count - search_first);
    for (uint64_t first = search_first; first < frame_count;) {
      const uint64_t block_idx = first / block_columns;
      const uint64_t end = std::min(frame_count, (block_idx + 1) * block_columns);
      columns.clear();
      if (old_blocks_left) {
        MOTIF_RETURN_IF_ERROR(search.SearchColumnsAndReverse(first, end - first, query, &columns,
                                                             &reverse, &report.search_stats));
        for (uint64_t idx = 0; idx < end - first; ++idx) {
          for (const Neighbour& found : reverse[idx]) {
            pairs.push_back({found.frame, static_cast<uint32_t>(first + idx), found.distance});
          }
        }
      } else {
        MOTIF_RETURN_IF_ERROR(
            search.SearchColumns(first, end - first, &columns, &report.search_stats));
      }
      if (first % block_columns != 0) {
        mixed_new_columns = std::move(columns);  // the mixed block's new columns
        columns = {};
      } else if (block_idx >= first_out_block) {
        trellis_file::BlockHandle handle;
        new_block_bytes[block_idx] = std::make_unique<std::string>();
        MOTIF_RETURN_IF_ERROR(
            encoder.Encode(first, columns, params.eps, new_block_bytes[block_idx].get(), &handle));
        set_thresholds(first, columns);
        if (options.on_block) {
          new_block_columns[block_idx] = std::make_unique<Columns>(std::move(columns));
          columns = {};
        }
      }
      progress("new columns", end - search_first, frame_count - search_first);
      first = end;
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const ReversePair& a, const ReversePair& b) {
    return a.old_frame != b.old_frame ? a.old_frame < b.old_frame : a.new_frame < b.new_frame;
  });
  report.reverse_candidates = pairs.size();
  report.search_seconds = SecondsSince(start);

  // 3. The output blocks in order: old blocks copied or merged, the mixed block, the new blocks.
  // Blocks are prepared in parallel and appended (and given to the sink) in order.
  start = Clock::now();
  tbb::enumerable_thread_specific<std::unique_ptr<trellis_file::BlockEncoder>> encoders(
      [] { return std::make_unique<trellis_file::BlockEncoder>(kZstdLevel); });
  tbb::enumerable_thread_specific<TrellisBlock> blocks;
  tbb::enumerable_thread_specific<MergeScratch> merge_scratch;
  BufferPool<Columns> column_pool;
  BufferPool<std::string> byte_pool;
  auto prepare = [&](OutputBlock* out) {
    const uint64_t block_idx = out->block_idx;
    const uint64_t first_column = block_idx * block_columns;
    const uint64_t end_column = std::min(frame_count, first_column + block_columns);
    if (first_column >= old_columns) {  // a whole new block
      out->owned = std::move(new_block_bytes[block_idx]);
      out->columns = std::move(new_block_columns[block_idx]);
      out->bytes = reinterpret_cast<const uint8_t*>(out->owned->data());
      out->size = out->owned->size();
      return;
    }
    const auto pairs_begin = std::lower_bound(
        pairs.begin(), pairs.end(), first_column,
        [](const ReversePair& pair, uint64_t column) { return pair.old_frame < column; });
    const auto pairs_end = std::lower_bound(
        pairs_begin, pairs.end(), end_column,
        [](const ReversePair& pair, uint64_t column) { return pair.old_frame < column; });
    const bool copy = pairs_begin == pairs_end && end_column <= old_columns;
    if (copy) {
      out->status = previous.ReadEncodedBlock(block_idx, &out->bytes, &out->size);
      out->copied = true;
      if (next_thresholds) {
        std::copy(thresholds->begin() + first_column, thresholds->begin() + end_column,
                  next_thresholds->begin() + first_column);
      }
      if (!options.on_block || !out->status.ok()) return;
    }
    TrellisBlock& block = blocks.local();
    out->status = previous.ReadBlock(block_idx, &block, /*decode_distances=*/true);
    if (!out->status.ok()) return;
    out->columns = column_pool.Take();
    Columns& columns = *out->columns;
    columns.resize(end_column - first_column);
    auto pair = pairs_begin;
    for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
      const uint64_t column = first_column + column_idx;
      const auto column_pairs_begin = pair;
      while (pair != pairs_end && pair->old_frame == column) ++pair;
      const uint32_t begin = block.offsets[column_idx];
      const uint32_t end = block.offsets[column_idx + 1];
      if (MergeColumn(features, column, params.eps, params.k_max, block.neighbours.data() + begin,
                      end - begin, pairs.data() + (column_pairs_begin - pairs.begin()),
                      static_cast<size_t>(pair - column_pairs_begin), &columns[column_idx],
                      &out->recomputed, &merge_scratch.local())) {
        ++out->changed_columns;
      }
    }
    if (copy) return;  // decoded for the sink only
    for (uint64_t column = old_columns; column < end_column; ++column) {
      columns[column - first_column] = std::move(mixed_new_columns[column - old_columns]);
    }
    if (first_column < old_columns || end_column > old_columns)
      set_thresholds(first_column, columns);
    trellis_file::BlockHandle handle;
    out->owned = byte_pool.Take();
    out->status =
        encoders.local()->Encode(first_column, columns, params.eps, out->owned.get(), &handle);
    out->bytes = reinterpret_cast<const uint8_t*>(out->owned->data());
    out->size = out->owned->size();
    out->rewritten = true;
  };

  Status failure;
  uint64_t next_block = first_out_block;
  progress("merge", 0, out_blocks - first_out_block);
  arena.execute([&] {
    tbb::parallel_pipeline(
        2 * static_cast<size_t>(arena.max_concurrency()),
        tbb::make_filter<void, std::shared_ptr<OutputBlock>>(
            tbb::filter_mode::serial_in_order,
            [&](tbb::flow_control& control) -> std::shared_ptr<OutputBlock> {
              if (next_block >= out_blocks || !failure.ok()) {
                control.stop();
                return nullptr;
              }
              auto out = std::make_shared<OutputBlock>();
              out->block_idx = next_block++;
              return out;
            }) &
            tbb::make_filter<std::shared_ptr<OutputBlock>, std::shared_ptr<OutputBlock>>(
                tbb::filter_mode::parallel,
                [&](std::shared_ptr<OutputBlock> out) {
                  try {
                    prepare(out.get());
                  } catch (const std::bad_alloc&) {
                    out->status = Status::ResourceExhausted("trellis update: out of memory");
                  }
                  return out;
                }) &
            tbb::make_filter<std::shared_ptr<OutputBlock>, void>(
                tbb::filter_mode::serial_in_order, [&](std::shared_ptr<OutputBlock> out) {
                  if (!failure.ok()) return;
                  Status status = out->status;
                  if (status.ok()) status = writer->AppendEncodedBlock(out->bytes, out->size);
                  const uint64_t first_column = out->block_idx * block_columns;
                  if (status.ok() && options.on_block && out->columns) {
                    status = options.on_block(first_column, *out->columns);
                  }
                  if (!status.ok()) {
                    failure = status;
                    return;
                  }
                  if (out->block_idx < previous.block_count()) {
                    // A memory hint; it fails only for a block out of range (checked above).
                    (void)previous.ReleaseBlocks(out->block_idx, out->block_idx + 1);
                  }
                  if (first_column >= old_columns || out->block_idx == mixed_block) {
                    ++report.new_blocks;
                  }
                  if (out->copied) ++report.copied_blocks;
                  if (out->rewritten && first_column + block_columns <= old_columns) {
                    ++report.rewritten_blocks;
                  }
                  report.changed_columns += out->changed_columns;
                  report.exact_recomputations += out->recomputed;
                  if (first_column < old_columns) {
                    column_pool.Give(std::move(out->columns));
                    byte_pool.Give(std::move(out->owned));
                  }
                  progress("merge", out->block_idx + 1 - first_out_block,
                           out_blocks - first_out_block);
                }));
  });
  MOTIF_RETURN_IF_ERROR(failure);
  MOTIF_RETURN_IF_ERROR(writer->Finish());
  report.merge_seconds = SecondsSince(start);
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> finished,
                         TrellisFileReader::Open(out_path));
  report.neighbours = finished->neighbour_count();
  return report;
}

}  // namespace motif
