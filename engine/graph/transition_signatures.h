// The paper's constraint on a motion graph (Aristidou et al. 2018, "Constrained Motion Graph"):
// a transition is kept only when the motion it leaves and the motion it enters have close
// signatures. For a transition from frame s of one take to frame g of another:
//  * the source window is the 12 words ending at the word centred nearest s (the motion the walk
//    comes from), the target window the 12 words starting at the word centred nearest g (the
//    motion it goes into); each shifted inward at its take's ends to keep 12 words (the whole
//    take when it has fewer);
//  * their distance is the EMD between the two windows' TF-IDF signatures (tf_idf.h);
//  * the threshold is one number for the archive: the median, over every take and every word
//    boundary scored, of the EMD between the 12 words before and the 12 after
//    (signature_change.h). A transition is kept when its distance is at most that: it changes
//    the context no more than a take's own motion typically does from one moment to the next.
// A transition with a side in a take without words cannot be judged and is pruned.
// Thread-safety: a pure function; it runs in its own task_arena and writes each transition's
// distance into its own slot (the result does not depend on the thread count).
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/graph/motion_graph.h"
#include "engine/words/word_model.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

inline constexpr uint32_t kConstraintWindowWords = 12;

struct SignatureConstraint {
  double threshold = 0;
  uint64_t scores = 0;  // change scores the threshold is the median of
};

// Sets signature_distance of every transition (NaN where a side has no words) and returns the
// threshold. InvalidArgument: no take with enough words for a change score. Errors of the EMD
// pass through.
Result<SignatureConstraint> MeasureTransitionSignatures(const FrameFileReader& reader,
                                                        const LoadedWords& words,
                                                        const ClipBounds& clips,
                                                        std::vector<GraphTransition>* transitions,
                                                        int threads);

// Marks the transitions above the threshold (or not measured) TransitionFate::kSignature.
void PruneBySignature(double threshold, std::vector<GraphTransition>* transitions);

}  // namespace motif
