#include "engine/lsh/lsh_index.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <queue>
#include <string>

#include "common/status.h"

namespace motif {
namespace {

int ArenaThreads(int threads) { return threads > 0 ? threads : tbb::task_arena::automatic; }

}  // namespace

Result<LshIndex> LshIndex::Build(const PoseFeatures& features, const HashFamily& family,
                                 uint32_t shard_frames, int threads, bool position_codes,
                                 RankGroup* ranks) {
  const uint64_t frame_count = features.frame_count();
  if (frame_count >= (uint64_t{1} << 32)) {
    return Status::InvalidArgument("lsh index: " + std::to_string(frame_count) +
                                   " frames; frame ids are 32-bit");
  }
  if (shard_frames == 0) return Status::InvalidArgument("lsh index: shard_frames is 0");
  const uint32_t table_count = family.table_count();
  LshIndex index;
  index.frame_count_ = frame_count;
  index.position_codes_ = position_codes;
  index.tables_.resize(table_count);
  index.directories_.resize(table_count);
  // One allocation per array for the whole build: shards fill their slices in place (large
  // allocations are mapped and unmapped whole, so nothing lingers in the heap afterwards).
  for (LshTableEntries& table : index.tables_) {
    table.keys.resize(frame_count);
    table.sort_values.resize(frame_count);
    table.frames.resize(frame_count);
    if (position_codes) table.codes.resize(frame_count);
  }
  const uint64_t shard_count = (frame_count + shard_frames - 1) / shard_frames;
  std::vector<uint64_t> run_starts(shard_count + 1);
  for (uint64_t shard_idx = 0; shard_idx <= shard_count; ++shard_idx) {
    run_starts[shard_idx] = std::min<uint64_t>(shard_idx * shard_frames, frame_count);
  }
  // This rank's shards: all of them, or its share in a distributed run.
  const RankShare share = ShareOf(shard_count, ranks);
  const LshShardBuilder builder(features, family);
  tbb::task_arena arena(ArenaThreads(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(share.first(), share.end(), /*grainsize=*/1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t shard_idx = range.begin(); shard_idx != range.end();
                             ++shard_idx) {
                          const uint64_t first = run_starts[shard_idx];
                          const uint64_t count = run_starts[shard_idx + 1] - first;
                          std::vector<LshShardSlice> slices(table_count);
                          for (uint32_t table_idx = 0; table_idx < table_count; ++table_idx) {
                            LshTableEntries& table = index.tables_[table_idx];
                            slices[table_idx] = {&table.keys[first], &table.sort_values[first],
                                                 &table.frames[first],
                                                 position_codes ? &table.codes[first] : nullptr};
                          }
                          builder.Build(first, count, slices);
                        }
                      });
  });
  if (share.shared()) MOTIF_RETURN_IF_ERROR(index.ShareSlices(ranks, run_starts, share.starts));
  index.SetDirectoryShift();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, table_count, /*grainsize=*/1),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                        for (uint32_t table_idx = range.begin(); table_idx != range.end();
                             ++table_idx) {
                          index.MergeRuns(table_idx, run_starts);
                          index.BuildDirectory(table_idx);
                        }
                      });
  });
  return index;
}

Status LshIndex::ShareSlices(RankGroup* ranks, const std::vector<uint64_t>& run_starts,
                             const std::vector<uint64_t>& shard_starts) {
  std::vector<uint64_t> frame_starts;
  for (uint64_t shard : shard_starts) frame_starts.push_back(run_starts[shard]);
  for (LshTableEntries& table : tables_) {
    MOTIF_RETURN_IF_ERROR(ranks->ShareParts(table.keys.data(), sizeof(uint32_t), frame_starts));
    MOTIF_RETURN_IF_ERROR(
        ranks->ShareParts(table.sort_values.data(), sizeof(int16_t), frame_starts));
    MOTIF_RETURN_IF_ERROR(ranks->ShareParts(table.frames.data(), sizeof(uint32_t), frame_starts));
    if (position_codes_) {
      MOTIF_RETURN_IF_ERROR(ranks->ShareParts(table.codes.data(), sizeof(uint32_t), frame_starts));
    }
  }
  return Status::Ok();
}

Result<LshIndex> LshIndex::FromTables(uint64_t frame_count, std::vector<LshTableEntries> tables,
                                      bool position_codes) {
  if (frame_count >= (uint64_t{1} << 32)) {
    return Status::InvalidArgument("lsh index: frame ids are 32-bit");
  }
  const bool with_codes = position_codes;
  for (const LshTableEntries& table : tables) {
    if (table.frames.size() != frame_count || table.keys.size() != frame_count ||
        table.sort_values.size() != frame_count ||
        table.codes.size() != (with_codes ? frame_count : 0)) {
      return Status::InvalidArgument("lsh index: a saved table does not hold " +
                                     std::to_string(frame_count) + " entries");
    }
    for (uint64_t idx = 1; idx < frame_count; ++idx) {
      const bool ordered = table.keys[idx - 1] != table.keys[idx]
                               ? table.keys[idx - 1] < table.keys[idx]
                               : (table.sort_values[idx - 1] != table.sort_values[idx]
                                      ? table.sort_values[idx - 1] < table.sort_values[idx]
                                      : table.frames[idx - 1] < table.frames[idx]);
      if (!ordered) return Status::InvalidArgument("lsh index: a saved table is not sorted");
    }
  }
  LshIndex index;
  index.frame_count_ = frame_count;
  index.position_codes_ = position_codes;
  index.tables_ = std::move(tables);
  index.directories_.resize(index.tables_.size());
  index.SetDirectoryShift();
  for (uint32_t table_idx = 0; table_idx < index.tables_.size(); ++table_idx) {
    index.BuildDirectory(table_idx);
  }
  return index;
}

Status LshIndex::Extend(const PoseFeatures& features, const HashFamily& family,
                        uint32_t shard_frames, int threads) {
  const uint64_t old_count = frame_count_;
  const uint64_t frame_count = features.frame_count();
  if (frame_count < old_count || frame_count >= (uint64_t{1} << 32)) {
    return Status::InvalidArgument("lsh index: cannot extend " + std::to_string(old_count) +
                                   " frames to " + std::to_string(frame_count));
  }
  if (shard_frames == 0) return Status::InvalidArgument("lsh index: shard_frames is 0");
  if (family.table_count() != tables_.size()) {
    return Status::InvalidArgument("lsh index: another hash family");
  }
  const uint32_t table_count = family.table_count();
  const bool position_codes = position_codes_;
  for (LshTableEntries& table : tables_) {
    table.keys.resize(frame_count);
    table.sort_values.resize(frame_count);
    table.frames.resize(frame_count);
    if (position_codes) table.codes.resize(frame_count);
  }
  // The new frames in shards, as Build cuts them (aligned on multiples of shard_frames from
  // frame 0, so the same frames share a shard): each shard sorted, then merged with the old
  // entries, a sorted run of their own.
  std::vector<uint64_t> run_starts = {0};
  for (uint64_t first = old_count; first < frame_count;) {
    if (first > 0) run_starts.push_back(first);
    first = std::min(frame_count, (first / shard_frames + 1) * shard_frames);
  }
  run_starts.push_back(frame_count);
  const LshShardBuilder builder(features, family);
  tbb::task_arena arena(ArenaThreads(threads));
  arena.execute([&] {
    const size_t first_new_run = old_count > 0 ? 1 : 0;
    tbb::parallel_for(tbb::blocked_range<size_t>(first_new_run, run_starts.size() - 1,
                                                 /*grainsize=*/1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t run = range.begin(); run != range.end(); ++run) {
                          const uint64_t first = run_starts[run];
                          const uint64_t count = run_starts[run + 1] - first;
                          std::vector<LshShardSlice> slices(table_count);
                          for (uint32_t table_idx = 0; table_idx < table_count; ++table_idx) {
                            LshTableEntries& table = tables_[table_idx];
                            slices[table_idx] = {&table.keys[first], &table.sort_values[first],
                                                 &table.frames[first],
                                                 position_codes ? &table.codes[first] : nullptr};
                          }
                          builder.Build(first, count, slices);
                        }
                      });
  });
  frame_count_ = frame_count;
  SetDirectoryShift();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, table_count, /*grainsize=*/1),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                        for (uint32_t table_idx = range.begin(); table_idx != range.end();
                             ++table_idx) {
                          MergeRuns(table_idx, run_starts);
                          BuildDirectory(table_idx);
                        }
                      });
  });
  return Status::Ok();
}

void LshIndex::SetDirectoryShift() {
  // About 16 entries per directory slot: a bucket lookup reads one slot pair and binary-searches
  // a cache line or two of keys.
  const uint32_t frame_bits = frame_count_ > 1 ? std::bit_width(frame_count_ - 1) : 1;
  const uint32_t directory_bits = std::clamp<uint32_t>(frame_bits > 4 ? frame_bits - 4 : 1, 1, 24);
  directory_shift_ = 32 - directory_bits;
}

void LshIndex::MergeRuns(uint32_t table_idx, const std::vector<uint64_t>& run_starts) {
  const size_t run_count = run_starts.size() - 1;
  if (run_count <= 1) return;
  LshTableEntries& in = tables_[table_idx];
  const size_t total = in.size();
  LshTableEntries out;
  out.keys.resize(total);
  out.sort_values.resize(total);
  out.frames.resize(total);
  const bool with_codes = !in.codes.empty();
  if (with_codes) out.codes.resize(total);
  struct Head {
    uint32_t key;
    int16_t sort_value;
    uint32_t frame;
    size_t position;
    size_t run_end;
  };
  auto after = [](const Head& a, const Head& b) {
    if (a.key != b.key) return a.key > b.key;
    if (a.sort_value != b.sort_value) return a.sort_value > b.sort_value;
    return a.frame > b.frame;
  };
  std::priority_queue<Head, std::vector<Head>, decltype(after)> heads(after);
  for (size_t run_idx = 0; run_idx < run_count; ++run_idx) {
    const size_t begin = run_starts[run_idx];
    const size_t end = run_starts[run_idx + 1];
    if (begin < end)
      heads.push({in.keys[begin], in.sort_values[begin], in.frames[begin], begin, end});
  }
  size_t written = 0;
  while (!heads.empty()) {
    const Head head = heads.top();
    heads.pop();
    // Copy the stretch of this run that stays below the next run's head. Frames are unique, so
    // the output is the one sorted order of the union whatever the runs.
    size_t position = head.position;
    while (true) {
      out.keys[written] = in.keys[position];
      out.sort_values[written] = in.sort_values[position];
      out.frames[written] = in.frames[position];
      if (with_codes) out.codes[written] = in.codes[position];
      ++written;
      ++position;
      if (position == head.run_end) break;
      if (heads.empty()) continue;
      const Head candidate{in.keys[position], in.sort_values[position], in.frames[position],
                           position, head.run_end};
      if (after(candidate, heads.top())) {
        heads.push(candidate);
        break;
      }
    }
  }
  MOTIF_CHECK(written == total);
  in = std::move(out);  // the unmerged arrays are freed here
}

void LshIndex::BuildDirectory(uint32_t table_idx) {
  const std::vector<uint32_t>& keys = tables_[table_idx].keys;
  const size_t slot_count = (size_t{1} << (32 - directory_shift_));
  std::vector<uint32_t>& directory = directories_[table_idx];
  directory.assign(slot_count + 1, 0);
  size_t position = 0;
  for (size_t slot = 0; slot <= slot_count; ++slot) {
    while (position < keys.size() && (keys[position] >> directory_shift_) < slot) ++position;
    directory[slot] = static_cast<uint32_t>(position);
  }
}

std::pair<uint32_t, uint32_t> LshIndex::FindBucket(uint32_t table_idx, uint32_t key) const {
  const std::vector<uint32_t>& directory = directories_[table_idx];
  const uint32_t slot = key >> directory_shift_;
  const uint32_t* keys = tables_[table_idx].keys.data();
  const uint32_t* first = keys + directory[slot];
  const uint32_t* last = keys + directory[slot + 1];
  const uint32_t* begin = std::lower_bound(first, last, key);
  if (begin == last || *begin != key) return {0, 0};
  const uint32_t* end = std::upper_bound(begin, last, key);
  return {static_cast<uint32_t>(begin - keys), static_cast<uint32_t>(end - keys)};
}

LshBucketStats LshIndex::BucketStats(uint32_t table_idx) const {
  LshBucketStats stats;
  const std::vector<uint32_t>& keys = tables_[table_idx].keys;
  double squared_sizes = 0;
  for (size_t begin = 0; begin < keys.size();) {
    size_t end = begin + 1;
    while (end < keys.size() && keys[end] == keys[begin]) ++end;
    const uint64_t size = end - begin;
    ++stats.buckets;
    stats.largest_bucket = std::max(stats.largest_bucket, size);
    squared_sizes += static_cast<double>(size) * static_cast<double>(size);
    begin = end;
  }
  if (!keys.empty()) stats.mean_entries_per_frame_bucket = squared_sizes / keys.size();
  return stats;
}

uint64_t LshIndex::memory_bytes() const {
  uint64_t bytes = 0;
  for (const LshTableEntries& table : tables_) {
    bytes += table.keys.capacity() * sizeof(uint32_t) +
             table.sort_values.capacity() * sizeof(int16_t) +
             table.frames.capacity() * sizeof(uint32_t) + table.codes.capacity() * sizeof(uint32_t);
  }
  for (const std::vector<uint32_t>& directory : directories_) {
    bytes += directory.capacity() * sizeof(uint32_t);
  }
  return bytes;
}

}  // namespace motif
