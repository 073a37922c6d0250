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

// One update, step by step (UpdateTrellis): the checks, the old columns' thresholds, the new
// columns' search, then the output blocks written in order.
class TrellisUpdater {
 public:
  TrellisUpdater(const TrellisFileReader& previous, const PoseFeatures& features,
                 const NeighbourRules& rules, const NeighbourSearch& search,
                 const TrellisParams& params, const std::string& out_path,
                 const TrellisUpdateOptions& options)
      : previous_(previous),
        features_(features),
        rules_(rules),
        search_(search),
        params_(params),
        out_path_(out_path),
        options_(options),
        old_columns_(previous.column_count()),
        frame_count_(features.frame_count()),
        arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {}

  Result<TrellisUpdateReport> Run();

 private:
  Status Check() const;
  Status OpenWriter();
  Status PrepareThresholds();
  Status SearchNewColumns();
  void KeepNewBlock(uint64_t first, Columns* columns, trellis_file::BlockEncoder* encoder,
                    Status* status);
  void SetThresholds(uint64_t first_column, const Columns& columns);
  void PrepareBlock(OutputBlock* out);
  void CopyBlock(OutputBlock* out, uint64_t first_column, uint64_t end_column);
  void MergeBlock(OutputBlock* out, uint64_t first_column, uint64_t end_column, bool copied);
  Status WriteBlocks();
  void AppendBlock(OutputBlock* out);
  void Progress(const std::string& stage, uint64_t done, uint64_t total) const {
    if (options_.progress) options_.progress(stage, done, total);
  }

  const TrellisFileReader& previous_;
  const PoseFeatures& features_;
  const NeighbourRules& rules_;
  const NeighbourSearch& search_;
  const TrellisParams& params_;
  const std::string& out_path_;
  const TrellisUpdateOptions& options_;
  const uint64_t old_columns_;
  const uint64_t frame_count_;
  tbb::task_arena arena_;
  TrellisUpdateReport report_;
  std::unique_ptr<TrellisFileWriter> writer_;
  uint64_t block_columns_ = 0;
  uint64_t first_out_block_ = 0;
  uint64_t out_blocks_ = 0;
  // Blocks [0, mixed_block_) hold old columns only; from mixed_block_ on they hold new columns
  // (mixed_block_ itself also the last old ones when old_columns_ is not a multiple of B).
  uint64_t mixed_block_ = 0;
  bool old_blocks_left_ = false;
  std::vector<float> computed_thresholds_;
  const std::vector<float>* thresholds_ = nullptr;
  std::vector<float>* next_thresholds_ = nullptr;
  std::vector<ReversePair> pairs_;
  Columns mixed_new_columns_;  // [old_columns_, the mixed end)
  std::vector<std::unique_ptr<std::string>> new_block_bytes_;
  std::vector<std::unique_ptr<Columns>> new_block_columns_;
  tbb::enumerable_thread_specific<std::unique_ptr<trellis_file::BlockEncoder>> encoders_{
      [] { return std::make_unique<trellis_file::BlockEncoder>(kZstdLevel); }};
  tbb::enumerable_thread_specific<TrellisBlock> blocks_;
  tbb::enumerable_thread_specific<MergeScratch> merge_scratch_;
  BufferPool<Columns> column_pool_;
  BufferPool<std::string> byte_pool_;
  Status failure_;
};

Status TrellisUpdater::Check() const {
  const TrellisParams& old_params = previous_.params();
  auto invalid = [&](const std::string& what) {
    return Status::InvalidArgument("trellis update of " + previous_.path() + ": " + what);
  };
  if (old_params.eps != params_.eps || old_params.k_max != params_.k_max ||
      old_params.exclusion_frames != params_.exclusion_frames ||
      old_params.weights_hash != params_.weights_hash) {
    return invalid("eps, k_max, exclusion or joint weights differ from the new trellis's");
  }
  if (params_.eps != rules_.eps || params_.k_max != rules_.k_max ||
      params_.exclusion_frames != rules_.exclusion_frames) {
    return invalid("the search's rules differ from the new trellis's parameters");
  }
  if (params_.frame_count != frame_count_ || old_columns_ > frame_count_) {
    return invalid("the old trellis has " + std::to_string(old_columns_) +
                   " columns, the archive " + std::to_string(frame_count_) +
                   " frames, the new parameters " + std::to_string(params_.frame_count));
  }
  return Status::Ok();
}

Status TrellisUpdater::OpenWriter() {
  TrellisFileWriterOptions writer_options;
  writer_options.block_columns = previous_.block_columns();
  writer_options.zstd_level = kZstdLevel;
  writer_options.file_system = options_.file_system;
  // Blocks come faster than a disk syncs them; Finish syncs the file before its rename.
  writer_options.sync_each_block = false;
  MOTIF_ASSIGN_OR_RETURN(writer_,
                         TrellisFileWriter::OpenOrResume(out_path_, params_, writer_options));
  block_columns_ = writer_->block_columns();
  // next_column is a multiple of B, or N when every block was written (an update interrupted
  // while finishing).
  first_out_block_ = (writer_->next_column() + block_columns_ - 1) / block_columns_;
  out_blocks_ = (frame_count_ + block_columns_ - 1) / block_columns_;
  report_.resumed_from_column = writer_->next_column();
  mixed_block_ = old_columns_ / block_columns_;
  old_blocks_left_ = first_out_block_ * block_columns_ < old_columns_;
  return Status::Ok();
}

// 1. Thresholds of the old columns still to write: saved by the previous update, or decoded.
Status TrellisUpdater::PrepareThresholds() {
  const Clock::time_point start = Clock::now();
  if (old_blocks_left_) {
    if (options_.thresholds != nullptr && options_.thresholds->size() == old_columns_) {
      thresholds_ = options_.thresholds;
    } else {
      Progress("thresholds", 0, previous_.block_count() - first_out_block_);
      MOTIF_RETURN_IF_ERROR(ComputeThresholds(
          previous_, first_out_block_, arena_,
          [&](uint64_t done, uint64_t total) { Progress("thresholds", done, total); },
          &computed_thresholds_));
      thresholds_ = &computed_thresholds_;
    }
  }
  // The new trellis's thresholds, when every block goes through this update.
  next_thresholds_ = report_.resumed_from_column == 0 ? options_.next_thresholds : nullptr;
  if (options_.next_thresholds) options_.next_thresholds->clear();
  if (next_thresholds_) next_thresholds_->assign(frame_count_, params_.eps);
  report_.thresholds_seconds = SecondsSince(start);
  return Status::Ok();
}

void TrellisUpdater::SetThresholds(uint64_t first_column, const Columns& columns) {
  if (next_thresholds_ == nullptr) return;
  for (size_t idx = 0; idx < columns.size(); ++idx) {
    (*next_thresholds_)[first_column + idx] =
        ColumnThreshold(columns[idx].data(), columns[idx].size(), params_.eps, params_.k_max);
  }
}

// A whole new block: encoded at once, and its columns kept for the block sink.
void TrellisUpdater::KeepNewBlock(uint64_t first, Columns* columns,
                                  trellis_file::BlockEncoder* encoder, Status* status) {
  const uint64_t block_idx = first / block_columns_;
  trellis_file::BlockHandle handle;
  new_block_bytes_[block_idx] = std::make_unique<std::string>();
  *status =
      encoder->Encode(first, *columns, params_.eps, new_block_bytes_[block_idx].get(), &handle);
  SetThresholds(first, *columns);
  if (options_.on_block) {
    new_block_columns_[block_idx] = std::make_unique<Columns>(std::move(*columns));
    *columns = {};
  }
}

// 2. The new columns, block by block of the output: whole new blocks are encoded at once, the
// new columns of the mixed block are kept for the merge. With old blocks still to write, the
// queries also report the old columns they enter.
Status TrellisUpdater::SearchNewColumns() {
  const Clock::time_point start = Clock::now();
  const uint64_t search_first =
      old_blocks_left_ ? old_columns_ : std::max(old_columns_, writer_->next_column());
  new_block_bytes_.resize(out_blocks_);
  new_block_columns_.resize(out_blocks_);
  trellis_file::BlockEncoder encoder(kZstdLevel);
  ReverseQuery query;
  query.frame_limit = old_columns_;
  query.thresholds = thresholds_ ? thresholds_->data() : nullptr;
  Columns columns;
  Columns reverse;
  Progress("new columns", 0, frame_count_ - search_first);
  for (uint64_t first = search_first; first < frame_count_;) {
    const uint64_t block_idx = first / block_columns_;
    const uint64_t end = std::min(frame_count_, (block_idx + 1) * block_columns_);
    columns.clear();
    if (old_blocks_left_) {
      MOTIF_RETURN_IF_ERROR(search_.SearchColumnsAndReverse(first, end - first, query, &columns,
                                                            &reverse, &report_.search_stats));
      for (uint64_t idx = 0; idx < end - first; ++idx) {
        for (const Neighbour& found : reverse[idx]) {
          pairs_.push_back({found.frame, static_cast<uint32_t>(first + idx), found.distance});
        }
      }
    } else {
      MOTIF_RETURN_IF_ERROR(
          search_.SearchColumns(first, end - first, &columns, &report_.search_stats));
    }
    if (first % block_columns_ != 0) {
      mixed_new_columns_ = std::move(columns);  // the mixed block's new columns
      columns = {};
    } else if (block_idx >= first_out_block_) {
      Status encoded;
      KeepNewBlock(first, &columns, &encoder, &encoded);
      MOTIF_RETURN_IF_ERROR(encoded);
    }
    Progress("new columns", end - search_first, frame_count_ - search_first);
    first = end;
  }
  std::sort(pairs_.begin(), pairs_.end(), [](const ReversePair& a, const ReversePair& b) {
    return a.old_frame != b.old_frame ? a.old_frame < b.old_frame : a.new_frame < b.new_frame;
  });
  report_.reverse_candidates = pairs_.size();
  report_.search_seconds = SecondsSince(start);
  return Status::Ok();
}

// An old block no new frame enters, as the old file's bytes.
void TrellisUpdater::CopyBlock(OutputBlock* out, uint64_t first_column, uint64_t end_column) {
  out->status = previous_.ReadEncodedBlock(out->block_idx, &out->bytes, &out->size);
  out->copied = true;
  if (next_thresholds_) {
    std::copy(thresholds_->begin() + first_column, thresholds_->begin() + end_column,
              next_thresholds_->begin() + first_column);
  }
}

// An old block merged with its candidates (and the mixed block's new columns), encoded again;
// or, when `copied`, only decoded for the sink.
void TrellisUpdater::MergeBlock(OutputBlock* out, uint64_t first_column, uint64_t end_column,
                                bool copied) {
  TrellisBlock& block = blocks_.local();
  out->status = previous_.ReadBlock(out->block_idx, &block, /*decode_distances=*/true);
  if (!out->status.ok()) return;
  out->columns = column_pool_.Take();
  Columns& columns = *out->columns;
  columns.resize(end_column - first_column);
  const auto by_old_frame = [](const ReversePair& pair, uint64_t column) {
    return pair.old_frame < column;
  };
  auto pair = std::lower_bound(pairs_.begin(), pairs_.end(), first_column, by_old_frame);
  const auto pairs_end = std::lower_bound(pair, pairs_.end(), end_column, by_old_frame);
  for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
    const uint64_t column = first_column + column_idx;
    const auto column_pairs_begin = pair;
    while (pair != pairs_end && pair->old_frame == column) ++pair;
    const uint32_t begin = block.offsets[column_idx];
    const uint32_t end = block.offsets[column_idx + 1];
    if (MergeColumn(features_, column, params_.eps, params_.k_max, block.neighbours.data() + begin,
                    end - begin, pairs_.data() + (column_pairs_begin - pairs_.begin()),
                    static_cast<size_t>(pair - column_pairs_begin), &columns[column_idx],
                    &out->recomputed, &merge_scratch_.local())) {
      ++out->changed_columns;
    }
  }
  if (copied) return;  // decoded for the sink only
  for (uint64_t column = old_columns_; column < end_column; ++column) {
    columns[column - first_column] = std::move(mixed_new_columns_[column - old_columns_]);
  }
  if (first_column < old_columns_ || end_column > old_columns_) {
    SetThresholds(first_column, columns);
  }
  trellis_file::BlockHandle handle;
  out->owned = byte_pool_.Take();
  out->status =
      encoders_.local()->Encode(first_column, columns, params_.eps, out->owned.get(), &handle);
  out->bytes = reinterpret_cast<const uint8_t*>(out->owned->data());
  out->size = out->owned->size();
  out->rewritten = true;
}

// Runs on many threads: a block's bytes (and columns for the sink), from whichever source.
void TrellisUpdater::PrepareBlock(OutputBlock* out) {
  const uint64_t first_column = out->block_idx * block_columns_;
  const uint64_t end_column = std::min(frame_count_, first_column + block_columns_);
  if (first_column >= old_columns_) {  // a whole new block
    out->owned = std::move(new_block_bytes_[out->block_idx]);
    out->columns = std::move(new_block_columns_[out->block_idx]);
    out->bytes = reinterpret_cast<const uint8_t*>(out->owned->data());
    out->size = out->owned->size();
    return;
  }
  const auto by_old_frame = [](const ReversePair& pair, uint64_t column) {
    return pair.old_frame < column;
  };
  const auto pairs_begin =
      std::lower_bound(pairs_.begin(), pairs_.end(), first_column, by_old_frame);
  const auto pairs_end = std::lower_bound(pairs_begin, pairs_.end(), end_column, by_old_frame);
  const bool copy = pairs_begin == pairs_end && end_column <= old_columns_;
  if (copy) {
    CopyBlock(out, first_column, end_column);
    if (!options_.on_block || !out->status.ok()) return;
  }
  MergeBlock(out, first_column, end_column, copy);
}

// Runs in block order: the block appended, given to the sink, counted.
void TrellisUpdater::AppendBlock(OutputBlock* out) {
  if (!failure_.ok()) return;
  Status status = out->status;
  if (status.ok()) status = writer_->AppendEncodedBlock(out->bytes, out->size);
  const uint64_t first_column = out->block_idx * block_columns_;
  if (status.ok() && options_.on_block && out->columns) {
    status = options_.on_block(first_column, *out->columns);
  }
  if (!status.ok()) {
    failure_ = status;
    return;
  }
  if (out->block_idx < previous_.block_count()) {
    // A memory hint; it fails only for a block out of range (checked above).
    (void)previous_.ReleaseBlocks(out->block_idx, out->block_idx + 1);
  }
  if (first_column >= old_columns_ || out->block_idx == mixed_block_) ++report_.new_blocks;
  if (out->copied) ++report_.copied_blocks;
  if (out->rewritten && first_column + block_columns_ <= old_columns_) {
    ++report_.rewritten_blocks;
  }
  report_.changed_columns += out->changed_columns;
  report_.exact_recomputations += out->recomputed;
  if (first_column < old_columns_) {
    column_pool_.Give(std::move(out->columns));
    byte_pool_.Give(std::move(out->owned));
  }
  Progress("merge", out->block_idx + 1 - first_out_block_, out_blocks_ - first_out_block_);
}

// 3. The output blocks in order: old blocks copied or merged, the mixed block, the new blocks.
// Blocks are prepared in parallel and appended (and given to the sink) in order.
Status TrellisUpdater::WriteBlocks() {
  const Clock::time_point start = Clock::now();
  uint64_t next_block = first_out_block_;
  Progress("merge", 0, out_blocks_ - first_out_block_);
  arena_.execute([&] {
    tbb::parallel_pipeline(
        2 * static_cast<size_t>(arena_.max_concurrency()),
        tbb::make_filter<void, std::shared_ptr<OutputBlock>>(
            tbb::filter_mode::serial_in_order,
            [&](tbb::flow_control& control) -> std::shared_ptr<OutputBlock> {
              if (next_block >= out_blocks_ || !failure_.ok()) {
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
                    PrepareBlock(out.get());
                  } catch (const std::bad_alloc&) {
                    out->status = Status::ResourceExhausted("trellis update: out of memory");
                  }
                  return out;
                }) &
            tbb::make_filter<std::shared_ptr<OutputBlock>, void>(
                tbb::filter_mode::serial_in_order,
                [&](std::shared_ptr<OutputBlock> out) { AppendBlock(out.get()); }));
  });
  MOTIF_RETURN_IF_ERROR(failure_);
  MOTIF_RETURN_IF_ERROR(writer_->Finish());
  report_.merge_seconds = SecondsSince(start);
  return Status::Ok();
}

Result<TrellisUpdateReport> TrellisUpdater::Run() {
  MOTIF_RETURN_IF_ERROR(Check());
  report_.old_columns = old_columns_;
  report_.new_columns = frame_count_ - old_columns_;
  MOTIF_RETURN_IF_ERROR(OpenWriter());
  MOTIF_RETURN_IF_ERROR(PrepareThresholds());
  MOTIF_RETURN_IF_ERROR(SearchNewColumns());
  MOTIF_RETURN_IF_ERROR(WriteBlocks());
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> finished,
                         TrellisFileReader::Open(out_path_));
  report_.neighbours = finished->neighbour_count();
  return report_;
}

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
  return TrellisUpdater(previous, features, rules, search, params, out_path, options).Run();
}

}  // namespace motif
