// LshShardBuilder: hashes one shard of the archive (a contiguous frame range) into every table
// of a HashFamily. A shard is the unit of parallel work of the index build (LshIndex::Build runs
// one TBB task per shard); its tables are sorted by (bucket key, sort value, frame), a total
// order, so merging the shards in shard order gives the same index for any thread count.
// Thread-safety: Build is const; several shards may be built at once from one builder.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/distance/pose_features.h"
#include "engine/lsh/hash_family.h"

namespace motif {

// One table's entries of a shard, or of the merged index: parallel arrays, sorted by
// (keys[i], sort_values[i], frames[i]).
struct LshTableEntries {
  std::vector<uint32_t> keys;
  std::vector<int16_t> sort_values;
  std::vector<uint32_t> frames;

  size_t size() const { return frames.size(); }
  void Clear() {
    keys = {};
    sort_values = {};
    frames = {};
  }
};

struct LshShard {
  uint64_t first_frame = 0;
  uint64_t frame_count = 0;
  std::vector<LshTableEntries> tables;  // one per hash table
};

class LshShardBuilder {
 public:
  // Both must outlive the builder.
  LshShardBuilder(const PoseFeatures& features, const HashFamily& family)
      : features_(features), family_(family) {}

  // Hashes frames [first_frame, first_frame + frame_count) (within the archive; frame indices
  // must fit in 32 bits) and sorts each table.
  LshShard Build(uint64_t first_frame, uint64_t frame_count) const;

 private:
  const PoseFeatures& features_;
  const HashFamily& family_;
};

}  // namespace motif
