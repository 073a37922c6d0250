// BucketScanner: reads the buckets of a column's probe sequence breadth first (docs/design/lsh.md,
// section 3): every probed bucket is read outward from the query's sort value, first_round_scan
// entries deep in every bucket, then 4x deeper, ..., up to max_bucket_scan per bucket, so that a
// budget goes to the entries nearest the query in all tables before the far ends of the first
// buckets. A probe whose lower bound exceeds the scan's reach ends the scan (probes are sorted:
// nothing later is within reach either).
//
// BucketCursor is the scan of one bucket: it hands out entries, the side with the nearer sort
// value first, and ends a bucket's scan once the entry's lower bound, probe score + sort-value
// gap^2, leaves the reach. BucketScanner owns the cursors of one scan (scratch reused across
// columns) and runs the rounds; what is done with each entry is the visitor's: the forward
// query verifies it (ColumnQuery), the position-code ranking gathers it, the reverse pass
// verifies it against the older columns' thresholds (ReversePass).
// Thread-safety: one scanner per query worker; the index it refers to is shared and immutable.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "engine/lsh/lsh_index.h"
#include "engine/lsh/lsh_options.h"
#include "engine/lsh/probe_sequence.h"

namespace motif {

// Scan state of one probed bucket: entries [begin, end) of its table, the next positions
// outward from the query's sort value (up: ascending, down: descending, exclusive).
struct BucketCursor {
  uint32_t begin = 0;
  uint32_t end = 0;
  uint32_t up = 0;
  uint32_t down = 0;
  uint32_t examined = 0;
  uint32_t scan_limit = 0;  // min(max_bucket_scan, bucket size)
  int16_t query_sort_value = 0;
  bool done = true;
  bool linear = false;  // a small bucket: read in stored order, all of it in the first round

  // The cursor of `probe`'s bucket, positioned at the query's sort value in the probe's table;
  // done at once for an empty bucket. A bucket of at most first_round_scan entries is read
  // linearly (it is read whole in the first round anyway).
  static BucketCursor Open(const LshIndex& index, const BucketProbe& probe,
                           int16_t query_sort_value, const LshOptions& options);

  // One step of the outward scan. kEntry: the entry at *position, whose sort-value gap (in
  // embedding units) is *gap, is within `limit_squared` (probe score + gap^2); kSkipped: a linear
  // cursor's entry beyond it (stored order: only that entry is out of reach); kDone: nothing left
  // within reach (the cursor is done). kEntry and kSkipped count as examined. Ties go up, so
  // equal sort values come lowest frame first.
  enum class Step { kEntry, kSkipped, kDone };
  Step Next(float score, const int16_t* sort_values, float sort_step, float limit_squared,
            uint32_t* position, float* gap) {
    const bool has_up = up < end;
    const bool has_down = !linear && down > begin;
    if (!has_up && !has_down) {
      done = true;
      return Step::kDone;
    }
    const int32_t up_gap = has_up ? std::abs(sort_values[up] - query_sort_value) : INT32_MAX;
    const int32_t down_gap = has_down ? query_sort_value - sort_values[down - 1] : INT32_MAX;
    const bool take_up = up_gap <= down_gap;
    *gap = static_cast<float>(take_up ? up_gap : down_gap) * sort_step;
    if (score + *gap * *gap > limit_squared) {
      if (!linear) {  // scanning outward: both sides only get farther
        done = true;
        return Step::kDone;
      }
      ++up;
      ++examined;
      return Step::kSkipped;
    }
    *position = take_up ? up++ : --down;
    ++examined;
    return Step::kEntry;
  }

  // After a round of the scan: a cursor that read up to its scan limit is done (counted in
  // *capped when that left entries of the bucket unread). True if it has entries left.
  bool EndRound(uint64_t* capped) {
    if (!done && examined == scan_limit) {
      done = true;
      if (scan_limit < end - begin) ++*capped;
    }
    return !done;
  }
};

// What a scan does with the buckets it reads (see BucketScanner::Scan).
template <typename V>
concept BucketVisitor = requires(V visitor, const BucketProbe& probe, size_t cursor_idx,
                                 uint32_t round_limit, BucketCursor* cursor) {
  // The squared reach: a probe whose score exceeds it is not read, nor any later one.
  { visitor.ReachSquared() } -> std::convertible_to<float>;
  // Called once when the cursor_idx-th probe of the scan opens a non-empty bucket.
  visitor.Opened(probe, cursor_idx);
  // Reads one round of a bucket, until cursor->examined reaches round_limit or the cursor is
  // done. True ends the whole scan (a budget is spent).
  { visitor.Round(probe, cursor_idx, round_limit, cursor) } -> std::convertible_to<bool>;
};

class BucketScanner {
 public:
  // Both must outlive the scanner.
  BucketScanner(const LshIndex& index, const LshOptions& options)
      : index_(index), options_(options) {}

  struct Outcome {
    bool stopped = false;         // a round ended the scan
    bool beyond_reach = false;    // a probe beyond the reach ended it
    uint64_t buckets_opened = 0;  // probes looked up
    uint64_t scans_capped = 0;    // buckets left early by max_bucket_scan
  };

  // Reads the buckets of probes[first_probe, ...) (sorted by ProbeBefore) breadth first, in
  // rounds of first_round_scan, 4x, 16x, ... entries per bucket up to max_bucket_scan, in probe
  // order within a round, until no bucket within reach has entries left or a round stops the
  // scan. query_sort_values[t]: the query's sort value in table t (ProbeSequence).
  template <BucketVisitor Visitor>
  Outcome Scan(const std::vector<BucketProbe>& probes, size_t first_probe,
               const int16_t* query_sort_values, Visitor* visitor) {
    Outcome outcome;
    cursors_.clear();
    uint32_t depth = options_.first_round_scan;
    size_t probe_limit = probes.size();
    while (!outcome.stopped) {
      bool more = false;  // some bucket still has entries within reach
      for (size_t probe_idx = first_probe; probe_idx < probe_limit && !outcome.stopped;
           ++probe_idx) {
        const BucketProbe& probe = probes[probe_idx];
        if (probe.score > visitor->ReachSquared()) {
          probe_limit = probe_idx;  // sorted by score: all later probes are beyond reach too
          outcome.beyond_reach = true;
          break;
        }
        BucketCursor& cursor =
            CursorOf(probe, query_sort_values, probe_idx - first_probe, visitor, &outcome);
        if (cursor.done) continue;
        outcome.stopped = visitor->Round(probe, probe_idx - first_probe,
                                         std::min(depth, cursor.scan_limit), &cursor);
        more = cursor.EndRound(&outcome.scans_capped) || more;
      }
      if (!more || depth >= options_.max_bucket_scan) break;
      depth = depth >= options_.max_bucket_scan / 4 ? options_.max_bucket_scan : depth * 4;
    }
    return outcome;
  }

 private:
  // The cursor of the cursor_idx-th probe of the scan, opened when it is the next one.
  template <typename Visitor>
  BucketCursor& CursorOf(const BucketProbe& probe, const int16_t* query_sort_values,
                         size_t cursor_idx, Visitor* visitor, Outcome* outcome) {
    if (cursor_idx == cursors_.size()) {
      ++outcome->buckets_opened;
      cursors_.push_back(
          BucketCursor::Open(index_, probe, query_sort_values[probe.table_idx], options_));
      if (!cursors_.back().done) visitor->Opened(probe, cursor_idx);
    }
    return cursors_[cursor_idx];
  }

  const LshIndex& index_;
  const LshOptions& options_;
  std::vector<BucketCursor> cursors_;
};

}  // namespace motif
