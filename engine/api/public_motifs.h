// The motifs and clips of a motifs.json document (engine/cluster/motifs_json.h) in the public
// types of include/motifmine/mine.h: one copy for motifmine::Mine (public_mine.cc) and
// motifmine::LoadMineResult (public_load.cc), so a loaded result is the mined one.
// Thread-safety: a pure function.
#pragma once

#include "engine/cluster/motifs_json.h"
#include "motifmine/mine.h"

namespace motif {

// Replaces result->motifs (id = rank, each instance with its clip's fps) and result->clips;
// leaves the other fields.
void CopyMotifsDocument(const MotifsDocument& document, motifmine::MineResult* result);

}  // namespace motif
