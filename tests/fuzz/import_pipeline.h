// What the importer does with a parsed take, for the BVH, ASF and AMC fuzz targets: the steps of
// ImportTake after parsing (first-frame check and drop, canonical skeleton) and of the archive
// import after it (resampling to the archive's rate, conversion to rows), so that takes a
// parser accepts are also fuzzed through the code that consumes them.
// Thread-safety: a pure function.
#pragma once

#include "formats/motion/take.h"

namespace motif::fuzz {

// The rate of the archive a fuzzed take is imported into (CMU's, the usual archive rate).
inline constexpr double kArchiveFps = 120.0;

// Runs `take` (as a parser returned it) through the import pipeline and checks what the
// pipeline promises: one rotation per joint and frame, rows of the layout's stride (Fail
// otherwise).
void ImportParsedTake(Take take);

}  // namespace motif::fuzz
