// Reading frames [start, end) of one clip of an archive back as a Take (world root trajectory,
// full root rotations, the clip's own bone lengths), ready for WriteBvh: what `motifmine export`,
// `export-motif` and the motion graph's walk (engine/graph/walk_take.h) play.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>

#include "common/status.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/take.h"

namespace motif {

// Frames [start, end) of `take` (start < end <= take.frame_count()).
Take SliceTake(const Take& take, size_t start, size_t end);

// Frames [start, end) of `clip` (a clip of `reader`), within the clip. The root trajectory is
// integrated from the clip's first frame, so frames [0, end) are read. InvalidArgument if the
// range is empty or outside the clip; Corruption if a block does not decode.
Result<Take> ReadClipRangeAsTake(const FrameFileReader& reader, const ClipInfo& clip,
                                 uint64_t start, uint64_t end);

}  // namespace motif
