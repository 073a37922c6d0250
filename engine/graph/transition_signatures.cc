#include "engine/graph/transition_signatures.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/earth_movers_distance.h"
#include "engine/words/take_segmentation.h"
#include "engine/words/window_vote.h"

namespace motif {
namespace {

// The word of `clip` whose centre is nearest clip frame `frame` (ties: the earlier).
uint64_t NearestWord(const std::vector<double>& centres, uint64_t frame) {
  const auto at = static_cast<double>(frame);
  const auto after = std::lower_bound(centres.begin(), centres.end(), at);
  if (after == centres.begin()) return 0;
  if (after == centres.end()) return centres.size() - 1;
  const auto before = after - 1;
  return static_cast<uint64_t>((at - *before <= *after - at ? before : after) - centres.begin());
}

// The median change score over every take (signature_change.h, 12 words either side).
Result<SignatureConstraint> Threshold(const LoadedWords& words) {
  EarthMoversDistance emd;
  std::vector<double> all;
  for (uint32_t clip = 0; clip < words.signatures.clip_words.size(); ++clip) {
    MOTIF_ASSIGN_OR_RETURN(const std::vector<double> scores,
                           TakeChangeScores(words, clip, kConstraintWindowWords, emd));
    for (double score : scores) {
      if (std::isfinite(score)) all.push_back(score);
    }
  }
  if (all.empty()) {
    return Status::InvalidArgument("motion graph: no take has the 2 x " +
                                   std::to_string(kConstraintWindowWords / 2) +
                                   " motion words a change score needs; use unconstrained")
        .WithOption("unconstrained");
  }
  std::sort(all.begin(), all.end());
  const size_t mid = all.size() / 2;
  SignatureConstraint constraint;
  constraint.threshold = all.size() % 2 ? all[mid] : (all[mid - 1] + all[mid]) / 2;
  constraint.scores = all.size();
  return constraint;
}

}  // namespace

Result<SignatureConstraint> MeasureTransitionSignatures(const FrameFileReader& reader,
                                                        const LoadedWords& words,
                                                        const ClipBounds& clips,
                                                        std::vector<GraphTransition>* transitions,
                                                        int threads) {
  MOTIF_ASSIGN_OR_RETURN(SignatureConstraint constraint, Threshold(words));
  std::vector<std::vector<double>> centres(reader.clips().size());
  for (uint32_t clip = 0; clip < centres.size(); ++clip) {
    centres[clip] = WordCentres(reader, words, clip);
  }
  std::vector<Status> failures(transitions->size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, transitions->size(), 256),
        [&](const tbb::blocked_range<size_t>& range) {
          EarthMoversDistance emd;
          for (size_t idx = range.begin(); idx != range.end(); ++idx) {
            GraphTransition& edge = (*transitions)[idx];
            const uint32_t from = clips.ClipOf(edge.transition.source);
            const uint32_t to = clips.ClipOf(edge.transition.target);
            if (centres[from].empty() || centres[to].empty()) continue;
            const uint64_t s =
                NearestWord(centres[from], edge.transition.source - clips.starts[from]);
            const uint64_t g = NearestWord(centres[to], edge.transition.target - clips.starts[to]);
            const int64_t window = kConstraintWindowWords;
            const auto before =
                WindowFrom(static_cast<int64_t>(s) - window + 1, centres[from].size(), window);
            const auto after = WindowFrom(static_cast<int64_t>(g), centres[to].size(), window);
            Result<std::vector<double>> a = words.RangeSignature(from, before.first, before.second);
            Result<std::vector<double>> b = words.RangeSignature(to, after.first, after.second);
            Result<double> d = a.ok() && b.ok() ? emd.Distance(*a, *b, words.ground)
                                                : Result<double>(a.ok() ? b.status() : a.status());
            if (!d.ok()) {
              failures[idx] = d.status();
              continue;
            }
            edge.signature_distance = *d;
          }
        });
  });
  for (const Status& failure : failures) MOTIF_RETURN_IF_ERROR(failure);
  return constraint;
}

void PruneBySignature(double threshold, std::vector<GraphTransition>* transitions) {
  for (GraphTransition& edge : *transitions) {
    if (edge.fate != TransitionFate::kKept) continue;
    if (std::isfinite(edge.signature_distance) && edge.signature_distance <= threshold) continue;
    edge.fate = TransitionFate::kSignature;
  }
}

}  // namespace motif
