// Resampling a take to another frame rate: an archive has one rate, and takes at another rate
// are resampled on import. Rotations are interpolated with slerp (shortest arc), root positions
// linearly. Output frame k sits at time k / target_fps; the output ends at or before the last
// source frame, so no motion is invented past the end.
// Thread-safety: a pure function.
#pragma once

#include "formats/motion/take.h"

namespace motif {

// Returns `take` resampled to `target_fps` (> 0). If the rates agree within 0.1 %, returns the
// take unchanged except for its fps field.
Take ResampleTake(const Take& take, double target_fps);

// True if two frame rates are the same for motifmine's purposes (within 0.1 %): BVH files store
// a rounded frame time (".0083333" is 120.0005 fps).
bool SameFrameRate(double a_fps, double b_fps);

}  // namespace motif
