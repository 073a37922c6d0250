#include "engine/cluster/held_pose.h"

namespace motif {

bool IsHeldPose(const PoseFeatures& features, uint64_t length, float eps) {
  const uint64_t middle = length / 2;
  for (uint64_t frame_idx = 0; frame_idx < length; ++frame_idx) {
    if (PoseDistance(features, middle, frame_idx) > eps) return false;
  }
  return true;
}

}  // namespace motif
