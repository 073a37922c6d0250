#include "engine/evaluation/truth_score.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace motif {

namespace {

bool Hits(const MotifsJsonInstance& instance, const TruthOccurrence& occurrence) {
  return instance.clip == occurrence.clip &&
         IntervalIoU(instance.start, instance.end, occurrence.start, occurrence.end) >=
             kTruthHitIoU;
}

double Ratio(uint64_t part, uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

MotifMovementMatch Match(const MotifsJsonMotif& motif, const std::string& movement,
                         const std::vector<const TruthOccurrence*>& occurrences) {
  MotifMovementMatch match;
  match.motif = motif.id;
  match.movement = movement;
  match.instances = motif.instances.size();
  match.occurrences = occurrences.size();
  std::vector<bool> occurrence_hit(occurrences.size(), false);
  for (const MotifsJsonInstance& instance : motif.instances) {
    bool hitting = false;
    for (size_t occurrence_idx = 0; occurrence_idx < occurrences.size(); ++occurrence_idx) {
      if (!Hits(instance, *occurrences[occurrence_idx])) continue;
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

}  // namespace

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
  if (!score.per_motif.empty()) score.top1 = score.per_motif.front();
  return score;
}

}  // namespace motif
