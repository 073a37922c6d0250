// Held poses: instances in which the body does not move. Standing still at the start of a take
// matches standing still later on (and itself, a little later), so the grower finds long paths
// through it; but a person asked what repeats does not name "standing". An instance is a held pose
// when every one of its frames lies within eps of its middle frame (the pose distance D with the
// skeleton's default weights): the matching radius says which poses count as the same, so a held
// pose is one pose for the whole instance. Such instances are never motif instances.
// The cluster stage flags its instances while it reads their samples (instance_samples.h).
// Thread-safety: pure function.
#pragma once

#include <cstdint>

#include "engine/distance/pose_features.h"

namespace motif {

// True if every one of the `length` frames of `features` (an instance's frames, length >= 1)
// lies within eps of the middle one, frame length / 2.
bool IsHeldPose(const PoseFeatures& features, uint64_t length, float eps);

}  // namespace motif
