// Whole takes ranked by their movement (engine/signature/take_movement.h) against a query take
// of the archive, as `motifmine search --clip NAME --distance movement` does: the same action in
// another style before another action. No words files are read. Takes shorter than two steps
// of 0.1 s are left out (SearchResult::wordless_clips, the list of takes not compared); ties go
// to the lower clip index.
// Thread-safety: pure functions; the result does not depend on the thread count.
#pragma once

#include <cstdint>

#include "common/status.h"
#include "engine/words/window_search.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// Every other take, one whole-take match each, the `top` nearest kept. InvalidArgument: a query
// clip out of range or too short, top 0, a skeleton whose body parts cannot be found.
Result<SearchResult> WholeTakeMovementSearch(const FrameFileReader& reader, uint32_t query_clip,
                                             uint32_t top, int threads);

}  // namespace motif
