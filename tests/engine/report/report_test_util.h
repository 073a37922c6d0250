// Shared by the report tests: a small synthetic archive with planted motifs (engine/synth), and
// a motifs document that lists the planted instances as the mined motifs, as if the miner had
// found them exactly.
#pragma once

#include <string>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motifs_json.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif::testing {

struct SyntheticMotifs {
  std::string archive_path;
  MotifsDocument document;  // one motif per planted motif, id = planted id
  std::vector<PlantedInstance> truth;
};

// Writes `archive_path` from `options`; clip 0 is renamed `first_clip_name` when not empty (to
// test escaping).
Result<SyntheticMotifs> MakeSyntheticMotifs(const std::string& archive_path,
                                            const SynthOptions& options,
                                            const std::string& first_clip_name = "");

}  // namespace motif::testing
