// Writing a synthesizer's archive, shared by `motifmine synth` and the mining pipeline: the clips
// go to a temporary file beside OUT that is renamed over OUT once committed (OUT is never left
// half written), then OUT.truth.json is written.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "common/status.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif {

// The number of frames written. Errors of the writer, the synthesizer or the rename; the
// temporary file is removed on failure. `progress(frames_done, frames_total)` if given: (0, total)
// first, then after each clip.
Result<uint64_t> WriteSyntheticArchive(
    const std::string& out, MotionSynthesizer& synthesizer, const SynthOptions& options,
    uint32_t block_frames,
    const std::function<void(uint64_t done, uint64_t total)>& progress = nullptr);

}  // namespace motif
