#include "engine/cluster/held_pose.h"

#include "engine/cluster/instance_rows.h"
#include "engine/distance/pose_features.h"

namespace motif {

Result<std::vector<bool>> FindHeldPoses(const FrameFileReader& archive,
                                        const std::vector<MotifInstance>& instances, float eps) {
  MOTIF_ASSIGN_OR_RETURN(const std::vector<float> weights,
                         LoadDistanceWeights(archive.skeleton(), ""));
  const uint32_t joint_count = archive.layout().joint_count;
  std::vector<bool> held(instances.size(), false);
  MOTIF_RETURN_IF_ERROR(ForEachInstanceRows(archive, instances, [&](size_t idx, const float* rows) {
    const uint64_t length = instances[idx].length();
    const PoseFeatures features = PoseFeatures::FromRows(rows, length, joint_count, weights, {0});
    const uint64_t middle = length / 2;
    bool within = true;
    for (uint64_t frame_idx = 0; frame_idx < length && within; ++frame_idx) {
      within = PoseDistance(features, middle, frame_idx) <= eps;
    }
    held[idx] = within;
    return Status::Ok();
  }));
  return held;
}

}  // namespace motif
