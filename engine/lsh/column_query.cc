#include "engine/lsh/column_query.h"

namespace motif {

// Each bucket's entries within the column's current radius, nearest sort value first, go into
// the verifier's batch (which continues across buckets, so the eight-wide verification stays
// full) until the budget is spent. The radius shrinks as batches are verified.
class ColumnQuery::SortValueRounds {
 public:
  explicit SortValueRounds(ColumnQuery* query) : query_(*query), verifier_(query->verifier_) {}

  float ReachSquared() const {
    const float reach = verifier_.bound() + kBoundSlack;
    return reach * reach;
  }
  void Opened(const BucketProbe&, size_t) {}

  bool Round(const BucketProbe& probe, size_t, uint32_t round_limit, BucketCursor* cursor) {
    const LshTableEntries& table = query_.context_.index.table(probe.table_idx);
    const int16_t* sort_values = table.sort_values.data();
    const uint32_t* frames = table.frames.data();
    const float sort_step = query_.context_.family.sort_value_step();
    uint64_t examined = 0;  // counted here, in a register, and added once
    bool spent = false;
    while (!cursor->done && cursor->examined < round_limit) {
      const uint32_t batch_limit = verifier_.BatchLimit();
      while (verifier_.batch_size() < batch_limit && cursor->examined < round_limit) {
        const float limit = verifier_.bound() + kBoundSlack;
        uint32_t position = 0;
        float gap = 0;
        const BucketCursor::Step step =
            cursor->Next(probe.score, sort_values, sort_step, limit * limit, &position, &gap);
        if (step == BucketCursor::Step::kDone) break;
        ++examined;
        if (step == BucketCursor::Step::kSkipped) continue;
        const uint32_t frame = frames[position];
        if (verifier_.Excluded(frame)) continue;
        if (!verifier_.FirstVisit(frame)) continue;
        verifier_.AddToBatch(frame);
      }
      if (verifier_.batch_size() == batch_limit) verifier_.Flush();
      if (verifier_.BudgetReached()) {
        spent = true;
        break;
      }
    }
    query_.stats_.entries_examined += examined;
    return spent;
  }

 private:
  ColumnQuery& query_;
  CandidateVerifier& verifier_;
};

// Each bucket's entries within reach (fixed for the scan: the radius when it started) go to the
// ranker with their estimates, up to max_entries per column.
class ColumnQuery::CodeGatherRounds {
 public:
  CodeGatherRounds(ColumnQuery* query, float limit_squared)
      : query_(*query), limit_squared_(limit_squared) {}

  float ReachSquared() const { return limit_squared_; }
  void Opened(const BucketProbe& probe, size_t cursor_idx) {
    query_.ranker_.FillEstimateTable(probe, query_.probes_.coordinates(probe.table_idx),
                                     cursor_idx);
  }

  bool Round(const BucketProbe& probe, size_t cursor_idx, uint32_t round_limit,
             BucketCursor* cursor) {
    const LshTableEntries& table = query_.context_.index.table(probe.table_idx);
    const int16_t* sort_values = table.sort_values.data();
    const uint32_t* frames = table.frames.data();
    const uint32_t* codes = table.codes.data();
    const float sort_step = query_.context_.family.sort_value_step();
    const uint32_t max_entries = query_.context_.options.max_entries;
    uint64_t examined = 0;  // counted here, in a register, and added once
    bool spent = false;
    while (cursor->examined < round_limit) {
      uint32_t position = 0;
      float gap = 0;
      const BucketCursor::Step step =
          cursor->Next(probe.score, sort_values, sort_step, limit_squared_, &position, &gap);
      if (step == BucketCursor::Step::kDone) break;
      ++examined;
      if (step == BucketCursor::Step::kSkipped) continue;
      const float lower_squared = probe.score + gap * gap;
      const uint32_t frame = frames[position];
      if (query_.verifier_.Excluded(frame)) continue;
      if (query_.ranker_.Add(frame, lower_squared, cursor_idx, codes[position], gap) >=
          max_entries) {
        spent = true;
        break;
      }
    }
    query_.stats_.entries_examined += examined;
    return spent;
  }

 private:
  ColumnQuery& query_;
  const float limit_squared_;
};

ColumnQuery::ColumnQuery(const LshQueryContext& context)
    : context_(context),
      probes_(context.family, context.index),
      scanner_(context.index, context.options),
      verifier_(context.features, context.rules, context.visited_capacity()),
      ranker_(context.family) {}

void ColumnQuery::Run(uint64_t column, const std::vector<Neighbour>* previous,
                      std::vector<Neighbour>* out, ColumnWork* work,
                      const ReverseQuery* reverse_query, std::vector<Neighbour>* reverse) {
  const LshOptions& options = context_.options;
  verifier_.BeginColumn(column, options.max_candidates, reverse_query, reverse);
  stats_ = LshQueryStats();
  budget_spent_ = false;
  bound_stopped_ = false;
  const bool probing = previous == nullptr || VerifySeeds(*previous);
  if (probing) {
    probes_.Prepare(context_.features.frame(column), options.probes_per_table);
    Scan(0);
    ProbeFartherBuckets();
  }
  verifier_.Drain();
  LshQueryStats stats = stats_;
  if (budget_spent_) ++stats.columns_budget_capped;
  if (bound_stopped_) ++stats.columns_bound_stopped;
  const uint32_t k_max = context_.rules.k_max;
  out->assign(verifier_.accepted().begin(), verifier_.accepted().end());
  FinishColumn(k_max, out);
  work->evaluations += verifier_.evaluations();
  work->capped = work->capped || verifier_.within_eps() > k_max;
  work->lsh.Add(stats);
}

// Seeds of a chained column: the predecessor's neighbours advanced by 0..chain_advance frames
// (in frame order: neighbours come in runs, so consecutive seeds share cache lines). Verified
// first, they give the radius of a nearly finished column, which prunes most probes and entries
// by their lower bounds; the probed buckets then get chained_max_candidates, in every
// chain_probe_every-th column of the chain only (the others keep their seeds and get the chain
// sweeps, which pool what the probing columns found: docs/design/lsh.md section 3c).
bool ColumnQuery::VerifySeeds(const std::vector<Neighbour>& previous) {
  const LshOptions& options = context_.options;
  const uint64_t frame_count = context_.features.frame_count();
  for (const Neighbour& neighbour : previous) {
    for (uint32_t advance = 0; advance <= options.chain_advance; ++advance) {
      const uint64_t frame = uint64_t{neighbour.frame} + advance;
      if (frame >= frame_count) break;
      const uint32_t candidate = static_cast<uint32_t>(frame);
      if (verifier_.Excluded(candidate) || !verifier_.FirstVisit(candidate)) continue;
      verifier_.Gather(candidate);
    }
  }
  verifier_.VerifyGathered();
  stats_.seed_evaluations += verifier_.evaluations();
  verifier_.SetBudget(verifier_.evaluations() + options.chained_max_candidates);
  return (verifier_.column() % options.chain_columns) % options.chain_probe_every == 0;
}

void ColumnQuery::Scan(size_t first_probe) {
  if (context_.options.ranking == LshRanking::kPositionCode) {
    ScanByCode(first_probe);
  } else {
    ScanBySortValue(first_probe);
  }
}

void ColumnQuery::CountScan(const BucketScanner::Outcome& outcome) {
  stats_.probes += outcome.buckets_opened;
  stats_.bucket_scans_capped += outcome.scans_capped;
  if (outcome.beyond_reach) bound_stopped_ = true;
}

// Breadth first, verified as met: the budget goes to the entries nearest the query in all
// tables before the far ends of the first buckets.
void ColumnQuery::ScanBySortValue(size_t first_probe) {
  SortValueRounds rounds(this);
  const BucketScanner::Outcome outcome =
      scanner_.Scan(probes_.probes(), first_probe, probes_.query_sort_values(), &rounds);
  CountScan(outcome);
  if (outcome.stopped) budget_spent_ = true;
}

// Gather, rank, verify: the entries within reach are gathered breadth first, up to max_entries,
// then verified in order of their estimates (PositionCodeRanker), up to the budget. Ordering by
// the code is what keeps recall on large archives, where a column's probed buckets hold ten
// times more frames than the budget can verify (docs/design/lsh.md).
void ColumnQuery::ScanByCode(size_t first_probe) {
  ranker_.Clear();
  const float limit = verifier_.bound() + kBoundSlack;
  CodeGatherRounds rounds(this, limit * limit);
  CountScan(scanner_.Scan(probes_.probes(), first_probe, probes_.query_sort_values(), &rounds));
  VerifyRanked(ranker_.Rank());
}

// A candidate is skipped if its lower bound exceeds the current radius, or if it was verified
// already from another table.
void ColumnQuery::VerifyRanked(const std::vector<PositionCodeRanker::Ranked>& ranked) {
  for (const PositionCodeRanker::Ranked& candidate : ranked) {
    if (verifier_.BudgetReached()) {
      budget_spent_ = true;
      break;
    }
    const float radius = verifier_.bound() + kBoundSlack;
    if (candidate.lower_squared > radius * radius) continue;  // cannot enter the column
    if (!verifier_.FirstVisit(candidate.frame)) continue;     // seen in another table
    verifier_.Gather(candidate.frame);
  }
}

// Sparse columns: when the probes are used up before the budget and the column is not full, or
// its k_max-th neighbour is much farther than the archive's typical one (the cells were sized
// for the typical column), more distant buckets are probed: 4x the probes per table, then 16x,
// each stage visiting only the new ones.
void ColumnQuery::ProbeFartherBuckets() {
  const LshOptions& options = context_.options;
  uint32_t per_table = options.probes_per_table;
  for (uint32_t stage = 0; stage < options.extension_stages; ++stage) {
    if (budget_spent_ || bound_stopped_) break;
    verifier_.VerifyGathered();  // everything gathered is verified: the radius is up to date
    if (verifier_.accepted().size() == context_.rules.k_max &&
        verifier_.bound() <= context_.extension_radius) {
      break;
    }
    const size_t first_new = probes_.probes().size();
    probes_.AddProbes(per_table * 4, per_table);
    per_table *= 4;
    ++stats_.extensions;
    Scan(first_new);
  }
}

}  // namespace motif
