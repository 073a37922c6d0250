#include "engine/lsh/reverse_pass.h"

namespace motif {

// The probed buckets out to eps: each older frame within its column's threshold (lower bound
// plus slack) is verified, until the budget is spent.
class ReversePass::ScanRounds {
 public:
  ScanRounds(ReversePass* pass, uint32_t budget)
      : pass_(*pass), limit_(pass->context_.rules.eps + kBoundSlack), budget_(budget) {}

  float ReachSquared() const { return limit_ * limit_; }
  void Opened(const BucketProbe&, size_t) {}

  bool Round(const BucketProbe& probe, size_t, uint32_t round_limit, BucketCursor* cursor) {
    const LshTableEntries& table = pass_.context_.index.table(probe.table_idx);
    const float sort_step = pass_.context_.family.sort_value_step();
    const uint64_t frame_limit = pass_.query_->frame_limit;
    while (cursor->examined < round_limit) {
      uint32_t position = 0;
      float gap = 0;
      const BucketCursor::Step step = cursor->Next(probe.score, table.sort_values.data(), sort_step,
                                                   limit_ * limit_, &position, &gap);
      if (step == BucketCursor::Step::kDone) break;
      if (step == BucketCursor::Step::kSkipped) continue;
      const uint32_t frame = table.frames[position];
      if (frame >= frame_limit) continue;  // a new frame: searched itself
      const float threshold = pass_.ThresholdOf(frame);
      if (threshold < 0) continue;  // its column is not wanted
      const float reach = threshold + kBoundSlack;
      if (probe.score + gap * gap > reach * reach) continue;  // cannot enter that column
      if (pass_.exclusion_.Excluded(pass_.column_, pass_.clip_, frame) ||
          !pass_.visited_.Insert(frame)) {
        continue;
      }
      pass_.distance_.Prefetch(frame);
      pass_.batch_[pass_.batch_size_++] = frame;
      if (pass_.batch_size_ == kVerifyBatch) pass_.evaluations_ += pass_.VerifyBatch();
      if (pass_.evaluations_ + pass_.batch_size_ >= budget_) return true;
    }
    return false;
  }

 private:
  ReversePass& pass_;
  const float limit_;
  const uint32_t budget_;
};

ReversePass::ReversePass(const LshQueryContext& context)
    : context_(context),
      probes_(context.family, context.index),
      scanner_(context.index, context.options),
      exclusion_(context.features, context.rules),
      visited_(context.visited_capacity()),
      distance_(context.features) {}

void ReversePass::Run(uint64_t column, const ReverseQuery& query, uint32_t budget,
                      const std::vector<Neighbour>* seeds, std::vector<Neighbour>* out) {
  probes_.Prepare(context_.features.frame(column), context_.options.probes_per_table);
  visited_.Clear();
  distance_.SetQuery(column);
  column_ = column;
  clip_ = context_.features.ClipOf(column);
  query_ = &query;
  out_ = out;
  batch_size_ = 0;
  evaluations_ = 0;
  if (seeds != nullptr) VerifySeeds(*seeds);
  ScanRounds rounds(this, budget);
  scanner_.Scan(probes_.probes(), 0, probes_.query_sort_values(), &rounds);
  VerifyBatch();
}

// New frames come in runs (clips), and so do the old frames they match: the previous column's
// reverse frames, advanced, are the likeliest ones of this column. Not counted in the budget.
void ReversePass::VerifySeeds(const std::vector<Neighbour>& seeds) {
  for (const Neighbour& seed : seeds) {
    for (uint32_t advance = 0; advance <= context_.options.chain_advance; ++advance) {
      const uint64_t frame = uint64_t{seed.frame} + advance;
      if (frame >= query_->frame_limit) break;
      const uint32_t candidate = static_cast<uint32_t>(frame);
      if (ThresholdOf(candidate) < 0 || exclusion_.Excluded(column_, clip_, candidate)) continue;
      if (!visited_.Insert(candidate)) continue;
      batch_[batch_size_++] = candidate;
      if (batch_size_ == kVerifyBatch) VerifyBatch();
    }
  }
  VerifyBatch();
}

uint32_t ReversePass::VerifyBatch() {
  const float eps = context_.rules.eps;
  float distances[kVerifyBatch];
  distance_.ToBatch(batch_, batch_size_, eps, distances);
  for (uint32_t idx = 0; idx < batch_size_; ++idx) {
    if (distances[idx] <= eps && distances[idx] <= ThresholdOf(batch_[idx])) {
      out_->push_back({batch_[idx], distances[idx]});
    }
  }
  const uint32_t verified = batch_size_;
  batch_size_ = 0;
  return verified;
}

}  // namespace motif
