// Writing a synthesizer's archive, shared by `motifmine synth` and `motifmine mine`: the clips go
// to a temporary file beside OUT that is renamed over OUT once committed (OUT is never left half
// written), then OUT.truth.json is written, with one progress stage "synth".
#pragma once

#include <cstdint>
#include <string>

#include "common/status.h"
#include "engine/cli/progress_reporter.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif::cli {

// The number of frames written. Errors of the writer, the synthesizer or the rename; the
// temporary file is removed on failure.
Result<uint64_t> WriteSyntheticArchive(const std::string& out, MotionSynthesizer& synthesizer,
                                       const SynthOptions& options, uint32_t block_frames,
                                       ProgressReporter* progress);

}  // namespace motif::cli
