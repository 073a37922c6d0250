// LshShardBuilder: hashes one shard of the archive (a contiguous frame range) into every table
// of a HashFamily. A shard is the unit of parallel work of the index build (LshIndex::Build runs
// one TBB task per shard). Each shard writes only its own slice of the index's table arrays
// (the slice at its frame range), sorted by (bucket key, sort value, frame), a total order; the
// index then merges the sorted slices of each table in shard order, so the merged index is the
// same for any thread count and shard size.
// Thread-safety: Build is const; several shards may be built at once from one builder, each into
// its own slices.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"

namespace motif {

// One table's entries: parallel arrays sorted by (keys[i], sort_values[i], frames[i]); codes[i]
// is the entry's HashFamily::PositionCode (empty when the index keeps no codes).
struct LshTableEntries {
  std::vector<uint32_t> keys;
  std::vector<int16_t> sort_values;
  std::vector<uint32_t> frames;
  std::vector<uint32_t> codes;

  size_t size() const { return frames.size(); }
};

// Where a shard writes one table's entries: frame_count slots of each array.
struct LshShardSlice {
  uint32_t* keys = nullptr;
  int16_t* sort_values = nullptr;
  uint32_t* frames = nullptr;
  uint32_t* codes = nullptr;  // null: the index keeps no position codes
};

class LshShardBuilder {
 public:
  // Both must outlive the builder.
  LshShardBuilder(const PoseFeatures& features, const HashFamily& family)
      : features_(features), family_(family) {}

  // Hashes frames [first_frame, first_frame + frame_count) (within the archive; frame indices
  // must fit in 32 bits) and writes each table's entries, sorted, to slices[table_idx], which
  // has one slice per table of frame_count slots.
  void Build(uint64_t first_frame, uint64_t frame_count,
             const std::vector<LshShardSlice>& slices) const;

 private:
  const PoseFeatures& features_;
  const HashFamily& family_;
};

}  // namespace motif
