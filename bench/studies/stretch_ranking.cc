#include "bench/studies/stretch_ranking.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace motif::testing {

double SpanIoU(const Span& a, const Span& b) {
  const uint64_t low = std::max(a.start, b.start);
  const uint64_t high = std::min(a.end, b.end);
  if (high <= low) return 0;
  const double intersection = static_cast<double>(high - low);
  return intersection / static_cast<double>(a.length() + b.length() - (high - low));
}

std::vector<Query> BuildQueries(const std::vector<TruthOccurrence>& occurrences) {
  std::vector<Query> queries;
  for (size_t idx = 0; idx < occurrences.size(); ++idx) {
    const Span span{occurrences[idx].start, occurrences[idx].end};
    std::set<std::string> movements;
    for (const TruthOccurrence& other : occurrences) {
      if (SpanIoU(span, Span{other.start, other.end}) >= 0.5) movements.insert(other.movement);
    }
    Query query{idx, occurrences[idx].movement, span, {}};
    for (const TruthOccurrence& other : occurrences) {
      const Span other_span{other.start, other.end};
      if (movements.count(other.movement) > 0 && !other_span.Overlaps(span)) {
        query.targets.push_back(other_span);
      }
    }
    if (!query.targets.empty()) queries.push_back(std::move(query));
  }
  return queries;
}

namespace {

StretchLabel Label(const Span& stretch, const std::vector<Span>& targets) {
  double best = 0;
  for (const Span& target : targets) best = std::max(best, SpanIoU(stretch, target));
  if (best >= 0.5) return StretchLabel::kPositive;
  return best > 0 ? StretchLabel::kPartial : StretchLabel::kNegative;
}

}  // namespace

std::vector<Stretch> BuildStretches(const Query& query, uint64_t clip_frames,
                                    const StretchOptions& options) {
  std::vector<Stretch> stretches;
  const uint32_t steps = std::max(1u, options.scale_steps);
  for (uint32_t step = 0; step < steps; ++step) {
    const double fraction = steps == 1 ? 0.5 : static_cast<double>(step) / (steps - 1);
    const double scale =
        options.min_scale * std::pow(options.max_scale / options.min_scale, fraction);
    const auto length = static_cast<uint64_t>(
        std::max<long>(2, std::lround(static_cast<double>(query.span.length()) * scale)));
    for (uint64_t start = 0; start + length <= clip_frames; start += options.start_stride) {
      const Span span{start, start + length};
      if (span.Overlaps(query.span)) continue;
      stretches.push_back({span, Label(span, query.targets)});
    }
  }
  return stretches;
}

bool HasPositive(const std::vector<Stretch>& stretches) {
  return std::any_of(stretches.begin(), stretches.end(),
                     [](const Stretch& s) { return s.label == StretchLabel::kPositive; });
}

double RocAuc(std::vector<float> positives, std::vector<float> negatives) {
  if (positives.empty() || negatives.empty()) return -1;
  std::sort(positives.begin(), positives.end());
  std::sort(negatives.begin(), negatives.end());
  // For each positive: negatives strictly farther, plus half of those equal.
  double wins = 0;
  size_t below = 0;    // negatives < value
  size_t at_most = 0;  // negatives <= value
  for (float value : positives) {
    while (below < negatives.size() && negatives[below] < value) ++below;
    at_most = std::max(at_most, below);
    while (at_most < negatives.size() && negatives[at_most] <= value) ++at_most;
    wins += static_cast<double>(negatives.size() - at_most) + 0.5 * (at_most - below);
  }
  return wins / (static_cast<double>(positives.size()) * static_cast<double>(negatives.size()));
}

StretchLabel NearestLabel(const std::vector<Stretch>& stretches,
                          const std::vector<float>& distances) {
  size_t best = 0;
  for (size_t idx = 1; idx < distances.size(); ++idx) {
    if (distances[idx] < distances[best]) best = idx;
  }
  return stretches.empty() ? StretchLabel::kNegative : stretches[best].label;
}

bool NearestIsPositive(const std::vector<Stretch>& stretches, const std::vector<float>& distances) {
  return NearestLabel(stretches, distances) == StretchLabel::kPositive;
}

RankingScore ScoreRanking(const std::vector<std::vector<Stretch>>& stretches,
                          const std::vector<std::vector<float>>& distances) {
  RankingScore score;
  std::vector<float> all_positives;
  std::vector<float> all_negatives;
  double auc_sum = 0;
  for (size_t query = 0; query < stretches.size(); ++query) {
    ++score.queries;
    const StretchLabel nearest = NearestLabel(stretches[query], distances[query]);
    score.hits += nearest == StretchLabel::kPositive ? 1 : 0;
    score.partial_misses += nearest == StretchLabel::kPartial ? 1 : 0;
    std::vector<float> positives;
    std::vector<float> negatives;
    for (size_t idx = 0; idx < stretches[query].size(); ++idx) {
      const float d = distances[query][idx];
      if (stretches[query][idx].label == StretchLabel::kPositive) positives.push_back(d);
      if (stretches[query][idx].label == StretchLabel::kNegative) negatives.push_back(d);
    }
    all_positives.insert(all_positives.end(), positives.begin(), positives.end());
    all_negatives.insert(all_negatives.end(), negatives.begin(), negatives.end());
    const double auc = RocAuc(std::move(positives), std::move(negatives));
    if (auc >= 0) {
      auc_sum += auc;
      ++score.auc_queries;
    }
  }
  score.auc_pooled = RocAuc(std::move(all_positives), std::move(all_negatives));
  if (score.auc_queries > 0) score.auc_query_mean = auc_sum / score.auc_queries;
  return score;
}

}  // namespace motif::testing
