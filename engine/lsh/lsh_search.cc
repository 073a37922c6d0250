#include "engine/lsh/lsh_search.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <queue>

#include "engine/lsh/lsh_tuning.h"
#include "engine/lsh/query_distance.h"
#include "engine/lsh/visited_set.h"

namespace motif {
namespace {

// Lower bounds are computed from float projections of quantised quaternions (|q|^2 = 1 +- 1e-4)
// and int16 sort values; this slack keeps them below the true D.
constexpr float kBoundSlack = 1e-3f;

// One bucket to visit: table, bucket key and lower bound (squared, embedding units).
struct Probe {
  float score = 0;
  uint32_t table_idx = 0;
  uint32_t rank = 0;  // order within its table (0: the query's own bucket)
  uint32_t key = 0;
  // Coordinates whose cell is one below / one above the query's (bit i: hash coordinate i).
  uint32_t minus_mask = 0;
  uint32_t plus_mask = 0;
};

bool ProbeBefore(const Probe& a, const Probe& b) {
  if (a.score != b.score) return a.score < b.score;
  if (a.table_idx != b.table_idx) return a.table_idx < b.table_idx;
  return a.rank < b.rank;
}

struct Nearer {
  bool operator()(const Neighbour& a, const Neighbour& b) const {
    return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
  }
};

// The work of one column, added to a range's statistics only if the range asked for the column.
struct ColumnWork {
  uint64_t evaluations = 0;
  bool capped = false;  // more than k_max frames within eps were seen
  LshQueryStats lsh;
};

// Keeps the k_max nearest of *best (unordered) once it holds k_max or more; returns the radius
// nothing farther can enter: min(eps, the k_max-th distance), or eps while *best is not full.
float KeepNearest(uint32_t k_max, float eps, std::vector<Neighbour>* best) {
  if (best->size() < k_max) return eps;
  std::nth_element(best->begin(), best->begin() + (k_max - 1), best->end(), Nearer());
  best->resize(k_max);
  return std::min(eps, (*best)[k_max - 1].distance);
}

}  // namespace

// Scratch of one worker: reused across the columns of a range.
class LshSearch::Query {
 public:
  explicit Query(const LshSearch& search)
      : search_(search),
        // A column inserts at most its budget, and a chained one its seeds before that.
        visited_(search.options_.chain_columns > 1
                     ? std::max(search.options_.max_candidates,
                                search.rules_.k_max * (search.options_.chain_advance + 1) +
                                    search.options_.chained_max_candidates)
                     : search.options_.max_candidates),
        embedding_(search.family_.embedding_dims()),
        projections_(static_cast<size_t>(search.family_.table_count()) *
                     (search.family_.hashes_per_table() + 1)),
        distance_(search.features_),
        exclusion_floor_(std::max(search.rules_.exclusion_frames, 1u)) {}

  // `previous`: the neighbours of column - 1 in the same chain (seeds), or null. With
  // `reverse_query`, the verified older frames within their thresholds go to *reverse.
  void Run(uint64_t column, const std::vector<Neighbour>* previous, std::vector<Neighbour>* out,
           ColumnWork* work, const ReverseQuery* reverse_query = nullptr,
           std::vector<Neighbour>* reverse = nullptr);
  // A chain sweep: column `column` (*out, found already, sorted by frame) verifies the frames of
  // `from` (the neighbours of column + direction) moved by -direction * (0..chain_advance) that
  // it does not hold yet, and keeps the k_max nearest, sorted by frame.
  void Sweep(uint64_t column, const std::vector<Neighbour>& from, int direction,
             std::vector<Neighbour>* out, ColumnWork* work);
  // The older frames whose columns the new frame `column` may enter (SearchColumnsAndReverse):
  // appended to *out, at most `budget` evaluations.
  // `seeds`: the previous column's reverse frames in the same chain (or null), verified first
  // advanced by 0..chain_advance frames, as a chained forward query verifies its predecessor's
  // neighbours.
  void RunReverse(uint64_t column, const ReverseQuery& reverse_query, uint32_t budget,
                  const std::vector<Neighbour>* seeds, std::vector<Neighbour>* out);
  // Hashes the column and lists its probes (sorted) in probes_.
  void Prepare(uint64_t column);
  // Appends the probes of rank [skip, wanted) of every table, sorted among themselves.
  void AddProbes(uint32_t wanted, uint32_t skip);
  const std::vector<Probe>& probes() const { return probes_; }

 private:
  // Appends the probes of rank [skip, wanted) of one table to probes_.
  void ListProbes(uint32_t table_idx, const float* coordinates, uint32_t wanted, uint32_t skip);

  // Scan state of one probed bucket: entries [begin, end) of its table, the next positions
  // outward from the query's sort value (up: ascending, down: descending, exclusive).
  struct Cursor {
    uint32_t begin = 0;
    uint32_t end = 0;
    uint32_t up = 0;
    uint32_t down = 0;
    uint32_t examined = 0;
    uint32_t scan_limit = 0;
    int16_t query_sort_value = 0;
    bool done = true;
    bool linear = false;  // a small bucket: read in stored order, all of it in the first round

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
  Cursor OpenBucket(const Probe& probe) const;
  // One step of a bucket's outward scan: the side whose next sort value is nearer (ties go up,
  // so equal sort values come lowest frame first). kEntry: the entry at *position, whose
  // sort-value gap is *gap, is within `limit_squared` (probe score + gap^2); kSkipped: a linear
  // cursor's entry beyond it (stored order: only that entry is out of reach); kDone: nothing
  // left within reach. kEntry and kSkipped count as examined.
  enum class Step { kEntry, kSkipped, kDone };
  static Step NextEntry(Cursor* cursor, float score, const int16_t* sort_values, float sort_step,
                        float limit_squared, uint32_t* position, float* gap);

  const LshSearch& search_;
  std::vector<Cursor> cursors_;
  VisitedSet visited_;
  std::vector<float> embedding_;
  std::vector<float> projections_;
  std::vector<Probe> probes_;
  std::vector<Neighbour> best_;  // accepted candidates: the k_max nearest of them are kept
  std::vector<uint32_t> sweep_candidates_;
  std::vector<Neighbour> merged_;  // Sweep's merged column
  QueryDistance distance_;

  // Ranking by position code. Per probed bucket, eight 16-entry tables (one per code nibble) of
  // the estimated squared distance contributed by that nibble's two coordinates, in units of
  // 1/128 cell^2 (small enough to stay in L1 for all of a column's buckets). The estimate, in
  // those units, is the bin of the counting sort: 1/128 cell^2 resolution up to 8 cells^2.
  static constexpr size_t kEstimateTableSize = 8 * 16;
  static constexpr float kEstimateUnitsPerCell2 = 128.0f;
  static constexpr uint32_t kRankBins = 1024;
  void FillEstimateTable(const Probe& probe, size_t cursor_idx);
  struct Gathered {
    uint32_t frame;
    float lower_squared;  // lower bound on D^2 from the probe and the sort value
    uint32_t bin;         // estimate bin
  };
  struct Ranked {
    uint32_t frame;
    float lower_squared;
  };
  std::vector<uint16_t> estimate_tables_;
  std::vector<Gathered> gathered_;
  std::vector<Ranked> ranked_;
  std::vector<uint32_t> bin_starts_;

  // The forward query of one column (Run), in named steps over column_: seeds, probing scans,
  // farther probes. Candidates are verified in small batches whose features are prefetched one
  // batch ahead: a candidate's 96 bytes are a random access into the archive, and overlapping
  // those misses is most of the speed of the verification.
  static constexpr uint32_t kBatch = 16;
  struct ColumnState {
    uint64_t column = 0;
    uint32_t clip = 0;
    float bound = 0;  // nothing farther than this can enter the column
    uint64_t evaluations = 0;
    uint64_t within_eps = 0;
    // Evaluations allowed in all: the probed buckets' budget, after the seeds of a chained column.
    uint64_t max_evaluations = 0;
    bool budget_spent = false;
    bool bound_stopped = false;
    const ReverseQuery* reverse_query = nullptr;
    std::vector<Neighbour>* reverse = nullptr;  // Run's reverse frames, or null
    LshQueryStats stats;
    uint32_t batch[kBatch];    // being gathered
    uint32_t pending[kBatch];  // gathered and prefetched: verified at the next Flush
    uint32_t batch_size = 0;
    uint32_t pending_size = 0;
  };
  void BeginColumn(uint64_t column, const ReverseQuery* reverse_query,
                   std::vector<Neighbour>* reverse);
  // The column itself and its own clip's temporal neighbourhood are never candidates. Called
  // for every entry read: inlined, with the rare near case out of line.
  [[gnu::always_inline]] bool Excluded(uint64_t column, uint32_t clip_of_column,
                                       uint32_t frame) const {
    const uint64_t frame_gap = frame > column ? frame - column : column - frame;
    return frame_gap < exclusion_floor_ && ExcludedNear(column, clip_of_column, frame);
  }
  bool ExcludedNear(uint64_t column, uint32_t clip_of_column, uint32_t frame) const;
  void Prune();
  // Verifies `count` candidates: the accepted ones go to best_, the reverse ones to the reverse.
  void Verify(const uint32_t* candidates, uint32_t count);
  // Verifies the pending batch and makes the gathered one pending.
  void Flush();
  // Verifies everything gathered and brings the radius up to date.
  void VerifyGathered();
  // Adds a candidate to the batch (prefetching it), flushing a full batch.
  void Gather(uint32_t frame);
  bool BudgetReached() const;
  bool VerifySeeds(const std::vector<Neighbour>& previous);
  Cursor& CursorOf(size_t cursor_idx, const Probe& probe, bool with_estimates);
  void ScanBySortValue(size_t first_probe);
  void ScanRound(const Probe& probe, uint32_t round_limit, Cursor* cursor);
  void ScanByCode(size_t first_probe);
  void GatherByCode(size_t first_probe);
  bool GatherRound(const Probe& probe, size_t cursor_idx, uint32_t round_limit, float limit_squared,
                   Cursor* cursor);
  void RankGathered();
  void VerifyRanked();
  void Scan(size_t first_probe);
  void ProbeFartherBuckets();
  // RunReverse's verification of a batch: the frames within eps and within their columns'
  // thresholds go to *out. Empties the batch (*count = 0); returns how many were verified.
  uint32_t VerifyReverse(const uint32_t* frames, uint32_t* count, const ReverseQuery& reverse_query,
                         std::vector<Neighbour>* out);
  // A reverse frame's threshold: its column's own (negative: not wanted), or eps.
  static float ThresholdOf(const ReverseQuery& reverse_query, float eps, uint32_t frame);

  ColumnState column_;
  uint32_t exclusion_floor_ = 1;  // frames nearer the column than this may be excluded
};

// The estimate of an entry with code c in `probe`'s bucket: per coded coordinate i, the squared
// distance (in cells) from the query's position x_i to the centre of the entry's quarter of its
// cell (the probe's cell is the query's, one below or one above along i); coordinates beyond
// the coded ones add the squared distance to the crossed boundary, if any (in the first table).
void LshSearch::Query::FillEstimateTable(const Probe& probe, size_t cursor_idx) {
  const HashFamily& family = search_.family_;
  const uint32_t hashes = family.hashes_per_table();
  const uint32_t coded = std::min(hashes, HashFamily::kCodedHashes);
  const float* coordinates = &projections_[static_cast<size_t>(probe.table_idx) * (hashes + 1)];
  float terms[HashFamily::kCodedHashes][4] = {};
  for (uint32_t idx = 0; idx < coded; ++idx) {
    const float fraction = coordinates[idx] - std::floor(coordinates[idx]);
    const float offset = (probe.minus_mask >> idx & 1u)  ? -1.0f
                         : (probe.plus_mask >> idx & 1u) ? 1.0f
                                                         : 0.0f;
    for (uint32_t quarter = 0; quarter < 4; ++quarter) {
      const float delta = offset + (static_cast<float>(quarter) + 0.5f) * 0.25f - fraction;
      terms[idx][quarter] = delta * delta * kEstimateUnitsPerCell2;
    }
  }
  float base = 0;
  for (uint32_t idx = coded; idx < hashes; ++idx) {
    const float fraction = coordinates[idx] - std::floor(coordinates[idx]);
    if (probe.minus_mask >> idx & 1u) base += fraction * fraction;
    if (probe.plus_mask >> idx & 1u) base += (1.0f - fraction) * (1.0f - fraction);
  }
  base *= kEstimateUnitsPerCell2;
  if (estimate_tables_.size() < (cursor_idx + 1) * kEstimateTableSize) {
    estimate_tables_.resize((cursor_idx + 1) * kEstimateTableSize);
  }
  uint16_t* table = &estimate_tables_[cursor_idx * kEstimateTableSize];
  for (uint32_t nibble = 0; nibble < 8; ++nibble) {
    const float add = nibble == 0 ? base : 0.0f;
    for (uint32_t value = 0; value < 16; ++value) {
      const float sum = terms[2 * nibble][value & 3] + terms[2 * nibble + 1][value >> 2] + add;
      table[16 * nibble + value] = static_cast<uint16_t>(std::min(std::round(sum), 8000.0f));
    }
  }
}

// Multi-probe sequence of one table (Lv et al. 2007, query-directed probing): the 2m boundaries
// of the query's cell sorted by squared distance; perturbation sets are generated in increasing
// score by a heap with the "shift" and "expand" moves, skipping sets that move one coordinate
// both ways.
void LshSearch::Query::ListProbes(uint32_t table_idx, const float* coordinates, uint32_t wanted,
                                  uint32_t skip) {
  const HashFamily& family = search_.family_;
  const uint32_t hashes = family.hashes_per_table();
  const float width = family.bucket_width();
  int32_t cells[HashFamily::kMaxHashesPerTable];
  struct Boundary {
    float squared = 0;  // squared distance in cells
    uint32_t coordinate = 0;
    int32_t step = 0;  // -1 or +1
  };
  Boundary boundaries[2 * HashFamily::kMaxHashesPerTable];
  for (uint32_t idx = 0; idx < hashes; ++idx) {
    const float floor_value = std::floor(coordinates[idx]);
    cells[idx] = static_cast<int32_t>(floor_value);
    const float below = coordinates[idx] - floor_value;
    const float above = 1.0f - below;
    boundaries[2 * idx] = {below * below, idx, -1};
    boundaries[2 * idx + 1] = {above * above, idx, +1};
  }
  const uint32_t boundary_count = 2 * hashes;
  std::sort(boundaries, boundaries + boundary_count, [](const Boundary& a, const Boundary& b) {
    if (a.squared != b.squared) return a.squared < b.squared;
    return a.coordinate < b.coordinate || (a.coordinate == b.coordinate && a.step < b.step);
  });
  if (skip == 0) {
    probes_.push_back({0.0f, table_idx, 0, HashFamily::BucketKey(cells, hashes), 0, 0});
  }
  if (wanted <= 1) return;

  // A set is a bit mask over sorted boundaries (at most 64) and its largest member.
  struct Set {
    float score;
    uint64_t members;
    uint32_t largest;
  };
  auto greater = [](const Set& a, const Set& b) {
    if (a.score != b.score) return a.score > b.score;
    return a.members > b.members;
  };
  std::priority_queue<Set, std::vector<Set>, decltype(greater)> heap(greater);
  heap.push({boundaries[0].squared, 1, 0});
  uint32_t emitted = 1;
  const float width_squared = width * width;
  // Each pop pushes at most two sets; bounding pops bounds the work when most sets are invalid.
  for (uint32_t pops = 0; emitted < wanted && !heap.empty() && pops < 8 * wanted; ++pops) {
    const Set set = heap.top();
    heap.pop();
    if (set.largest + 1 < boundary_count) {
      const uint32_t next = set.largest + 1;
      const float next_squared = boundaries[next].squared;
      // shift: replace the largest member by the next boundary
      heap.push({set.score - boundaries[set.largest].squared + next_squared,
                 (set.members & ~(uint64_t{1} << set.largest)) | (uint64_t{1} << next), next});
      // expand: add the next boundary
      heap.push({set.score + next_squared, set.members | (uint64_t{1} << next), next});
    }
    uint32_t used = 0;
    uint32_t minus_mask = 0;
    uint32_t plus_mask = 0;
    bool valid = true;
    int32_t perturbed[HashFamily::kMaxHashesPerTable];
    std::copy(cells, cells + hashes, perturbed);
    for (uint64_t members = set.members; members != 0; members &= members - 1) {
      const Boundary& boundary = boundaries[std::countr_zero(members)];
      if (used & (1u << boundary.coordinate)) {
        valid = false;
        break;
      }
      used |= 1u << boundary.coordinate;
      perturbed[boundary.coordinate] += boundary.step;
      (boundary.step < 0 ? minus_mask : plus_mask) |= 1u << boundary.coordinate;
    }
    if (!valid) continue;
    if (emitted >= skip) {
      probes_.push_back({set.score * width_squared, table_idx, emitted,
                         HashFamily::BucketKey(perturbed, hashes), minus_mask, plus_mask});
    }
    ++emitted;
  }
}

LshSearch::Query::Step LshSearch::Query::NextEntry(Cursor* cursor, float score,
                                                   const int16_t* sort_values, float sort_step,
                                                   float limit_squared, uint32_t* position,
                                                   float* gap) {
  const bool has_up = cursor->up < cursor->end;
  const bool has_down = !cursor->linear && cursor->down > cursor->begin;
  if (!has_up && !has_down) {
    cursor->done = true;
    return Step::kDone;
  }
  const int32_t up_gap =
      has_up ? std::abs(sort_values[cursor->up] - cursor->query_sort_value) : INT32_MAX;
  const int32_t down_gap =
      has_down ? cursor->query_sort_value - sort_values[cursor->down - 1] : INT32_MAX;
  const bool take_up = up_gap <= down_gap;
  *gap = static_cast<float>(take_up ? up_gap : down_gap) * sort_step;
  if (score + *gap * *gap > limit_squared) {
    if (!cursor->linear) {  // scanning outward: both sides only get farther
      cursor->done = true;
      return Step::kDone;
    }
    ++cursor->up;
    ++cursor->examined;
    return Step::kSkipped;
  }
  *position = take_up ? cursor->up++ : --cursor->down;
  ++cursor->examined;
  return Step::kEntry;
}

LshSearch::Query::Cursor LshSearch::Query::OpenBucket(const Probe& probe) const {
  Cursor cursor;
  const auto [begin, end] = search_.index_.FindBucket(probe.table_idx, probe.key);
  if (begin == end) return cursor;
  const HashFamily& family = search_.family_;
  const uint32_t rows_per_table = family.hashes_per_table() + 1;
  cursor.query_sort_value = family.QuantiseSortValue(
      projections_[static_cast<size_t>(probe.table_idx) * rows_per_table + rows_per_table - 1]);
  const int16_t* sort_values = search_.index_.table(probe.table_idx).sort_values.data();
  cursor.begin = begin;
  cursor.end = end;
  if (end - begin <= search_.options_.first_round_scan) {
    // Read whole in the first round anyway: the order does not matter, skip the search.
    cursor.linear = true;
    cursor.up = begin;
  } else {
    cursor.up = static_cast<uint32_t>(
        std::lower_bound(sort_values + begin, sort_values + end, cursor.query_sort_value) -
        sort_values);
  }
  cursor.down = cursor.up;
  __builtin_prefetch(search_.index_.table(probe.table_idx).frames.data() + cursor.up);
  cursor.scan_limit = std::min<uint32_t>(search_.options_.max_bucket_scan, end - begin);
  cursor.done = false;
  return cursor;
}

void LshSearch::Query::Prepare(uint64_t column) {
  const HashFamily& family = search_.family_;
  family.Embed(search_.features_.frame(column), embedding_.data());
  family.Project(embedding_.data(), projections_.data());
  probes_.clear();
  AddProbes(search_.options_.probes_per_table, 0);
}

void LshSearch::Query::AddProbes(uint32_t wanted, uint32_t skip) {
  const HashFamily& family = search_.family_;
  const uint32_t rows_per_table = family.hashes_per_table() + 1;
  const size_t first = probes_.size();
  for (uint32_t table_idx = 0; table_idx < family.table_count(); ++table_idx) {
    ListProbes(table_idx, &projections_[static_cast<size_t>(table_idx) * rows_per_table], wanted,
               skip);
  }
  std::sort(probes_.begin() + first, probes_.end(), ProbeBefore);
  // The buckets are looked up in this order later: start fetching their directory slots and
  // keys now, so that the lookups' cache misses overlap.
  const LshIndex& index = search_.index_;
  for (size_t idx = first; idx < probes_.size(); ++idx) {
    index.PrefetchDirectory(probes_[idx].table_idx, probes_[idx].key);
  }
  for (size_t idx = first; idx < probes_.size(); ++idx) {
    index.PrefetchKeys(probes_[idx].table_idx, probes_[idx].key);
  }
}

std::vector<LshSearch::ProbeInfo> LshSearch::ProbeSequence(uint64_t column) const {
  Query query(*this);
  query.Prepare(column);
  std::vector<ProbeInfo> sequence;
  for (const Probe& probe : query.probes()) {
    sequence.push_back({probe.table_idx, probe.key, std::sqrt(probe.score)});
  }
  return sequence;
}

void LshSearch::Query::BeginColumn(uint64_t column, const ReverseQuery* reverse_query,
                                   std::vector<Neighbour>* reverse) {
  visited_.Clear();
  best_.clear();
  distance_.SetQuery(column);
  column_ = ColumnState();
  column_.column = column;
  column_.clip = search_.features_.ClipOf(column);
  column_.bound = search_.rules_.eps;
  column_.max_evaluations = search_.options_.max_candidates;
  column_.reverse_query = reverse_query;
  column_.reverse = reverse;
  if (reverse != nullptr) reverse->clear();
}

bool LshSearch::Query::ExcludedNear(uint64_t column, uint32_t clip_of_column,
                                    uint32_t frame) const {
  return search_.rules_.Excluded(column, frame, clip_of_column, search_.features_.ClipOf(frame));
}

// Keeps the k_max nearest accepted so far and sets the radius to the k_max-th distance. Done when
// twice k_max have been accepted (amortised O(1) per candidate, where a heap would pay
// O(log k_max) on every improvement), and when a decision needs the exact radius.
void LshSearch::Query::Prune() {
  column_.bound = KeepNearest(search_.rules_.k_max, search_.rules_.eps, &best_);
}

void LshSearch::Query::Verify(const uint32_t* candidates, uint32_t count) {
  ColumnState& state = column_;
  const float eps = search_.rules_.eps;
  const size_t prune_at = 2 * static_cast<size_t>(search_.rules_.k_max);
  const ReverseQuery* reverse_query = state.reverse_query;
  // For the reverse neighbours every distance up to eps is needed exactly; a distance within the
  // bound is the same either way (the joints are summed in the same order).
  float distances[kBatch];
  distance_.ToBatch(candidates, count, state.reverse != nullptr ? eps : state.bound, distances);
  // Counted in locals (registers) and stored once: best_.push_back may allocate.
  float bound = state.bound;
  uint64_t within_eps = 0;
  for (uint32_t idx = 0; idx < count; ++idx) {
    const float distance = distances[idx];
    if (state.reverse != nullptr && candidates[idx] < reverse_query->frame_limit &&
        distance <= eps &&
        (reverse_query->thresholds == nullptr ||
         distance <= reverse_query->thresholds[candidates[idx]])) {
      state.reverse->push_back({candidates[idx], distance});
    }
    // A value above the bound may be a partial sum: it only says D > bound. capped_columns
    // counts a column when more than k_max candidates came out at or below eps this way.
    if (distance <= eps) ++within_eps;
    if (distance > bound) continue;  // cannot enter the column (bound <= eps)
    best_.push_back({candidates[idx], distance});
    if (best_.size() >= prune_at) {
      Prune();
      bound = state.bound;
    }
  }
  state.evaluations += count;
  state.within_eps += within_eps;
}

void LshSearch::Query::Flush() {
  ColumnState& state = column_;
  Verify(state.pending, state.pending_size);
  std::copy(state.batch, state.batch + state.batch_size, state.pending);
  state.pending_size = state.batch_size;
  state.batch_size = 0;
}

void LshSearch::Query::VerifyGathered() {
  Flush();
  Flush();
  Prune();
}

void LshSearch::Query::Gather(uint32_t frame) {
  distance_.Prefetch(frame);
  column_.batch[column_.batch_size++] = frame;
  if (column_.batch_size == kBatch) Flush();
}

bool LshSearch::Query::BudgetReached() const {
  const ColumnState& state = column_;
  return state.evaluations + state.pending_size + state.batch_size >= state.max_evaluations;
}

// Seeds of a chained column: the predecessor's neighbours advanced by 0..chain_advance frames
// (in frame order: neighbours come in runs, so consecutive seeds share cache lines). Verified
// first, they give the radius of a nearly finished column, which prunes most probes and entries
// by their lower bounds; the probed buckets then get chained_max_candidates, in every
// chain_probe_every-th column of the chain only (the others keep their seeds and get the chain
// sweeps, which pool what the probing columns found: docs/design/lsh.md section 3c). True if
// this column probes.
bool LshSearch::Query::VerifySeeds(const std::vector<Neighbour>& previous) {
  const LshOptions& options = search_.options_;
  ColumnState& state = column_;
  const uint64_t frame_count = search_.features_.frame_count();
  for (const Neighbour& neighbour : previous) {
    for (uint32_t advance = 0; advance <= options.chain_advance; ++advance) {
      const uint64_t frame = uint64_t{neighbour.frame} + advance;
      if (frame >= frame_count) break;
      const uint32_t candidate = static_cast<uint32_t>(frame);
      if (Excluded(state.column, state.clip, candidate) || !visited_.Insert(candidate)) continue;
      Gather(candidate);
    }
  }
  VerifyGathered();
  state.stats.seed_evaluations += state.evaluations;
  state.max_evaluations = state.evaluations + options.chained_max_candidates;
  return (state.column % options.chain_columns) % options.chain_probe_every == 0;
}

// Opens the cursor of probe `probe_idx` (the cursor_idx-th of this scan) when it is the next one.
LshSearch::Query::Cursor& LshSearch::Query::CursorOf(size_t cursor_idx, const Probe& probe,
                                                     bool with_estimates) {
  if (cursor_idx == cursors_.size()) {
    ++column_.stats.probes;
    cursors_.push_back(OpenBucket(probe));
    if (with_estimates && !cursors_.back().done) FillEstimateTable(probe, cursor_idx);
  }
  return cursors_[cursor_idx];
}

// Breadth first: every probed bucket is scanned outward from the query's sort value in rounds of
// growing depth, so the budget goes to the entries nearest the query in all tables before the
// far ends of the first buckets. Probes are in increasing lower bound; a probe whose bound
// exceeds the current radius ends the column's probing (nothing left can enter).
void LshSearch::Query::ScanBySortValue(size_t first_probe) {
  const LshOptions& options = search_.options_;
  ColumnState& state = column_;
  cursors_.clear();
  uint32_t depth = options.first_round_scan;
  size_t probe_limit = probes_.size();
  while (!state.budget_spent) {
    bool more = false;  // some bucket still has entries within the radius
    for (size_t probe_idx = first_probe; probe_idx < probe_limit && !state.budget_spent;
         ++probe_idx) {
      const Probe& probe = probes_[probe_idx];
      if (probe.score > (state.bound + kBoundSlack) * (state.bound + kBoundSlack)) {
        probe_limit = probe_idx;  // sorted by score: all later probes are beyond the radius too
        state.bound_stopped = true;
        break;
      }
      Cursor& cursor = CursorOf(probe_idx - first_probe, probe, false);
      if (cursor.done) continue;
      ScanRound(probe, std::min(depth, cursor.scan_limit), &cursor);
      more = cursor.EndRound(&state.stats.bucket_scans_capped) || more;
    }
    if (!more || depth >= options.max_bucket_scan) break;
    depth = depth >= options.max_bucket_scan / 4 ? options.max_bucket_scan : depth * 4;
  }
}

// One round of a bucket's scan by sort value, up to `round_limit` entries examined: new, allowed
// candidates, nearest sort value first, go into the batch (which continues across buckets, so
// the eight-wide verification stays full) until the budget is spent.
void LshSearch::Query::ScanRound(const Probe& probe, uint32_t round_limit, Cursor* cursor) {
  ColumnState& state = column_;
  const LshTableEntries& table = search_.index_.table(probe.table_idx);
  const int16_t* sort_values = table.sort_values.data();
  const uint32_t* frames = table.frames.data();
  const float sort_step = search_.family_.sort_value_step();
  uint64_t examined = 0;  // counted here, in a register, and added once
  while (!cursor->done && cursor->examined < round_limit) {
    const uint64_t room = state.max_evaluations - state.evaluations - state.pending_size;
    const uint32_t batch_limit = static_cast<uint32_t>(std::min<uint64_t>(kBatch, room));
    while (state.batch_size < batch_limit && cursor->examined < round_limit) {
      const float limit = state.bound + kBoundSlack;
      uint32_t position = 0;
      float gap = 0;
      const Step step =
          NextEntry(cursor, probe.score, sort_values, sort_step, limit * limit, &position, &gap);
      if (step == Step::kDone) break;
      ++examined;
      if (step == Step::kSkipped) continue;
      const uint32_t frame = frames[position];
      if (Excluded(state.column, state.clip, frame)) continue;
      if (!visited_.Insert(frame)) continue;
      distance_.Prefetch(frame);
      state.batch[state.batch_size++] = frame;
    }
    if (state.batch_size == batch_limit) Flush();
    if (BudgetReached()) {
      state.budget_spent = true;
      break;
    }
  }
  state.stats.entries_examined += examined;
}

// Gather, rank, verify. The entries of the probed buckets within reach (the probe's lower bound
// plus the sort-value gap within the radius) are read breadth first, in rounds of growing depth
// outward from the query's sort value, up to max_entries per column. Each gets an estimate of
// its squared distance from the query: its position code (the quarter of the cell it sits in
// along each of the first 16 projections) against the query's exact position, plus the
// sort-value gap. Candidates are then verified in order of that estimate (a counting sort on
// kRankBins bins; within a bin, gathering order), up to max_candidates. Ordering by the code is
// what keeps recall on large archives, where a column's probed buckets hold ten times more
// frames than the budget can verify (docs/design/lsh.md).
void LshSearch::Query::ScanByCode(size_t first_probe) {
  GatherByCode(first_probe);
  RankGathered();
  VerifyRanked();
}

void LshSearch::Query::GatherByCode(size_t first_probe) {
  const LshOptions& options = search_.options_;
  ColumnState& state = column_;
  cursors_.clear();
  gathered_.clear();
  const float limit = state.bound + kBoundSlack;
  const float limit_squared = limit * limit;
  uint32_t depth = options.first_round_scan;
  size_t probe_limit = probes_.size();
  bool entries_spent = false;
  while (!entries_spent) {
    bool more = false;  // some bucket still has entries within reach
    for (size_t probe_idx = first_probe; probe_idx < probe_limit && !entries_spent; ++probe_idx) {
      const Probe& probe = probes_[probe_idx];
      if (probe.score > limit_squared) {
        probe_limit = probe_idx;  // sorted by score: all later probes are beyond the radius too
        state.bound_stopped = true;
        break;
      }
      const size_t cursor_idx = probe_idx - first_probe;
      Cursor& cursor = CursorOf(cursor_idx, probe, true);
      if (cursor.done) continue;
      entries_spent = GatherRound(probe, cursor_idx, std::min(depth, cursor.scan_limit),
                                  limit_squared, &cursor);
      more = cursor.EndRound(&state.stats.bucket_scans_capped) || more;
    }
    if (!more || depth >= options.max_bucket_scan) break;
    depth = depth >= options.max_bucket_scan / 4 ? options.max_bucket_scan : depth * 4;
  }
}

// One round of a bucket's gathering by code, up to `round_limit` entries examined: each allowed
// entry within reach goes to gathered_ with its estimate bin. True when max_entries are gathered.
bool LshSearch::Query::GatherRound(const Probe& probe, size_t cursor_idx, uint32_t round_limit,
                                   float limit_squared, Cursor* cursor) {
  ColumnState& state = column_;
  const LshTableEntries& table = search_.index_.table(probe.table_idx);
  const int16_t* sort_values = table.sort_values.data();
  const uint32_t* frames = table.frames.data();
  const uint32_t* codes = table.codes.data();
  const uint16_t* estimates = &estimate_tables_[cursor_idx * kEstimateTableSize];
  const float sort_step = search_.family_.sort_value_step();
  // An estimate unit is 1 / kEstimateUnitsPerCell2 of a squared cell width.
  const float gap_scale = std::sqrt(kEstimateUnitsPerCell2) / search_.family_.bucket_width();
  uint64_t examined = 0;  // counted here, in a register, and added once
  bool spent = false;
  while (cursor->examined < round_limit) {
    uint32_t position = 0;
    float gap = 0;
    const Step step =
        NextEntry(cursor, probe.score, sort_values, sort_step, limit_squared, &position, &gap);
    if (step == Step::kDone) break;
    ++examined;
    if (step == Step::kSkipped) continue;
    const float lower_squared = probe.score + gap * gap;
    const uint32_t frame = frames[position];
    if (Excluded(state.column, state.clip, frame)) continue;
    const uint32_t code = codes[position];
    uint32_t estimate = 0;
    for (uint32_t nibble = 0; nibble < 8; ++nibble) {
      estimate += estimates[16 * nibble + ((code >> (4 * nibble)) & 15u)];
    }
    const float gap_units = gap * gap_scale;
    estimate += static_cast<uint32_t>(std::min(gap_units * gap_units, 65535.0f));
    const uint32_t bin = std::min(estimate, kRankBins - 1);
    gathered_.push_back({frame, lower_squared, bin});
    if (gathered_.size() >= search_.options_.max_entries) {
      spent = true;
      break;
    }
  }
  state.stats.entries_examined += examined;
  return spent;
}

// Counting sort of the gathered entries by estimate bin (stable: gathering order within a bin,
// so the verification order depends only on the index and the query).
void LshSearch::Query::RankGathered() {
  bin_starts_.assign(kRankBins + 1, 0);
  for (const Gathered& entry : gathered_) ++bin_starts_[entry.bin + 1];
  for (uint32_t bin = 0; bin < kRankBins; ++bin) bin_starts_[bin + 1] += bin_starts_[bin];
  ranked_.resize(gathered_.size());
  for (const Gathered& entry : gathered_) {
    ranked_[bin_starts_[entry.bin]++] = {entry.frame, entry.lower_squared};
  }
}

void LshSearch::Query::VerifyRanked() {
  ColumnState& state = column_;
  for (const Ranked& candidate : ranked_) {
    if (BudgetReached()) {
      state.budget_spent = true;
      break;
    }
    const float radius = state.bound + kBoundSlack;
    if (candidate.lower_squared > radius * radius) continue;  // cannot enter the column
    if (!visited_.Insert(candidate.frame)) continue;          // seen in another table
    Gather(candidate.frame);
  }
}

void LshSearch::Query::Scan(size_t first_probe) {
  if (search_.options_.ranking == LshRanking::kPositionCode) {
    ScanByCode(first_probe);
  } else {
    ScanBySortValue(first_probe);
  }
}

// Sparse columns: when the probes are used up before the budget and the column is not full, or
// its k_max-th neighbour is much farther than the archive's typical one (the cells were sized
// for the typical column), more distant buckets are probed: 4x the probes per table, then 16x,
// each stage visiting only the new ones.
void LshSearch::Query::ProbeFartherBuckets() {
  const LshOptions& options = search_.options_;
  ColumnState& state = column_;
  uint32_t per_table = options.probes_per_table;
  for (uint32_t stage = 0; stage < options.extension_stages; ++stage) {
    if (state.budget_spent || state.bound_stopped) break;
    VerifyGathered();  // everything gathered is verified: the radius is up to date
    if (best_.size() == search_.rules_.k_max && state.bound <= search_.extension_radius_) break;
    const size_t first_new = probes_.size();
    AddProbes(per_table * 4, per_table);
    per_table *= 4;
    ++state.stats.extensions;
    Scan(first_new);
  }
}

void LshSearch::Query::Run(uint64_t column, const std::vector<Neighbour>* previous,
                           std::vector<Neighbour>* out, ColumnWork* work,
                           const ReverseQuery* reverse_query, std::vector<Neighbour>* reverse) {
  BeginColumn(column, reverse_query, reverse);
  const bool probing = previous == nullptr || VerifySeeds(*previous);
  if (probing) {
    Prepare(column);
    Scan(0);
    ProbeFartherBuckets();
  }
  Flush();
  Flush();
  const ColumnState& state = column_;
  LshQueryStats stats = state.stats;
  if (state.budget_spent) ++stats.columns_budget_capped;
  if (state.bound_stopped) ++stats.columns_bound_stopped;
  const uint32_t k_max = search_.rules_.k_max;
  out->assign(best_.begin(), best_.end());
  FinishColumn(k_max, out);
  work->evaluations += state.evaluations;
  work->capped = work->capped || state.within_eps > k_max;
  work->lsh.Add(stats);
}

void LshSearch::Query::Sweep(uint64_t column, const std::vector<Neighbour>& from, int direction,
                             std::vector<Neighbour>* out, ColumnWork* work) {
  const PoseFeatures& features = search_.features_;
  const NeighbourRules& rules = search_.rules_;
  const uint32_t k_max = rules.k_max;
  const float eps = rules.eps;
  const int64_t frame_count = static_cast<int64_t>(features.frame_count());
  const int64_t advance = search_.options_.chain_advance;
  const uint32_t clip_of_column = features.ClipOf(column);
  // The candidates: the union of [j - advance, j] (backward) or [j, j + advance] (forward) over
  // the frames j of `from`, less the frames *out holds. Both lists are sorted by frame, so one
  // merging walk gives them in increasing order, each once, with no set.
  sweep_candidates_.clear();
  size_t held = 0;
  int64_t next = 0;  // frames below this were considered already
  for (const Neighbour& neighbour : from) {
    const int64_t frame = neighbour.frame;
    const int64_t low = std::max(next, direction > 0 ? frame - advance : frame);
    const int64_t high = std::min(frame_count - 1, direction > 0 ? frame : frame + advance);
    for (int64_t candidate = low; candidate <= high; ++candidate) {
      while (held < out->size() && (*out)[held].frame < candidate) ++held;
      if (held < out->size() && (*out)[held].frame == candidate) continue;
      if (Excluded(column, clip_of_column, static_cast<uint32_t>(candidate))) continue;
      sweep_candidates_.push_back(static_cast<uint32_t>(candidate));
    }
    next = std::max(next, high + 1);
  }
  if (sweep_candidates_.empty()) return;
  // Nothing farther than the column's k_max-th neighbour can enter it.
  float bound = eps;
  if (out->size() >= k_max) {
    float farthest = 0;
    for (const Neighbour& neighbour : *out) farthest = std::max(farthest, neighbour.distance);
    bound = std::min(eps, farthest);
  }
  distance_.SetQuery(column);
  float distances[kBatch];
  uint64_t within_eps = 0;
  best_.clear();  // the candidates accepted
  const size_t count = sweep_candidates_.size();
  for (size_t idx = 0; idx < std::min<size_t>(kBatch, count); ++idx) {
    distance_.Prefetch(sweep_candidates_[idx]);
  }
  for (size_t first = 0; first < count; first += kBatch) {
    const uint32_t batch = static_cast<uint32_t>(std::min<size_t>(kBatch, count - first));
    for (size_t idx = first + kBatch; idx < std::min(count, first + 2 * kBatch); ++idx) {
      distance_.Prefetch(sweep_candidates_[idx]);  // the next batch, while this one is verified
    }
    distance_.ToBatch(&sweep_candidates_[first], batch, bound, distances);
    for (uint32_t idx = 0; idx < batch; ++idx) {
      if (distances[idx] <= eps) ++within_eps;
      if (distances[idx] <= bound)
        best_.push_back({sweep_candidates_[first + idx], distances[idx]});
    }
  }
  work->evaluations += count;
  work->lsh.sweep_evaluations += count;
  // The column's own frames and the new ones within eps are distinct frames within eps.
  work->capped = work->capped || out->size() + within_eps > k_max;
  if (best_.empty()) return;
  // best_ came in increasing frame order, like *out: merge them, then drop the farthest beyond
  // k_max. The same column as FinishColumn over both, without its sort.
  merged_.resize(out->size() + best_.size());
  std::merge(out->begin(), out->end(), best_.begin(), best_.end(), merged_.begin(),
             [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
  if (merged_.size() > k_max) {
    best_.assign(merged_.begin(), merged_.end());
    std::nth_element(best_.begin(), best_.begin() + (k_max - 1), best_.end(), Nearer());
    const Neighbour cut = best_[k_max - 1];  // the k_max-th nearest: it and all nearer stay
    merged_.erase(std::remove_if(merged_.begin(), merged_.end(),
                                 [&](const Neighbour& n) { return Nearer()(cut, n); }),
                  merged_.end());
  }
  out->swap(merged_);
}

float LshSearch::Query::ThresholdOf(const ReverseQuery& reverse_query, float eps, uint32_t frame) {
  return reverse_query.thresholds != nullptr ? reverse_query.thresholds[frame] : eps;
}

uint32_t LshSearch::Query::VerifyReverse(const uint32_t* frames, uint32_t* count,
                                         const ReverseQuery& reverse_query,
                                         std::vector<Neighbour>* out) {
  const float eps = search_.rules_.eps;
  float distances[kBatch];
  distance_.ToBatch(frames, *count, eps, distances);
  for (uint32_t idx = 0; idx < *count; ++idx) {
    if (distances[idx] <= eps && distances[idx] <= ThresholdOf(reverse_query, eps, frames[idx])) {
      out->push_back({frames[idx], distances[idx]});
    }
  }
  const uint32_t verified = *count;
  *count = 0;
  return verified;
}

// A new frame n enters an old column t when D(n, t) is below t's own k_max-th distance, which
// may well be farther than n's: so n's probed buckets are scanned breadth first out to eps (not
// to n's shrinking radius, as the forward query does), and each older frame is skipped without
// an evaluation when its lower bound already exceeds its column's threshold. Bucket collisions
// and the sort-value gaps are symmetric in n and t, so this finds what t's own query would find
// of n, within the budget.
void LshSearch::Query::RunReverse(uint64_t column, const ReverseQuery& reverse_query,
                                  uint32_t budget, const std::vector<Neighbour>* seeds,
                                  std::vector<Neighbour>* out) {
  const LshIndex& index = search_.index_;
  const PoseFeatures& features = search_.features_;
  const NeighbourRules& rules = search_.rules_;
  const LshOptions& options = search_.options_;
  const float eps = rules.eps;
  const float limit = eps + kBoundSlack;
  const float sort_step = search_.family_.sort_value_step();
  Prepare(column);
  visited_.Clear();
  distance_.SetQuery(column);
  const uint32_t clip_of_column = features.ClipOf(column);
  uint32_t batch[kBatch];
  uint32_t batch_size = 0;
  uint32_t evaluations = 0;
  // New frames come in runs (clips), and so do the old frames they match: the previous column's
  // reverse frames, advanced, are the likeliest ones of this column. Not counted in the budget.
  if (seeds != nullptr) {
    for (const Neighbour& seed : *seeds) {
      for (uint32_t advance = 0; advance <= options.chain_advance; ++advance) {
        const uint64_t frame = uint64_t{seed.frame} + advance;
        if (frame >= reverse_query.frame_limit) break;
        const uint32_t candidate = static_cast<uint32_t>(frame);
        if (ThresholdOf(reverse_query, eps, candidate) < 0 ||
            Excluded(column, clip_of_column, candidate))
          continue;
        if (!visited_.Insert(candidate)) continue;
        batch[batch_size++] = candidate;
        if (batch_size == kBatch)
          evaluations += VerifyReverse(batch, &batch_size, reverse_query, out);
      }
    }
    VerifyReverse(batch, &batch_size, reverse_query, out);
    evaluations = 0;
  }
  cursors_.clear();
  uint64_t capped = 0;
  uint32_t depth = options.first_round_scan;
  bool budget_spent = false;
  while (!budget_spent) {
    bool more = false;
    for (size_t probe_idx = 0; probe_idx < probes_.size() && !budget_spent; ++probe_idx) {
      const Probe& probe = probes_[probe_idx];
      if (probe.score > limit * limit) break;  // sorted: the later probes are farther
      if (probe_idx == cursors_.size()) cursors_.push_back(OpenBucket(probe));
      Cursor& cursor = cursors_[probe_idx];
      if (cursor.done) continue;
      const LshTableEntries& table = index.table(probe.table_idx);
      const uint32_t round_limit = std::min(depth, cursor.scan_limit);
      while (cursor.examined < round_limit) {
        uint32_t position = 0;
        float gap = 0;
        const Step step = NextEntry(&cursor, probe.score, table.sort_values.data(), sort_step,
                                    limit * limit, &position, &gap);
        if (step == Step::kDone) break;
        if (step == Step::kSkipped) continue;
        const uint32_t frame = table.frames[position];
        if (frame >= reverse_query.frame_limit) continue;  // a new frame: searched itself
        const float threshold = ThresholdOf(reverse_query, eps, frame);
        if (threshold < 0) continue;  // its column is not wanted
        const float reach = threshold + kBoundSlack;
        if (probe.score + gap * gap > reach * reach) continue;  // cannot enter that column
        if (Excluded(column, clip_of_column, frame) || !visited_.Insert(frame)) continue;
        distance_.Prefetch(frame);
        batch[batch_size++] = frame;
        if (batch_size == kBatch)
          evaluations += VerifyReverse(batch, &batch_size, reverse_query, out);
        if (evaluations + batch_size >= budget) {
          budget_spent = true;
          break;
        }
      }
      more = cursor.EndRound(&capped) || more;
    }
    if (!more || depth >= options.max_bucket_scan) break;
    depth = depth >= options.max_bucket_scan / 4 ? options.max_bucket_scan : depth * 4;
  }
  VerifyReverse(batch, &batch_size, reverse_query, out);
}

LshSearch::LshSearch(const PoseFeatures& features, NeighbourRules rules, LshOptions options,
                     HashFamily family, LshIndex index, float extension_radius)
    : features_(features),
      rules_(std::move(rules)),
      options_(std::move(options)),
      family_(std::move(family)),
      index_(std::move(index)),
      extension_radius_(extension_radius) {}

Result<std::unique_ptr<LshSearch>> LshSearch::Create(const PoseFeatures& features,
                                                     NeighbourRules rules,
                                                     const LshOptions& options, RankGroup* ranks) {
  return Make(features, std::move(rules), options, nullptr, ranks);
}

Result<std::unique_ptr<LshSearch>> LshSearch::CreateWithIndex(const PoseFeatures& features,
                                                              NeighbourRules rules,
                                                              const LshOptions& options,
                                                              LshIndex index) {
  if (options.hashes_per_table == 0 || options.bucket_width == 0) {
    return Status::InvalidArgument("lsh search: a given index needs the hash family's sizes");
  }
  if (index.frame_count() != features.frame_count() || index.table_count() != options.tables) {
    return Status::InvalidArgument(
        "lsh search: the given index holds " + std::to_string(index.frame_count()) + " frames in " +
        std::to_string(index.table_count()) + " tables, not " +
        std::to_string(features.frame_count()) + " in " + std::to_string(options.tables));
  }
  return Make(features, std::move(rules), options, &index, nullptr);
}

Result<std::unique_ptr<LshSearch>> LshSearch::Make(const PoseFeatures& features,
                                                   NeighbourRules rules, const LshOptions& options,
                                                   LshIndex* given, RankGroup* ranks) {
  auto invalid = [](const std::string& what) {
    return Status::InvalidArgument("lsh search: " + what);
  };
  if (!(rules.eps > 0)) return invalid("eps must be > 0");
  if (rules.k_max == 0) return invalid("k_max must be > 0");
  // The features' clip layout is the one used (PoseFeatures::ClipOf); the rules may repeat it.
  if (rules.clip_first_frames.empty()) {
    rules.clip_first_frames = features.clip_first_frames();
  } else if (rules.clip_first_frames != features.clip_first_frames()) {
    return invalid("the rules' clip layout differs from the pose features' (" +
                   std::to_string(rules.clip_first_frames.size()) + " vs " +
                   std::to_string(features.clip_first_frames().size()) + " clips)");
  }
  const uint32_t dims = HashFamily::kDimsPerJoint * features.weighted_joint_count();
  if (dims == 0) return invalid("no weighted joint");
  if (options.tables == 0 || options.tables > 64) return invalid("tables must be in 1..64");
  if (options.hashes_per_table > HashFamily::kMaxHashesPerTable ||
      options.hashes_per_table + 1 > dims) {
    return invalid("hashes_per_table must be in 0.." +
                   std::to_string(std::min(HashFamily::kMaxHashesPerTable, dims - 1)));
  }
  if (options.probes_per_table == 0) return invalid("probes_per_table must be > 0");
  if (options.max_candidates == 0) return invalid("max_candidates must be > 0");
  if (options.max_entries == 0) return invalid("max_entries must be > 0");
  if (options.max_bucket_scan == 0) return invalid("max_bucket_scan must be > 0");
  if (options.bucket_width < 0 || !std::isfinite(options.bucket_width)) {
    return invalid("bucket_width must be >= 0");
  }
  if (features.frame_count() >= (uint64_t{1} << 32)) return invalid("2^32 frames or more");
  if (options.bucket_width == 0 && !(options.width_per_hash > 0)) {
    return invalid("width_per_hash must be > 0");
  }
  if (options.first_round_scan == 0) return invalid("first_round_scan must be > 0");
  if (options.shard_frames == 0) return invalid("shard_frames must be > 0");
  if (!(options.sparse_radius_factor > 0)) return invalid("sparse_radius_factor must be > 0");
  if (options.chain_advance > 16) return invalid("chain_advance must be in 0..16");
  if (options.chain_columns > 1 && options.chained_max_candidates == 0) {
    return invalid("chained_max_candidates must be > 0");
  }
  if (options.chain_probe_every == 0) return invalid("chain_probe_every must be > 0");
  MOTIF_ASSIGN_OR_RETURN(const SearchScale scale,
                         EstimateSearchScale(features, rules, options, ranks));
  LshOptions used =
      ResolveLshOptions(options, features.frame_count(), features.weighted_joint_count(), scale);
  HashFamily family = HashFamily::Draw(features.weights(), used.tables, used.hashes_per_table,
                                       used.bucket_width, used.seed);
  LshIndex index;
  if (given != nullptr) {
    index = std::move(*given);
  } else {
    MOTIF_ASSIGN_OR_RETURN(index,
                           LshIndex::Build(features, family, used.shard_frames, used.threads,
                                           used.ranking == LshRanking::kPositionCode, ranks));
  }
  const float extension_radius = options.sparse_radius_factor * scale.radius;
  return std::unique_ptr<LshSearch>(new LshSearch(features, std::move(rules), std::move(used),
                                                  std::move(family), std::move(index),
                                                  extension_radius));
}

Status LshSearch::SearchColumns(uint64_t first_column, uint64_t count,
                                std::vector<std::vector<Neighbour>>* columns,
                                SearchStats* stats) const {
  return SearchColumns(first_column, count, columns, stats, nullptr);
}

Status LshSearch::SearchColumns(uint64_t first_column, uint64_t count,
                                std::vector<std::vector<Neighbour>>* columns, SearchStats* stats,
                                LshQueryStats* lsh_stats) const {
  return Search(first_column, count, nullptr, columns, nullptr, stats, lsh_stats);
}

Status LshSearch::SearchColumnsAndReverse(uint64_t first_column, uint64_t count,
                                          const ReverseQuery& query,
                                          std::vector<std::vector<Neighbour>>* columns,
                                          std::vector<std::vector<Neighbour>>* reverse,
                                          SearchStats* stats) const {
  MOTIF_RETURN_IF_ERROR(CheckReverseQuery(query, features_.frame_count(), "lsh search"));
  if (reverse->size() < count) reverse->resize(count);
  return Search(first_column, count, &query, columns, reverse, stats, nullptr);
}

Status LshSearch::Search(uint64_t first_column, uint64_t count, const ReverseQuery* reverse_query,
                         std::vector<std::vector<Neighbour>>* columns,
                         std::vector<std::vector<Neighbour>>* reverse, SearchStats* stats,
                         LshQueryStats* lsh_stats) const {
  if (first_column + count > features_.frame_count()) {
    return Status::InvalidArgument("lsh search: columns [" + std::to_string(first_column) + ", " +
                                   std::to_string(first_column + count) + ") beyond " +
                                   std::to_string(features_.frame_count()) + " frames");
  }
  if (columns->size() < count) columns->resize(count);
  if (count == 0) return Status::Ok();
  // Integer counters: their sums do not depend on how the columns were split among threads.
  std::atomic<uint64_t> column_total{0}, evaluations{0}, neighbours{0}, capped{0};
  std::atomic<uint64_t> probes{0}, examined{0}, scans_capped{0}, budget_capped{0}, bound_stopped{0},
      extensions{0}, seed_evaluations{0}, sweep_evaluations{0};
  // One task per aligned chain (or per 64 columns without chaining). A chain is computed whole
  // whenever a range asks for one of its columns (only its columns inside the range are returned
  // and counted; without sweeps, it stops at the range's end): a column is the same whichever
  // range asked for it.
  const uint64_t chain = options_.chain_columns > 1 ? options_.chain_columns : 0;
  const uint32_t reverse_chained_budget =
      std::max<uint32_t>(1, options_.chained_max_candidates / options_.chain_probe_every);
  const uint64_t grain = chain ? chain : 64;
  const uint32_t sweeps = chain ? options_.chain_sweeps : 0;
  const uint64_t end_column = first_column + count;
  const uint64_t first_task = first_column / grain;
  const uint64_t task_count = (end_column + grain - 1) / grain - first_task;
  tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, task_count, 1),
        [&](const tbb::blocked_range<uint64_t>& range) {
          Query query(*this);
          SearchStats local;
          LshQueryStats local_lsh;
          std::vector<std::vector<Neighbour>> chain_columns;
          std::vector<ColumnWork> work;
          std::vector<Neighbour> previous_reverse;  // the chain's previous reverse frames
          for (uint64_t task = range.begin(); task != range.end(); ++task) {
            const uint64_t task_first = (first_task + task) * grain;
            const uint64_t begin = chain ? task_first : std::max(task_first, first_column);
            const uint64_t end =
                std::min(task_first + grain, sweeps ? features_.frame_count() : end_column);
            const size_t size = end - begin;
            chain_columns.resize(std::max(chain_columns.size(), size));
            work.assign(size, ColumnWork{});
            for (size_t idx = 0; idx < size; ++idx) {
              const uint64_t column = begin + idx;
              const bool seeded = chain && idx > 0;
              const bool in_range = column >= first_column && column < end_column;
              std::vector<Neighbour>* found =
                  reverse != nullptr && in_range ? &(*reverse)[column - first_column] : nullptr;
              query.Run(column, seeded ? &chain_columns[idx - 1] : nullptr, &chain_columns[idx],
                        &work[idx], reverse_query, found);
              if (found == nullptr) continue;
              // The forward query's verified older frames, and the wider reverse scan's. A
              // column whose predecessor's reverse frames are known spends a chained column's
              // probing budget on average (every column scans in reverse).
              const bool chained = seeded && column > first_column;
              query.RunReverse(column, *reverse_query,
                               chained ? reverse_chained_budget : options_.max_candidates,
                               chained ? &previous_reverse : nullptr, found);
              std::sort(found->begin(), found->end(),
                        [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
              found->erase(std::unique(found->begin(), found->end(),
                                       [](const Neighbour& a, const Neighbour& b) {
                                         return a.frame == b.frame;
                                       }),
                           found->end());
              if (chain) previous_reverse = *found;
            }
            for (uint32_t sweep = 0; sweep < sweeps && size > 1; ++sweep) {
              if (sweep % 2 == 0) {  // backward: from the successor
                for (size_t idx = size - 1; idx-- > 0;) {
                  query.Sweep(begin + idx, chain_columns[idx + 1], +1, &chain_columns[idx],
                              &work[idx]);
                }
              } else {  // forward: from the predecessor
                for (size_t idx = 1; idx < size; ++idx) {
                  query.Sweep(begin + idx, chain_columns[idx - 1], -1, &chain_columns[idx],
                              &work[idx]);
                }
              }
            }
            for (size_t idx = 0; idx < size; ++idx) {
              const uint64_t column = begin + idx;
              if (column < first_column || column >= end_column) continue;
              std::vector<Neighbour>& out = (*columns)[column - first_column];
              out.assign(chain_columns[idx].begin(), chain_columns[idx].end());
              local.columns += 1;
              local.distance_evaluations += work[idx].evaluations;
              local.neighbours += out.size();
              local.capped_columns += work[idx].capped ? 1 : 0;
              local_lsh.Add(work[idx].lsh);
            }
          }
          column_total += local.columns;
          evaluations += local.distance_evaluations;
          neighbours += local.neighbours;
          capped += local.capped_columns;
          probes += local_lsh.probes;
          examined += local_lsh.entries_examined;
          scans_capped += local_lsh.bucket_scans_capped;
          budget_capped += local_lsh.columns_budget_capped;
          bound_stopped += local_lsh.columns_bound_stopped;
          extensions += local_lsh.extensions;
          seed_evaluations += local_lsh.seed_evaluations;
          sweep_evaluations += local_lsh.sweep_evaluations;
        });
  });
  if (stats) {
    stats->columns += column_total;
    stats->distance_evaluations += evaluations;
    stats->neighbours += neighbours;
    stats->capped_columns += capped;
  }
  if (lsh_stats) {
    lsh_stats->probes += probes;
    lsh_stats->entries_examined += examined;
    lsh_stats->bucket_scans_capped += scans_capped;
    lsh_stats->columns_budget_capped += budget_capped;
    lsh_stats->columns_bound_stopped += bound_stopped;
    lsh_stats->extensions += extensions;
    lsh_stats->seed_evaluations += seed_evaluations;
    lsh_stats->sweep_evaluations += sweep_evaluations;
  }
  return Status::Ok();
}

}  // namespace motif
