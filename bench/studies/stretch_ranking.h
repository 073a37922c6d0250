// What the distance study ranks and how it scores a ranking (distance_study.cc;
// docs/design/motion_distance.md, "Definitions").
//
//  * A query is an annotated occurrence (clip frames [start, end)). Its movements are every
//    annotated movement with an occurrence of IoU >= 0.5 with it (its own, and the others of a
//    nested level at the same place: a movement matching at any annotated level counts). Its
//    targets are the occurrences of its movements that share no frame with it. A query without
//    a target is not asked.
//  * Its stretches: every window [s, s + L_k) of the clip with s a multiple of `start_stride`
//    frames and L_k = round(L * scale_k), L the query's length, the scales geometric from
//    min_scale to max_scale (0.5 to 2 in 9 steps: quarter octaves), that shares no frame with the
//    query (a trivial match otherwise).
//  * A stretch is positive if its IoU with some target is >= 0.5 (the hit rule of
//    `motifmine score`), partial if it overlaps a target below that, negative otherwise.
//    A query none of whose stretches is positive cannot be answered and is not asked either
//    (counted).
//  * 1-NN: the nearest stretch (ties: the first in stretch order) is positive.
//  * AUC: the probability that a positive stretch is nearer than a negative one (ties count
//    one half), partial stretches left out: per query, and pooled over the take's queries.
// Thread-safety: pure functions and value types.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/evaluation/motif_truth.h"

namespace motif::testing {

struct Span {
  uint64_t start = 0;  // clip frames, end exclusive
  uint64_t end = 0;
  uint64_t length() const { return end - start; }
  bool Overlaps(const Span& other) const { return start < other.end && other.start < end; }
};

double SpanIoU(const Span& a, const Span& b);

enum class StretchLabel : uint8_t { kNegative, kPartial, kPositive };

struct Query {
  size_t occurrence = 0;  // index into the clip's occurrences
  std::string movement;
  Span span;
  std::vector<Span> targets;
};

struct Stretch {
  Span span;
  StretchLabel label = StretchLabel::kNegative;
};

struct StretchOptions {
  uint32_t start_stride = 4;
  double min_scale = 0.5;
  double max_scale = 2.0;
  uint32_t scale_steps = 9;
};

// The queries of `occurrences` (one clip's), as above.
std::vector<Query> BuildQueries(const std::vector<TruthOccurrence>& occurrences);

// The stretches of `query` in a clip of `clip_frames` frames, labelled.
std::vector<Stretch> BuildStretches(const Query& query, uint64_t clip_frames,
                                    const StretchOptions& options);

bool HasPositive(const std::vector<Stretch>& stretches);

// The area under the ROC curve of "nearer is positive": P(d_pos < d_neg) + P(equal) / 2.
// -1 when either list is empty.
double RocAuc(std::vector<float> positives, std::vector<float> negatives);

// Scores of one distance on one clip.
struct RankingScore {
  uint32_t queries = 0;
  uint32_t hits = 0;            // 1-NN positive
  uint32_t partial_misses = 0;  // 1-NN partial: the movement, at other boundaries or length
  double auc_pooled = -1;
  double auc_query_mean = -1;  // over the queries that have negatives
  uint32_t auc_queries = 0;
};

// `distances[q]` holds query q's distance to each of `stretches[q]`.
RankingScore ScoreRanking(const std::vector<std::vector<Stretch>>& stretches,
                          const std::vector<std::vector<float>>& distances);

// The label of the query's nearest stretch (ties: the first).
StretchLabel NearestLabel(const std::vector<Stretch>& stretches,
                          const std::vector<float>& distances);

// Whether the query's nearest stretch is positive.
bool NearestIsPositive(const std::vector<Stretch>& stretches, const std::vector<float>& distances);

}  // namespace motif::testing
