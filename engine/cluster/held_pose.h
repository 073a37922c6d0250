// Held poses: instances in which the body does not move. Standing still at the start of a take
// matches standing still later on (and itself, a little later), so the grower finds long paths
// through it; but a person asked what repeats does not name "standing". An instance is a held pose
// when every one of its frames lies within eps of its middle frame (the pose distance D with the
// skeleton's default weights): the matching radius says which poses count as the same, so a held
// pose is one pose for the whole instance. Such instances are never motif instances.
// Thread-safety: pure function; the reader may be shared.
#pragma once

#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_instance.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// One flag per instance (global frame ranges of `archive`). InvalidArgument if an instance lies
// outside the archive; Corruption from reading it.
Result<std::vector<bool>> FindHeldPoses(const FrameFileReader& archive,
                                        const std::vector<MotifInstance>& instances, float eps);

}  // namespace motif
