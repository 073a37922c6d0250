#include "engine/lsh/lsh_shard_builder.h"

#include <algorithm>
#include <numeric>

#include "common/status.h"

namespace motif {

void LshShardBuilder::Build(uint64_t first_frame, uint64_t frame_count,
                            const std::vector<LshShardSlice>& slices) const {
  MOTIF_CHECK(first_frame + frame_count <= features_.frame_count());
  MOTIF_CHECK(first_frame + frame_count <= (uint64_t{1} << 32));
  const uint32_t table_count = family_.table_count();
  MOTIF_CHECK(slices.size() == table_count);
  const uint32_t hashes = family_.hashes_per_table();
  const uint32_t rows_per_table = hashes + 1;

  // Key, sort value (and position code, if the index keeps them) of every frame, table-major,
  // in frame order.
  const bool with_codes = slices[0].codes != nullptr;
  std::vector<uint32_t> keys(static_cast<size_t>(table_count) * frame_count);
  std::vector<int16_t> sort_values(static_cast<size_t>(table_count) * frame_count);
  std::vector<uint32_t> codes(with_codes ? static_cast<size_t>(table_count) * frame_count : 0);
  std::vector<float> embedding(family_.embedding_dims());
  std::vector<float> projections(static_cast<size_t>(table_count) * rows_per_table);
  for (uint64_t offset = 0; offset < frame_count; ++offset) {
    family_.Embed(features_.frame(first_frame + offset), embedding.data());
    family_.Project(embedding.data(), projections.data());
    for (uint32_t table_idx = 0; table_idx < table_count; ++table_idx) {
      const float* coordinates = &projections[static_cast<size_t>(table_idx) * rows_per_table];
      keys[table_idx * frame_count + offset] = family_.KeyOfCoordinates(coordinates);
      sort_values[table_idx * frame_count + offset] =
          family_.QuantiseSortValue(coordinates[hashes]);
      if (with_codes) codes[table_idx * frame_count + offset] = family_.PositionCode(coordinates);
    }
  }

  std::vector<uint32_t> order(frame_count);
  for (uint32_t table_idx = 0; table_idx < table_count; ++table_idx) {
    const uint32_t* table_keys = &keys[table_idx * frame_count];
    const int16_t* table_sort = &sort_values[table_idx * frame_count];
    std::iota(order.begin(), order.end(), 0u);
    // Offsets are unique, so this is a total order: the result does not depend on the sort.
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      if (table_keys[a] != table_keys[b]) return table_keys[a] < table_keys[b];
      if (table_sort[a] != table_sort[b]) return table_sort[a] < table_sort[b];
      return a < b;
    });
    const LshShardSlice& slice = slices[table_idx];
    for (uint64_t rank = 0; rank < frame_count; ++rank) {
      const uint32_t offset = order[rank];
      slice.keys[rank] = table_keys[offset];
      slice.sort_values[rank] = table_sort[offset];
      slice.frames[rank] = static_cast<uint32_t>(first_frame + offset);
      if (with_codes) slice.codes[rank] = codes[table_idx * frame_count + offset];
    }
  }
}

}  // namespace motif
