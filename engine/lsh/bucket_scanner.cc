#include "engine/lsh/bucket_scanner.h"

namespace motif {

BucketCursor BucketCursor::Open(const LshIndex& index, const BucketProbe& probe,
                                int16_t query_sort_value, const LshOptions& options) {
  BucketCursor cursor;
  const auto [begin, end] = index.FindBucket(probe.table_idx, probe.key);
  if (begin == end) return cursor;
  cursor.query_sort_value = query_sort_value;
  const int16_t* sort_values = index.table(probe.table_idx).sort_values.data();
  cursor.begin = begin;
  cursor.end = end;
  if (end - begin <= options.first_round_scan) {
    // Read whole in the first round anyway: the order does not matter, skip the search.
    cursor.linear = true;
    cursor.up = begin;
  } else {
    cursor.up = static_cast<uint32_t>(
        std::lower_bound(sort_values + begin, sort_values + end, cursor.query_sort_value) -
        sort_values);
  }
  cursor.down = cursor.up;
  __builtin_prefetch(index.table(probe.table_idx).frames.data() + cursor.up);
  cursor.scan_limit = std::min<uint32_t>(options.max_bucket_scan, end - begin);
  cursor.done = false;
  return cursor;
}

}  // namespace motif
