// Scores mined motifs (motifs.json) against ground truth occurrences (motif_truth.h): what
// `motifmine score` prints and scripts/eval_repetitions.sh aggregates (docs/guide.md, score).
//
// The hit rule: a found instance hits a truth occurrence when both are in the same clip and their
// intersection over union (in frames) is at least 0.5. For a motif m and a movement g:
//  * precision(m, g) = instances of m that hit an occurrence of g / instances of m;
//  * recall(m, g)    = occurrences of g hit by an instance of m / occurrences of g;
//  * F1 their harmonic mean (0 when both are 0).
// A motif is matched to the movement with the highest F1 (ties: more occurrences hit, then the
// movement's name); a movement to the motif with the highest F1 (ties: the better-ranked motif).
// The top-1 score is the first motif (the most important) against its movement: precision 0 and
// recall 0 when nothing was found. Occurrences in clips the document does not have are left out
// (and counted), so one truth file can serve archives that hold some of its clips.
//
// Phase-free figures, beside the ones above (never instead of them): a movement done back to back
// (a walk's gait cycles, a dribble's bounces: at least half its occurrences end where another of
// it starts, within kBackToBackGap frames) has no start of its own; where a cycle begins is the
// annotator's convention (a heel strike, the hand's highest point). For such a movement the
// phase-free match shifts all of the motif's instances by one common number of frames, at most
// half the movement's median occurrence length, and keeps the shift with the highest F1 (ties:
// the smallest shift); other movements score as above. A motif that finds every cycle with the
// right length but another phase scores 1 here and possibly 0 above
// (docs/design/motif_quality.md, section 11).
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/motif_truth.h"

namespace motif {

inline constexpr double kTruthHitIoU = 0.5;
inline constexpr uint64_t kBackToBackGap = 2;

// |[a_start, a_end) ∩ [b_start, b_end)| / |union|; 0 for empty intervals.
double IntervalIoU(uint64_t a_start, uint64_t a_end, uint64_t b_start, uint64_t b_end);

struct MotifMovementMatch {
  int64_t motif = -1;      // motif id (rank); -1: none
  std::string movement;    // empty: none
  uint64_t instances = 0;  // of the motif
  uint64_t instances_hitting = 0;
  uint64_t occurrences = 0;  // of the movement
  uint64_t occurrences_hit = 0;
  double precision = 0;
  double recall = 0;
  double f1 = 0;
  bool back_to_back = false;  // the movement is done back to back (phase-free scoring only)
  int64_t shift = 0;          // frames added to every instance (phase-free scoring only)
};

struct TruthScore {
  uint64_t occurrences = 0;            // in the document's clips
  uint64_t occurrences_elsewhere = 0;  // in clips the document does not have (left out)
  uint64_t movements = 0;
  uint64_t motifs = 0;
  // Every motif together: occurrences hit by any instance, instances hitting any occurrence.
  uint64_t instances = 0;
  uint64_t occurrences_hit = 0;
  uint64_t instances_hitting = 0;
  double recall = 0;
  double precision = 0;
  MotifMovementMatch top1;                       // the first motif against its movement
  MotifMovementMatch top1_phase_free;            // the same with phase-free matches
  std::vector<MotifMovementMatch> per_motif;     // by rank, each against its movement
  std::vector<MotifMovementMatch> per_movement;  // by name, each with its best motif
};

// True when at least half of `occurrences` (and at least one) end within kBackToBackGap frames of
// the start of another of them in the same clip.
bool IsBackToBack(const std::vector<const TruthOccurrence*>& occurrences);

TruthScore ScoreAgainstTruth(const MotifsDocument& document,
                             const std::vector<TruthOccurrence>& truth);

}  // namespace motif
