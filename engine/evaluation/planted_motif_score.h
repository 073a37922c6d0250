// Scoring found motifs against planted ones (synthetic archives, engine/synth/), for tests,
// benchmarks and `motifmine cluster --truth`.
//
// A found instance hits a planted one when both are in the same clip and they overlap by at
// least half of the shorter. Then:
//  * recall    = planted instances hit by some found instance / planted instances;
//  * precision = found instances that hit some planted instance / found instances;
//  * ARI       = the adjusted Rand index (Hubert & Arabie 1985) over the planted instances that
//                are hit, between their planted motif and the found motif of the found instance
//                that overlaps them most (ties: the lowest motif id, then the earliest start).
//                1 for the same grouping, about 0 for a random one, negative for worse.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/adjusted_rand_index.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif {

// A found instance, as in motifs.json.
struct FoundInstance {
  std::string clip;
  uint64_t start = 0;  // within the clip
  uint64_t end = 0;    // exclusive
  uint32_t motif = 0;  // found motif id
};

struct PlantedMotifScore {
  uint64_t planted = 0;
  uint64_t found = 0;
  uint64_t planted_hit = 0;
  uint64_t found_hitting = 0;
  double recall = 0;
  double precision = 0;
  double adjusted_rand_index = 0;
  uint32_t planted_motifs = 0;  // distinct planted motif ids
  uint32_t found_motifs = 0;    // distinct found motif ids
};

// True if a and b (same clip) overlap by at least half of the shorter.
bool InstancesHit(uint64_t a_start, uint64_t a_end, uint64_t b_start, uint64_t b_end);

PlantedMotifScore ScorePlantedMotifs(const std::vector<FoundInstance>& found,
                                     const std::vector<PlantedInstance>& planted);

// The same, for every instance of every motif of a motifs.json document.
PlantedMotifScore ScoreMotifsDocument(const MotifsDocument& document,
                                      const std::vector<PlantedInstance>& planted);

}  // namespace motif
