#include "engine/evaluation/truth_score.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace motif {

namespace {

// `shift` frames are added to the instance (clamped at the clip's frame 0).
bool Hits(const MotifsJsonInstance& instance, const TruthOccurrence& occurrence,
          int64_t shift = 0) {
  const auto moved = [shift](uint64_t frame) {
    const int64_t at = static_cast<int64_t>(frame) + shift;
    return static_cast<uint64_t>(std::max<int64_t>(0, at));
  };
  return instance.clip == occurrence.clip &&
         IntervalIoU(moved(instance.start), moved(instance.end), occurrence.start,
                     occurrence.end) >= kTruthHitIoU;
}

double Ratio(uint64_t part, uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

MotifMovementMatch Match(const MotifsJsonMotif& motif, const std::string& movement,
                         const std::vector<const TruthOccurrence*>& occurrences,
                         int64_t shift = 0) {
  MotifMovementMatch match;
  match.motif = motif.id;
  match.movement = movement;
  match.shift = shift;
  match.instances = motif.instances.size();
  match.occurrences = occurrences.size();
  std::vector<bool> occurrence_hit(occurrences.size(), false);
  for (const MotifsJsonInstance& instance : motif.instances) {
    bool hitting = false;
    for (size_t occurrence_idx = 0; occurrence_idx < occurrences.size(); ++occurrence_idx) {
      if (!Hits(instance, *occurrences[occurrence_idx], shift)) continue;
      hitting = true;
      occurrence_hit[occurrence_idx] = true;
    }
    match.instances_hitting += hitting;
  }
  match.occurrences_hit = std::count(occurrence_hit.begin(), occurrence_hit.end(), true);
  match.precision = Ratio(match.instances_hitting, match.instances);
  match.recall = Ratio(match.occurrences_hit, match.occurrences);
  const double sum = match.precision + match.recall;
  match.f1 = sum > 0 ? 2 * match.precision * match.recall / sum : 0.0;
  return match;
}

// a is a better match than b for the same motif (or, with by_motif, for the same movement).
bool Better(const MotifMovementMatch& a, const MotifMovementMatch& b, bool by_motif) {
  if (a.f1 != b.f1) return a.f1 > b.f1;
  if (by_motif) return a.motif < b.motif;
  if (a.occurrences_hit != b.occurrences_hit) return a.occurrences_hit > b.occurrences_hit;
  return a.movement < b.movement;
}

// The phase-free match (truth_score.h): the best common shift for a back-to-back movement.
MotifMovementMatch PhaseFreeMatch(const MotifsJsonMotif& motif, const std::string& movement,
                                  const std::vector<const TruthOccurrence*>& occurrences) {
  MotifMovementMatch best = Match(motif, movement, occurrences);
  if (!IsBackToBack(occurrences)) return best;
  best.back_to_back = true;
  std::vector<uint64_t> lengths;
  for (const TruthOccurrence* occurrence : occurrences) {
    lengths.push_back(occurrence->end - occurrence->start);
  }
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const auto reach = static_cast<int64_t>(lengths[lengths.size() / 2] / 2);
  for (int64_t size = 1; size <= reach; ++size) {  // by growing |shift|: ties keep the smaller
    for (int64_t shift : {-size, size}) {
      MotifMovementMatch match = Match(motif, movement, occurrences, shift);
      match.back_to_back = true;
      if (match.f1 > best.f1) best = match;
    }
  }
  return best;
}

}  // namespace

bool IsBackToBack(const std::vector<const TruthOccurrence*>& occurrences) {
  size_t followed = 0;
  for (const TruthOccurrence* a : occurrences) {
    for (const TruthOccurrence* b : occurrences) {
      if (a == b || a->clip != b->clip) continue;
      const uint64_t gap = a->end > b->start ? a->end - b->start : b->start - a->end;
      if (gap <= kBackToBackGap) {
        ++followed;
        break;
      }
    }
  }
  return followed > 0 && 2 * followed >= occurrences.size();
}

double IntervalIoU(uint64_t a_start, uint64_t a_end, uint64_t b_start, uint64_t b_end) {
  if (a_end <= a_start || b_end <= b_start) return 0;
  const uint64_t low = std::max(a_start, b_start);
  const uint64_t high = std::min(a_end, b_end);
  const uint64_t intersection = high > low ? high - low : 0;
  const uint64_t united = (a_end - a_start) + (b_end - b_start) - intersection;
  return static_cast<double>(intersection) / static_cast<double>(united);
}

TruthScore ScoreAgainstTruth(const MotifsDocument& document,
                             const std::vector<TruthOccurrence>& truth) {
  std::set<std::string> clips;
  for (const MotifsJsonClip& clip : document.clips) clips.insert(clip.name);
  TruthScore score;
  std::map<std::string, std::vector<const TruthOccurrence*>> by_movement;
  for (const TruthOccurrence& occurrence : truth) {
    if (!clips.count(occurrence.clip)) {
      ++score.occurrences_elsewhere;
      continue;
    }
    ++score.occurrences;
    by_movement[occurrence.movement].push_back(&occurrence);
  }
  score.movements = by_movement.size();
  score.motifs = document.motifs.size();

  std::vector<bool> occurrence_hit(truth.size(), false);
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      ++score.instances;
      bool hitting = false;
      for (size_t truth_idx = 0; truth_idx < truth.size(); ++truth_idx) {
        if (!clips.count(truth[truth_idx].clip) || !Hits(instance, truth[truth_idx])) continue;
        hitting = true;
        occurrence_hit[truth_idx] = true;
      }
      score.instances_hitting += hitting;
    }
  }
  score.occurrences_hit = std::count(occurrence_hit.begin(), occurrence_hit.end(), true);
  score.recall = Ratio(score.occurrences_hit, score.occurrences);
  score.precision = Ratio(score.instances_hitting, score.instances);

  std::map<std::string, MotifMovementMatch> best_for_movement;
  for (const MotifsJsonMotif& motif : document.motifs) {
    MotifMovementMatch best;
    best.motif = motif.id;
    best.instances = motif.instances.size();
    for (const auto& [movement, occurrences] : by_movement) {
      const MotifMovementMatch match = Match(motif, movement, occurrences);
      if (best.movement.empty() || Better(match, best, /*by_motif=*/false)) best = match;
      auto [slot, inserted] = best_for_movement.try_emplace(movement, match);
      if (!inserted && Better(match, slot->second, /*by_motif=*/true)) slot->second = match;
    }
    score.per_motif.push_back(best);
  }
  for (const auto& [movement, occurrences] : by_movement) {
    auto found = best_for_movement.find(movement);
    if (found != best_for_movement.end()) {
      score.per_movement.push_back(found->second);
    } else {
      MotifMovementMatch none;
      none.movement = movement;
      none.occurrences = occurrences.size();
      score.per_movement.push_back(none);
    }
  }
  if (!score.per_motif.empty()) {
    score.top1 = score.per_motif.front();
    score.top1_phase_free.motif = score.top1.motif;
    score.top1_phase_free.instances = score.top1.instances;
    for (const auto& [movement, occurrences] : by_movement) {
      const MotifMovementMatch match =
          PhaseFreeMatch(document.motifs.front(), movement, occurrences);
      if (score.top1_phase_free.movement.empty() ||
          Better(match, score.top1_phase_free, /*by_motif=*/false)) {
        score.top1_phase_free = match;
      }
    }
  }
  return score;
}

}  // namespace motif
