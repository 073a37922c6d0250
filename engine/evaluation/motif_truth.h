// The occurrences a person (or a synthetic archive's generator) says are there: ground truth
// for scoring mined motifs (truth_score.h, `motifmine score`).
//
// Two files are read:
//  * an annotation TSV (tests/data/repetitions/*.tsv, docs/formats/repetitions_tsv.md): a header
//    line `clip<TAB>movement<TAB>start<TAB>end`, then one occurrence a line; start and end are
//    0-based clip frames, end exclusive; lines starting with '#' and empty lines are skipped;
//  * a synthetic archive's truth.json (engine/synth/truth_json_reader.h): planted motif m becomes
//    the movement "planted-m";
//  * another run's motifs.json: motif k becomes the movement "motif-k" (to compare two runs: does
//    each motif of one have a motif of the other?).
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"

namespace motif {

struct TruthOccurrence {
  std::string clip;
  std::string movement;
  uint64_t start = 0;  // clip frame, 0-based
  uint64_t end = 0;    // exclusive
  bool operator==(const TruthOccurrence&) const = default;
};

// Parses an annotation TSV. InvalidArgument naming `name` and the line for a missing header, a
// line without four fields, a frame that is not a number, or end <= start.
Result<std::vector<TruthOccurrence>> ParseTruthTsv(const std::string& text,
                                                   const std::string& name);

// Reads PATH: when its name ends in ".json", a motifs.json if it has "motifs" and no
// "instances", else a truth.json; an annotation TSV otherwise.
// NotFound / IOError from reading; the parsers' errors.
Result<std::vector<TruthOccurrence>> ReadTruthOccurrences(const std::string& path);

}  // namespace motif
