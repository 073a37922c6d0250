#include "engine/lsh/lsh_index.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <queue>
#include <string>

namespace motif {
namespace {

int ArenaThreads(int threads) { return threads > 0 ? threads : tbb::task_arena::automatic; }

// Merges the sorted runs of one table, taken from the shards in shard order, into `out`. Keys
// are compared as (key, sort value, frame); frames are unique, so the output is the one sorted
// order of the union whatever the runs.
void MergeTable(std::vector<LshTableEntries*> runs, LshTableEntries* out) {
  size_t total = 0;
  for (const LshTableEntries* run : runs) total += run->size();
  out->keys.resize(total);
  out->sort_values.resize(total);
  out->frames.resize(total);
  struct Head {
    uint32_t key;
    int16_t sort_value;
    uint32_t frame;
    uint32_t run_idx;
    size_t position;
  };
  auto after = [](const Head& a, const Head& b) {
    if (a.key != b.key) return a.key > b.key;
    if (a.sort_value != b.sort_value) return a.sort_value > b.sort_value;
    return a.frame > b.frame;
  };
  std::priority_queue<Head, std::vector<Head>, decltype(after)> heads(after);
  for (uint32_t run_idx = 0; run_idx < runs.size(); ++run_idx) {
    const LshTableEntries* run = runs[run_idx];
    if (run->size() > 0) heads.push({run->keys[0], run->sort_values[0], run->frames[0], run_idx, 0});
  }
  size_t written = 0;
  while (!heads.empty()) {
    Head head = heads.top();
    heads.pop();
    const LshTableEntries* run = runs[head.run_idx];
    // Copy the whole stretch of this run that stays below the next run's head.
    size_t position = head.position;
    while (true) {
      out->keys[written] = run->keys[position];
      out->sort_values[written] = run->sort_values[position];
      out->frames[written] = run->frames[position];
      ++written;
      ++position;
      if (position == run->size()) break;
      if (heads.empty()) continue;
      const Head& next = heads.top();
      const Head candidate{run->keys[position], run->sort_values[position], run->frames[position],
                           head.run_idx, position};
      if (after(candidate, next)) {
        heads.push(candidate);
        break;
      }
    }
  }
  MOTIF_CHECK(written == total);
  for (LshTableEntries* run : runs) run->Clear();
}

}  // namespace

Result<LshIndex> LshIndex::Build(const PoseFeatures& features, const HashFamily& family,
                                 uint32_t shard_frames, int threads) {
  const uint64_t frame_count = features.frame_count();
  if (frame_count >= (uint64_t{1} << 32)) {
    return Status::InvalidArgument("lsh index: " + std::to_string(frame_count) +
                                   " frames; frame ids are 32-bit");
  }
  if (shard_frames == 0) return Status::InvalidArgument("lsh index: shard_frames is 0");
  const uint64_t shard_count = (frame_count + shard_frames - 1) / shard_frames;
  std::vector<LshShard> shards(shard_count);
  const LshShardBuilder builder(features, family);
  tbb::task_arena arena(ArenaThreads(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, shard_count, /*grainsize=*/1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t shard_idx = range.begin(); shard_idx != range.end();
                             ++shard_idx) {
                          const uint64_t first = shard_idx * uint64_t{shard_frames};
                          const uint64_t count =
                              std::min<uint64_t>(shard_frames, frame_count - first);
                          shards[shard_idx] = builder.Build(first, count);
                        }
                      });
  });
  return Merge(std::move(shards), family.table_count(), threads);
}

LshIndex LshIndex::Merge(std::vector<LshShard> shards, uint32_t table_count, int threads) {
  LshIndex index;
  uint64_t expected_first = 0;
  for (const LshShard& shard : shards) {
    MOTIF_CHECK(shard.first_frame == expected_first);
    MOTIF_CHECK(shard.tables.size() == table_count);
    expected_first += shard.frame_count;
  }
  index.frame_count_ = expected_first;
  // About 16 entries per directory slot: a bucket lookup reads one slot pair and binary-searches
  // a cache line or two of keys.
  const uint32_t frame_bits =
      index.frame_count_ > 1 ? std::bit_width(index.frame_count_ - 1) : 1;
  const uint32_t directory_bits = std::clamp<uint32_t>(frame_bits > 4 ? frame_bits - 4 : 1, 1, 24);
  index.directory_shift_ = 32 - directory_bits;
  index.tables_.resize(table_count);
  index.directories_.resize(table_count);
  tbb::task_arena arena(ArenaThreads(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, table_count, /*grainsize=*/1),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                        for (uint32_t table_idx = range.begin(); table_idx != range.end();
                             ++table_idx) {
                          std::vector<LshTableEntries*> runs;
                          for (LshShard& shard : shards) runs.push_back(&shard.tables[table_idx]);
                          MergeTable(std::move(runs), &index.tables_[table_idx]);
                          index.BuildDirectory(table_idx);
                        }
                      });
  });
  return index;
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
             table.frames.capacity() * sizeof(uint32_t);
  }
  for (const std::vector<uint32_t>& directory : directories_) {
    bytes += directory.capacity() * sizeof(uint32_t);
  }
  return bytes;
}

}  // namespace motif
