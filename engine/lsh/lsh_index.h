// LshIndex: the merged hash tables of an archive. Build() allocates each table's arrays once,
// hashes the archive in shards (one TBB task per shard of LshOptions::shard_frames frames,
// inside a task_arena of the requested thread count; LshShardBuilder), each writing its sorted
// slice of every table, then merges each table's slices in shard order (tables in parallel).
// Every table is sorted by (bucket key, sort value, frame), a total order, so the index is
// identical, byte for byte, for any thread count and shard size.
//
// Memory per frame and table: 4 bytes of frame id, 4 of bucket key, 2 of sort value, plus a
// directory of 4-byte offsets over the top bits of the key (about N / 16 slots per table), i.e.
// ~10.3 bytes; the default 8 tables take ~83 bytes per frame. While building, a table being
// merged needs a second copy: the peak is ~83 + 10 x (tables merged at once, one per thread)
// bytes per frame. A heavy bucket costs nothing extra: each frame is stored once per table
// whatever its bucket holds.
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/rank_group.h"
#include "common/status.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"
#include "engine/lsh/lsh_shard_builder.h"

namespace motif {

// Sizes of one table's buckets.
struct LshBucketStats {
  uint64_t buckets = 0;                      // distinct keys
  uint64_t largest_bucket = 0;               // entries in the fullest bucket
  double mean_entries_per_frame_bucket = 0;  // average over frames of the size of their bucket
};

class LshIndex {
 public:
  // Hashes all frames of `features` with `family` in shards of `shard_frames` frames on
  // `threads` threads (0: all cores). InvalidArgument for shard_frames 0 or an archive of 2^32
  // frames or more.
  // Without `position_codes` the tables hold no codes (LshRanking::kSortValue does not read
  // them), 4 bytes per frame per table less.
  // With `ranks` (a distributed run) each rank hashes a share of the shards and the ranks
  // exchange their slices before the merge: the same index on every rank.
  static Result<LshIndex> Build(const PoseFeatures& features, const HashFamily& family,
                                uint32_t shard_frames, int threads, bool position_codes = true,
                                RankGroup* ranks = nullptr);

  // The index of tables saved earlier (each sorted by (key, sort value, frame), all of
  // frame_count entries, with codes when position_codes): an incremental update keeps the
  // index of the frames it had. InvalidArgument if the sizes do not match or a table is not
  // sorted.
  static Result<LshIndex> FromTables(uint64_t frame_count, std::vector<LshTableEntries> tables,
                                     bool position_codes);
  // Whether the tables hold position codes.
  bool position_codes() const { return position_codes_; }

  // Adds frames [frame_count(), features.frame_count()) of `features` (which extend the frames
  // indexed so far) hashed with `family` (the one the index was built with), in shards as
  // Build does, each table's new slices merged with its entries: the result is the index Build
  // makes of all the frames, entry for entry. InvalidArgument if the features have fewer frames
  // or 2^32 or more.
  Status Extend(const PoseFeatures& features, const HashFamily& family, uint32_t shard_frames,
                int threads);

  uint32_t table_count() const { return static_cast<uint32_t>(tables_.size()); }
  uint64_t frame_count() const { return frame_count_; }
  const LshTableEntries& table(uint32_t table_idx) const { return tables_[table_idx]; }

  // The entries [begin, end) of table `table_idx` whose bucket key is `key` (empty if none).
  std::pair<uint32_t, uint32_t> FindBucket(uint32_t table_idx, uint32_t key) const;

  // Cache hints for a coming FindBucket(table_idx, key): first the directory slot, then (once
  // the slot has arrived) the start of the slot's keys. Lookups of a column's probes overlap
  // their memory latency this way.
  void PrefetchDirectory(uint32_t table_idx, uint32_t key) const {
    __builtin_prefetch(&directories_[table_idx][key >> directory_shift_]);
  }
  void PrefetchKeys(uint32_t table_idx, uint32_t key) const {
    __builtin_prefetch(&tables_[table_idx].keys[directories_[table_idx][key >> directory_shift_]]);
  }

  LshBucketStats BucketStats(uint32_t table_idx) const;
  // Bytes held by the tables and directories.
  uint64_t memory_bytes() const;

 private:
  // directory_shift_ for frame_count_ frames.
  void SetDirectoryShift();
  void BuildDirectory(uint32_t table_idx);
  // Merges the sorted runs of table `table_idx` (run r is [run_starts[r], run_starts[r + 1]))
  // into one sorted table.
  void MergeRuns(uint32_t table_idx, const std::vector<uint64_t>& run_starts);
  // Every rank's hashed shards to every rank: `shard_starts` the shards of each rank.
  Status ShareSlices(RankGroup* ranks, const std::vector<uint64_t>& run_starts,
                     const std::vector<uint64_t>& shard_starts);

  uint64_t frame_count_ = 0;
  bool position_codes_ = false;
  uint32_t directory_shift_ = 32;
  std::vector<LshTableEntries> tables_;
  // Per table: directory[slot] is the first entry whose key >> directory_shift_ >= slot.
  std::vector<std::vector<uint32_t>> directories_;
};

}  // namespace motif
